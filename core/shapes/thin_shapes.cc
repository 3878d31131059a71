#include "core/shapes/thin_shapes.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <numbers>
#include <utility>
#include <vector>

#include "core/geometry/vec.h"

namespace afmesh {
namespace {

constexpr double kHalfPi = std::numbers::pi / 2.0;

// Builds a surface patch by patch: points are merged by exact coordinates (patches compute
// their shared points with the same arithmetic, so these are bit-identical), and each triangle
// is oriented so that its normal points along a wanted direction.
class SurfaceBuilder {
 public:
  Index point(const Point& p) {
    auto [it, inserted] = index_.try_emplace(p, static_cast<Index>(mesh_.points.size()));
    if (inserted) mesh_.points.push_back(p);
    return it->second;
  }

  // Adds triangle (a, b, c), flipped if needed so that (b-a)x(c-a) · wanted > 0.
  void triangle(Index a, Index b, Index c, const Point& wanted, std::int32_t tag) {
    const Point& pa = mesh_.points[a];
    const Point n = cross(sub(mesh_.points[b], pa), sub(mesh_.points[c], pa));
    if (dot(n, wanted) < 0.0) std::swap(b, c);
    mesh_.triangles.push_back({a, b, c});
    mesh_.triangle_tags.push_back(tag);
  }

  const Point& at(Index p) const { return mesh_.points[p]; }

  Mesh take() { return std::move(mesh_); }

 private:
  Mesh mesh_;
  std::map<Point, Index> index_;  // ordered: no dependence on hashing
};

// Splits the quad (a, b, c, d) (in cyclic order) along a-c or b-d.
void add_quad(SurfaceBuilder& builder, Index a, Index b, Index c, Index d, bool along_ac,
              const Point& wanted, std::int32_t tag) {
  if (along_ac) {
    builder.triangle(a, b, c, wanted, tag);
    builder.triangle(a, c, d, wanted, tag);
  } else {
    builder.triangle(a, b, d, wanted, tag);
    builder.triangle(b, c, d, wanted, tag);
  }
}

// ----- quarter dome ---------------------------------------------------------------------------

// The point (u, v) of plane a through the origin (normal along axis a), whose in-plane axes
// are u = axis (a+1) % 3 and v = axis (a+2) % 3.
Point on_plane(int a, double u, double v) {
  Point p{0.0, 0.0, 0.0};
  p[(a + 1) % 3] = u;
  p[(a + 2) % 3] = v;
  return p;
}

// (cos, sin) of the angle (pi/2) j / n, exactly (1, 0) and (0, 1) at the ends.
std::array<double, 2> quarter_turn(int j, int n) {
  if (j == 0) return {1.0, 0.0};
  if (j == n) return {0.0, 1.0};
  const double angle = kHalfPi * j / n;
  return {std::cos(angle), std::sin(angle)};
}

// Point j of n + 1 on the quarter circle of radius r in plane a, from the u axis to the v axis.
Point arc_point(int a, int j, int n, double r) {
  const auto [c, s] = quarter_turn(j, n);
  return on_plane(a, r * c, r * s);
}

// Octant of the sphere of radius r: the spherical triangle between the axes, grid point with
// integer weights (w[0], w[1], w[2]) summing to n, mapped by normalize(sin(pi/2 w_k / n)); on
// the planes (a weight 0) this is the equal-angle arc point of arc_point.
Point sphere_point(const std::array<int, 3>& w, int n, double r) {
  for (int a = 0; a < 3; ++a) {
    if (w[a] == 0) return arc_point(a, w[(a + 2) % 3], n, r);
  }
  Point p{std::sin(kHalfPi * w[0] / n), std::sin(kHalfPi * w[1] / n),
          std::sin(kHalfPi * w[2] / n)};
  return scale(p, r / norm(p));
}

// The sphere octant: n^2 triangles whose normals point along `side` × radial (+1 outward).
void add_sphere_octant(SurfaceBuilder& b, int n, double r, double side, std::int32_t tag) {
  const auto at = [&](int i, int j) { return b.point(sphere_point({n - i - j, i, j}, n, r)); };
  for (int i = 0; i < n; ++i) {
    for (int j = 0; i + j < n; ++j) {
      const std::array<std::array<int, 2>, 3> up = {{{i, j}, {i + 1, j}, {i, j + 1}}};
      std::vector<std::array<std::array<int, 2>, 3>> cells = {up};
      if (i + j + 2 <= n) cells.push_back({{{i + 1, j}, {i + 1, j + 1}, {i, j + 1}}});
      for (const auto& cell : cells) {
        Point centre{0.0, 0.0, 0.0};
        std::array<Index, 3> ids{};
        for (int k = 0; k < 3; ++k) {
          ids[k] = at(cell[k][0], cell[k][1]);
          centre = add(centre, sphere_point({n - cell[k][0] - cell[k][1], cell[k][0], cell[k][1]},
                                            n, r));
        }
        b.triangle(ids[0], ids[1], ids[2], scale(centre, side), tag);
      }
    }
  }
}

// Point j of row k of the sector grid of the quarter disk of radius r in plane a (row k has
// k + 1 points at radius r k / n; row n is the arc).
Point sector_point(int a, int k, int j, int n, double r) {
  if (k == n) return arc_point(a, j, n, r);
  if (k == 0) return {0.0, 0.0, 0.0};
  const double radius = r * k / n;
  const auto [c, s] = quarter_turn(j, k);
  return on_plane(a, radius * c, radius * s);
}

// The quarter disk r <= radius of plane a (n^2 triangles), normal -axis a.
void add_quarter_disk(SurfaceBuilder& b, int a, int n, double r, std::int32_t tag) {
  Point wanted{0.0, 0.0, 0.0};
  wanted[a] = -1.0;
  const auto at = [&](int k, int j) { return b.point(sector_point(a, k, j, n, r)); };
  for (int k = 0; k < n; ++k) {
    for (int j = 0; j <= k; ++j) {
      b.triangle(at(k + 1, j), at(k + 1, j + 1), at(k, j), wanted, tag);
      if (j < k) b.triangle(at(k, j), at(k + 1, j + 1), at(k, j + 1), wanted, tag);
    }
  }
}

// Coordinate p of d equal steps along a box edge of length L.
double edge_coordinate(int p, int d, double length) {
  return p == d ? length : length * p / d;
}

// The outer plane a: the square [0, L]^2 minus the disk r < r_o, a grid from the outer arc
// (n segments, n even) to the square's two far edges (n / 2 segments each) with `layers` rings;
// ring i lies at fraction s_i = (g^i - 1) / (g^layers - 1) of the way (g = growth; i / layers
// for g = 1). Normal -axis a.
void add_outer_plane(SurfaceBuilder& b, int a, int n, double r, double length, int layers,
                     double growth, std::int32_t tag) {
  Point wanted{0.0, 0.0, 0.0};
  wanted[a] = -1.0;
  const int d = n / 2;
  const auto fraction = [&](int i) {
    if (i == layers) return 1.0;
    if (growth == 1.0) return static_cast<double>(i) / layers;
    return (std::pow(growth, i) - 1.0) / (std::pow(growth, layers) - 1.0);
  };
  const auto far_edge = [&](int j) -> std::array<double, 2> {  // on the square's far edges
    if (j <= d) return {length, edge_coordinate(j, d, length)};
    return {edge_coordinate(n - j, d, length), length};
  };
  const auto at = [&](int i, int j) {
    if (i == 0) return b.point(arc_point(a, j, n, r));
    const std::array<double, 2> outer = far_edge(j);
    if (i == layers) return b.point(on_plane(a, outer[0], outer[1]));
    const auto [c, s] = quarter_turn(j, n);
    const std::array<double, 2> inner = {r * c, r * s};
    const double f = fraction(i);
    return b.point(on_plane(a, inner[0] + f * (outer[0] - inner[0]),
                            inner[1] + f * (outer[1] - inner[1])));
  };
  for (int i = 0; i < layers; ++i) {
    for (int j = 0; j < n; ++j) {
      add_quad(b, at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1), (i + j) % 2 == 0,
               wanted, tag);
    }
  }
}

// The box face x_a = L: a uniform grid of d × d squares, normal +axis a.
void add_box_face(SurfaceBuilder& b, int a, int d, double length, std::int32_t tag) {
  Point wanted{0.0, 0.0, 0.0};
  wanted[a] = 1.0;
  const auto at = [&](int p, int q) {
    Point x = on_plane(a, edge_coordinate(p, d, length), edge_coordinate(q, d, length));
    x[a] = length;
    return b.point(x);
  };
  for (int p = 0; p < d; ++p) {
    for (int q = 0; q < d; ++q) {
      add_quad(b, at(p, q), at(p + 1, q), at(p + 1, q + 1), at(p, q + 1), (p + q) % 2 == 0,
               wanted, tag);
    }
  }
}

// ----- sails ----------------------------------------------------------------------------------

// One sail's mid-surface before heeling: leading edge from `tack` to `head`, chord lengths
// `foot_chord` at v = 0 and `head_chord` at v = 1 along `chord` (unit, horizontal), camber
// depth `camber` × chord along `side` (unit, horizontal, perpendicular to `chord`).
struct SailShape {
  Point tack;
  Point head;
  double foot_chord;
  double head_chord;
  Point chord;
  Point side;
  double camber;
  int chord_divisions;
  int height_divisions;
  std::int32_t tag_a;
  std::int32_t tag_b;
};

Point heeled(const Point& p, double heel_rad) {
  const double c = std::cos(heel_rad), s = std::sin(heel_rad);
  return {p[0], c * p[1] - s * p[2], s * p[1] + c * p[2]};
}

Point mid_surface(const SailShape& sail, double u, double v) {
  const double chord = sail.foot_chord + v * (sail.head_chord - sail.foot_chord);
  const Point luff = lerp(sail.tack, sail.head, v);
  return add(add(luff, scale(sail.chord, u * chord)),
             scale(sail.side, sail.camber * chord * 4.0 * u * (1.0 - u)));
}

// Unit normal of the mid-surface, d/du × d/dv by central differences of step 1e-6.
Point mid_normal(const SailShape& sail, double u, double v) {
  constexpr double kStep = 1e-6;
  const Point du = sub(mid_surface(sail, u + kStep, v), mid_surface(sail, u - kStep, v));
  const Point dv = sub(mid_surface(sail, u, v + kStep), mid_surface(sail, u, v - kStep));
  const Point n = cross(du, dv);
  return scale(n, 1.0 / norm(n));
}

double thickness_profile(double u, double v) {
  return (1.0 - std::pow(2.0 * u - 1.0, 8)) * (1.0 - std::pow(2.0 * v - 1.0, 8));
}

// One side of a sail (sign +1: side A at +t/2 N, grid as is, normals -N into the sail; -1: side
// B at -t/2 N, interior grid points moved, other diagonal, normals +N). Rim points (grid
// boundary) are the mid-surface points, shared by both sides.
void add_sail_side(SurfaceBuilder& b, const SailShape& sail, double sign, double thickness,
                   double heel_rad, int grid_scale) {
  const int nu = sail.chord_divisions * grid_scale, nv = sail.height_divisions * grid_scale;
  const auto uv = [&](int i, int j) -> std::array<double, 2> {
    double u = static_cast<double>(i) / nu, v = static_cast<double>(j) / nv;
    const bool rim = i == 0 || i == nu || j == 0 || j == nv;
    if (sign < 0.0 && !rim) {  // side B: an independent grid, rim unchanged
      const double u0 = u, v0 = v;
      u += 0.35 / nu * std::sin(2.0 * std::numbers::pi * v0) * std::sin(std::numbers::pi * u0);
      v += 0.35 / nv * std::sin(3.0 * std::numbers::pi * u0) * std::sin(std::numbers::pi * v0);
    }
    return {u, v};
  };
  const auto at = [&](int i, int j) {
    const auto [u, v] = uv(i, j);
    const bool rim = i == 0 || i == nu || j == 0 || j == nv;
    Point p = mid_surface(sail, u, v);
    if (!rim) {
      p = add(p, scale(mid_normal(sail, u, v), sign * 0.5 * thickness * thickness_profile(u, v)));
    }
    return b.point(heeled(p, heel_rad));
  };
  const std::int32_t tag = sign > 0.0 ? sail.tag_a : sail.tag_b;
  for (int i = 0; i < nu; ++i) {
    for (int j = 0; j < nv; ++j) {
      const Point wanted =
          scale(heeled(mid_normal(sail, (i + 0.5) / nu, (j + 0.5) / nv), heel_rad), -sign);
      add_quad(b, at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1), sign > 0.0, wanted,
               tag);
    }
  }
}

// The grid of the box [lo, hi] with steps of about h: n[k] steps along axis k.
struct BoxGrid {
  Point lo, hi;
  std::array<int, 3> n{};

  BoxGrid(const Point& lo_in, const Point& hi_in, double h) : lo(lo_in), hi(hi_in) {
    for (int k = 0; k < 3; ++k) {
      n[k] = std::max(1, static_cast<int>(std::lround((hi[k] - lo[k]) / h)));
    }
  }

  // Coordinate i of n[k] + 1 along axis k, exactly lo and hi at the ends.
  double coordinate(int k, int i) const {
    if (i == n[k]) return hi[k];
    return lo[k] + (hi[k] - lo[k]) * i / n[k];
  }
};

// The faces of the box grid, normals outward, tag 0; without the bottom z = lo when
// `with_bottom` is false (a ground meshed otherwise, sharing the grid's points on its rim).
void add_box(SurfaceBuilder& b, const BoxGrid& grid, bool with_bottom = true) {
  for (int a = 0; a < 3; ++a) {
    const int u = (a + 1) % 3, v = (a + 2) % 3;
    for (int side = 0; side < 2; ++side) {
      if (a == 2 && side == 0 && !with_bottom) continue;
      Point wanted{0.0, 0.0, 0.0};
      wanted[a] = side == 0 ? -1.0 : 1.0;
      const auto at = [&](int i, int j) {
        Point p{0.0, 0.0, 0.0};
        p[a] = side == 0 ? grid.lo[a] : grid.hi[a];
        p[u] = grid.coordinate(u, i);
        p[v] = grid.coordinate(v, j);
        return b.point(p);
      };
      for (int i = 0; i < grid.n[u]; ++i) {
        for (int j = 0; j < grid.n[v]; ++j) {
          add_quad(b, at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1), (i + j) % 2 == 0,
                   wanted, 0);
        }
      }
    }
  }
}

// ----- hemispherical shell --------------------------------------------------------------------

// A closed ring of points about the z axis in the order of their angles: turn[j] (the angle over
// 2 pi) increasing in [0, 1), id[j] the point. A ring of one point is a pole or a centre.
struct Ring {
  std::vector<double> turn;
  std::vector<Index> id;
};

// m points on the circle of radius r at height z, turned by `phase` steps (one point at the axis
// for m = 1).
Ring circle_ring(SurfaceBuilder& b, double r, double z, int m, double phase) {
  if (m == 1) return {{0.0}, {b.point({0.0, 0.0, z})}};
  Ring ring;
  const double shift = phase - std::floor(phase);
  for (int j = 0; j < m; ++j) {
    const double turn = (j + shift) / m;
    const double angle = 2.0 * std::numbers::pi * turn;
    ring.turn.push_back(turn);
    ring.id.push_back(b.point({r * std::cos(angle), r * std::sin(angle), z}));
  }
  return ring;
}

// Joins rings a and c by triangles in the order of their angles (a fan where one is a single
// point); each triangle's normal points along wanted(its centroid).
template <class Wanted>
void join_rings(SurfaceBuilder& b, const Ring& a, const Ring& c, const Wanted& wanted,
                std::int32_t tag) {
  const auto emit = [&](Index p, Index q, Index r) {
    const Point centre = scale(add(add(b.at(p), b.at(q)), b.at(r)), 1.0 / 3.0);
    b.triangle(p, q, r, wanted(centre), tag);
  };
  const int ma = static_cast<int>(a.id.size()), mc = static_cast<int>(c.id.size());
  if (mc == 1 || ma == 1) {
    const Ring& loop = mc == 1 ? a : c;
    const Index tip = mc == 1 ? c.id[0] : a.id[0];
    for (std::size_t i = 0; i < loop.id.size(); ++i) {
      emit(loop.id[i], loop.id[(i + 1) % loop.id.size()], tip);
    }
    return;
  }
  // Angles unwrapped: a's from its first point on, c's from the point nearest it.
  const auto turn_a = [&](int i) { return a.turn[i % ma] + i / ma; };
  const auto turn_c = [&](int j) { return c.turn[j % mc] + j / mc - 1.0; };
  int start = 0;
  for (int j = 1; j < 2 * mc; ++j) {
    if (std::abs(turn_c(j) - a.turn[0]) < std::abs(turn_c(start) - a.turn[0])) start = j;
  }
  int i = 0, j = start;
  while (i < ma || j < start + mc) {
    if (j == start + mc || (i < ma && turn_a(i + 1) <= turn_c(j + 1))) {
      emit(a.id[i % ma], a.id[(i + 1) % ma], c.id[j % mc]);
      ++i;
    } else {
      emit(a.id[i % ma], c.id[j % mc], c.id[(j + 1) % mc]);
      ++j;
    }
  }
}

// The hemisphere of radius r over the ground z = 0 in n rings (HemisphericalShellParams), normals
// along `side` × radial; returns its equator.
Ring add_hemisphere(SurfaceBuilder& b, double r, int n, double phase, double side,
                    std::int32_t tag) {
  std::vector<Ring> rings;
  for (int k = 0; k <= n; ++k) {
    if (k == n) {
      rings.push_back(circle_ring(b, 0.0, r, 1, 0.0));
      break;
    }
    const double elevation = kHalfPi * k / n;
    const double c = k == 0 ? 1.0 : std::cos(elevation), s = k == 0 ? 0.0 : std::sin(elevation);
    const int m = std::max(3, static_cast<int>(std::lround(4.0 * n * c)));
    rings.push_back(circle_ring(b, r * c, r * s, m, phase + 0.5 * k));
  }
  const auto radial = [side](const Point& centre) { return scale(centre, side); };
  for (int k = 0; k < n; ++k) join_rings(b, rings[k], rings[k + 1], radial, tag);
  return rings.front();
}

// The ground disk inside `equator` (radius r, drawn by a hemisphere of n rings): rings of the
// same step down to the centre, normals -z.
void add_ground_disk(SurfaceBuilder& b, const Ring& equator, double r, int n, double phase,
                     std::int32_t tag) {
  const int rings = std::max(1, static_cast<int>(std::lround(2.0 * n / std::numbers::pi)));
  const auto down = [](const Point&) { return Point{0.0, 0.0, -1.0}; };
  Ring outer = equator;
  for (int k = rings - 1; k >= 0; --k) {
    const int m = k == 0 ? 1 : std::max(3, static_cast<int>(std::lround(4.0 * n * k / rings)));
    Ring inner = circle_ring(b, r * k / rings, 0.0, m, phase + 0.5 * (rings - k));
    join_rings(b, outer, inner, down, tag);
    outer = std::move(inner);
  }
}

// The ground z = 0 between `equator` (radius r) and the bottom edges of the box grid: `layers`
// rings, ring i at fraction (g^i - 1) / (g^layers - 1) of the way from the circle to the square
// along each direction (i / layers for g = 1), its point count likewise between the two; normals
// -z.
void add_ground_outside(SurfaceBuilder& b, const Ring& equator, double r, const BoxGrid& grid,
                        int layers, double growth, double phase, std::int32_t tag) {
  Ring square;
  {
    std::vector<std::pair<double, Index>> rim;
    const auto add_point = [&](double x, double y) {
      double turn = std::atan2(y, x) / (2.0 * std::numbers::pi);
      if (turn < 0.0) turn += 1.0;
      rim.emplace_back(turn, b.point({x, y, grid.lo[2]}));
    };
    for (int i = 0; i < grid.n[0]; ++i) {  // each edge without its last corner
      add_point(grid.coordinate(0, i), grid.lo[1]);
      add_point(grid.coordinate(0, grid.n[0] - i), grid.hi[1]);
    }
    for (int j = 0; j < grid.n[1]; ++j) {
      add_point(grid.hi[0], grid.coordinate(1, j));
      add_point(grid.lo[0], grid.coordinate(1, grid.n[1] - j));
    }
    std::sort(rim.begin(), rim.end());
    for (const auto& [turn, id] : rim) {
      square.turn.push_back(turn);
      square.id.push_back(id);
    }
  }
  const auto fraction = [&](int i) {
    if (growth == 1.0) return static_cast<double>(i) / layers;
    return (std::pow(growth, i) - 1.0) / (std::pow(growth, layers) - 1.0);
  };
  const auto down = [](const Point&) { return Point{0.0, 0.0, -1.0}; };
  const double half = 0.5 * (grid.hi[0] - grid.lo[0]);
  Ring inner = equator;
  for (int i = 1; i <= layers; ++i) {
    Ring outer;
    if (i == layers) {
      outer = square;
    } else {
      const double f = fraction(i);
      const double from = static_cast<double>(equator.id.size());
      const double count = from + f * (static_cast<double>(square.id.size()) - from);
      const int m = std::max(3, static_cast<int>(std::lround(count)));
      const double shift = phase + 0.5 * i - std::floor(phase + 0.5 * i);
      for (int j = 0; j < m; ++j) {
        const double turn = (j + shift) / m;
        const double angle = 2.0 * std::numbers::pi * turn;
        const double c = std::cos(angle), s = std::sin(angle);
        const double to_square = half / std::max(std::abs(c), std::abs(s));
        const double radius = r + f * (to_square - r);
        outer.turn.push_back(turn);
        outer.id.push_back(b.point({radius * c, radius * s, grid.lo[2]}));
      }
    }
    join_rings(b, inner, outer, down, tag);
    inner = std::move(outer);
  }
}

// ----- crossing plates ------------------------------------------------------------------------

// Thickness of a plate at in-plane coordinate w and height z, both in [-1, 1]: full in the
// middle, 0 on the rim |w| = 1 or |z| = 1, where the plate's two sides meet.
double plate_thickness(double thickness, double w, double z) {
  return thickness * (1.0 - std::pow(w, 8)) * (1.0 - std::pow(z, 8));
}

// The plate's mid-surface offset from its plane at |w|, z: a bulge of depth `camber` towards
// the plate's normal (+y for plate A, +x for plate B), 0 on the rim and, to second order, on
// the crossing line, so that the corner stays where the flat plates meet.
double plate_camber(double camber, double w, double z) {
  const double s = std::sin(std::numbers::pi * w);
  return camber * s * s * (1.0 - z * z);
}

// The quadrants (sign of x, sign of y) in the order of their tags 1..4.
constexpr std::array<std::array<double, 2>, 4> kQuadrantSigns = {
    {{1.0, 1.0}, {-1.0, 1.0}, {-1.0, -1.0}, {1.0, -1.0}}};

// Plate B's direction from the crossing towards the quadrants sy = +1 and its normal towards
// the quadrants sx = +1: (0, 1, 0) and (1, 0, 0) at 90°, exactly; else turned about the z axis
// so that the plates make `angle_deg`.
struct PlateB {
  Point along;
  Point normal;
};

PlateB plate_b(double angle_deg) {
  if (angle_deg == 90.0) return {{0.0, 1.0, 0.0}, {1.0, 0.0, 0.0}};
  const double a = angle_deg * std::numbers::pi / 180.0;
  return {{std::cos(a), std::sin(a), 0.0}, {std::sin(a), -std::cos(a), 0.0}};
}

// Thickness of a plate at (w, z): tapering to 0 on the rim (plate_thickness), or the same
// everywhere when the rims are closed by strips.
double thickness_at(const CrossingPlatesParams& params, double w, double z) {
  return params.rim_strips ? params.thickness : plate_thickness(params.thickness, w, z);
}

// Point (i, j) of the side of quadrant (sx, sy): one grid over (i, j) in [0, 2n] × [0, 2n],
// z = -1 + j / n. Columns i > n are plate A's face y = m_A + sy t_A / 2 from the corner to the
// rim x = sx; columns i < n plate B's face (m_B + sx t_B / 2 along its normal) from the corner to
// the rim at sy along it (m the camber, t the thickness); column i = n is the corner line where
// the two faces meet, (sx t_c / 2, sy t_c / 2, z) at 90°, t_c the thickness on the crossing
// line. Tapered plates: t_c is 0 at z = ±1 (the apexes, shared by all four quadrants) and rim
// points (i = 0, i = 2n, j = 0, j = 2n) lie on the mid-planes, shared with the neighbouring
// quadrant across the plate; with rim strips every point is t / 2 off the mid-surface.
// Quadrants 2 and 4 (sx sy < 0) move their interior points by a fraction of a cell, so the two
// sides of every half plate are triangulated independently.
Point quadrant_point(const CrossingPlatesParams& params, double sx, double sy, int i, int j) {
  const int n = params.divisions;
  const bool moved = sx * sy < 0.0;
  const double z = j == 2 * n ? 1.0 : -1.0 + static_cast<double>(j) / n;
  const double corner = 0.5 * thickness_at(params, 0.0, z);
  const PlateB b = plate_b(params.angle_deg);
  if (i == n) {  // on A's face y = sy corner and on B's face at sx corner along its normal
    return {(sx * corner - sy * corner * b.normal[1]) / b.normal[0], sy * corner, z};
  }
  const bool on_a = i > n;
  const int k = on_a ? i - n : n - i;  // columns from the corner, 1..n
  const bool rim = k == n || j == 0 || j == 2 * n;
  double s = static_cast<double>(k) / n, v = static_cast<double>(j) / (2 * n);
  if (moved && !rim) {
    const double s0 = s, v0 = v;
    s += 0.35 / n * std::sin(2.0 * std::numbers::pi * v0) * std::sin(std::numbers::pi * s0);
    v += 0.35 / (2 * n) * std::sin(3.0 * std::numbers::pi * s0) *
         std::sin(std::numbers::pi * v0);
  }
  const double height = rim ? z : -1.0 + 2.0 * v;
  const double w = k == n ? 1.0 : corner + s * (1.0 - corner);
  const double off = rim && !params.rim_strips
                         ? 0.0
                         : plate_camber(params.camber, w, height) +
                               (on_a ? sy : sx) * 0.5 * thickness_at(params, w, height);
  if (on_a) return {sx * w, off, height};
  if (params.angle_deg == 90.0) return {off, sy * w, height};
  return add(add(scale(b.normal, off), scale(b.along, sy * w)), Point{0.0, 0.0, height});
}

// The side of quadrant (sx, sy) (quadrant_point), its quads cut along the other diagonal in the
// moved quadrants. Normals point into the plates.
void add_quadrant_side(SurfaceBuilder& b, const CrossingPlatesParams& params, double sx,
                       double sy, std::int32_t tag) {
  const int n = params.divisions;
  const bool moved = sx * sy < 0.0;
  const auto at = [&](int i, int j) { return b.point(quadrant_point(params, sx, sy, i, j)); };
  const Point into_a{0.0, -sy, 0.0};
  const Point into_b = params.angle_deg == 90.0 ? Point{-sx, 0.0, 0.0}
                                                : scale(plate_b(params.angle_deg).normal, -sx);
  for (int i = 0; i < 2 * n; ++i) {
    for (int j = 0; j < 2 * n; ++j) {
      add_quad(b, at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1), !moved,
               i >= n ? into_a : into_b, tag);
    }
  }
}

// The rims of plates of constant thickness (CrossingPlatesParams::rim_strips), tag 0: each half
// plate's end and its edges at z = ±1 closed by strips between the sides of the two quadrants
// it parts, and at z = ±1 the small cap between the four ends of the corner lines. Normals point
// into the plates.
void add_rim_strips(SurfaceBuilder& b, const CrossingPlatesParams& params) {
  const int n = params.divisions;
  const auto at = [&](int q, int i, int j) {
    return b.point(quadrant_point(params, kQuadrantSigns[q][0], kQuadrantSigns[q][1], i, j));
  };
  struct HalfPlate {
    int p, q;     // the quadrants on its two sides
    int rim;      // its rim column: 2n on plate A, 0 on plate B
    Point in;     // from its end into it
  };
  const Point along_b = plate_b(params.angle_deg).along;
  const HalfPlate halves[] = {{0, 3, 2 * n, {-1.0, 0.0, 0.0}},
                              {1, 2, 2 * n, {1.0, 0.0, 0.0}},
                              {0, 1, 0, scale(along_b, -1.0)},
                              {3, 2, 0, along_b}};
  for (const HalfPlate& h : halves) {
    for (int j = 0; j < 2 * n; ++j) {  // its end
      add_quad(b, at(h.p, h.rim, j), at(h.p, h.rim, j + 1), at(h.q, h.rim, j + 1),
               at(h.q, h.rim, j), true, h.in, 0);
    }
    const int step = h.rim > n ? 1 : -1;
    for (int c = n; c != h.rim; c += step) {  // its edges at z = -1 and z = +1
      for (const int row : {0, 2 * n}) {
        const Point in{0.0, 0.0, row == 0 ? 1.0 : -1.0};
        add_quad(b, at(h.p, c, row), at(h.p, c + step, row), at(h.q, c + step, row),
                 at(h.q, c, row), true, in, 0);
      }
    }
  }
  for (const int row : {0, 2 * n}) {  // the caps where the corner lines end
    const Point in{0.0, 0.0, row == 0 ? 1.0 : -1.0};
    add_quad(b, at(0, n, row), at(1, n, row), at(2, n, row), at(3, n, row), true, in, 0);
  }
}
}  // namespace

Mesh quarter_dome_surface(const QuarterDomeParams& params) {
  SurfaceBuilder b;
  const double ri = params.inner_radius;
  const double ro = params.inner_radius + params.thickness;
  // Inside: the octant of the ball r < r_i.
  add_sphere_octant(b, params.inner_divisions, ri, +1.0, kDomeInsideEnvironment);
  for (int a = 0; a < 3; ++a) {
    add_quarter_disk(b, a, params.inner_divisions, ri, kDomeInsideEnvironment);
  }
  // Outside: the box [0, L]^3 minus the ball r < r_o.
  add_sphere_octant(b, params.outer_divisions, ro, -1.0, kDomeOutsideEnvironment);
  for (int a = 0; a < 3; ++a) {
    add_outer_plane(b, a, params.outer_divisions, ro, params.box_side, params.radial_layers,
                    params.radial_growth, kDomeOutsideEnvironment);
  }
  for (int a = 0; a < 3; ++a) {
    add_box_face(b, a, params.outer_divisions / 2, params.box_side, 0);  // no environment
  }
  return b.take();
}

Mesh hemispherical_shell_surface(const HemisphericalShellParams& params) {
  SurfaceBuilder b;
  const double ri = params.inner_radius, ro = params.inner_radius + params.thickness;
  // Inside: the half ball r < r_i.
  const Ring inner = add_hemisphere(b, ri, params.inner_rings, params.inner_phase, +1.0,
                                    kDomeInsideEnvironment);
  add_ground_disk(b, inner, ri, params.inner_rings, params.inner_phase, kDomeInsideEnvironment);
  // Outside: the box minus the half ball r < r_o.
  const Ring outer = add_hemisphere(b, ro, params.outer_rings, params.outer_phase, -1.0,
                                    kDomeOutsideEnvironment);
  const double half = 0.5 * params.box_side;
  const BoxGrid box({-half, -half, 0.0}, {half, half, params.box_side}, params.box_size);
  add_ground_outside(b, outer, ro, box, params.radial_layers, params.radial_growth,
                     params.outer_phase, kDomeOutsideEnvironment);
  add_box(b, box, /*with_bottom=*/false);
  return b.take();
}

Mesh sails_surface(const SailsParams& params) {
  const double heel = params.heel_deg * std::numbers::pi / 180.0;
  const double jib_angle = 10.0 * std::numbers::pi / 180.0;  // the jib's chord, turned to leeward
  const std::array<SailShape, 2> sails = {{
      // Jib: forestay from (-9, 0, 2) to (-2.5, 0, 26); its leech ends about 1 m to leeward of
      // the mainsail's luff region: the slot.
      {{-9.0, 0.0, 2.0}, {-2.5, 0.0, 26.0}, 9.5, 2.5,
       {std::cos(jib_angle), std::sin(jib_angle), 0.0},
       {-std::sin(jib_angle), std::cos(jib_angle), 0.0}, 0.08, 6, 16, kJibSideA, kJibSideB},
      // Mainsail: mast from (0, 0, 2) to (1.5, 0, 32).
      {{0.0, 0.0, 2.0}, {1.5, 0.0, 32.0}, 10.0, 4.0, {1.0, 0.0, 0.0}, {0.0, 1.0, 0.0}, 0.08, 6,
       20, kMainSideA, kMainSideB},
  }};
  SurfaceBuilder b;
  for (const SailShape& sail : sails) {
    add_sail_side(b, sail, +1.0, params.thickness, heel, params.grid_scale);
    add_sail_side(b, sail, -1.0, params.thickness, heel, params.grid_scale);
  }
  const Point lo{-30.0, -35.0, -15.0}, hi{40.0, 25.0, 50.0};
  const Point middle = scale(add(lo, hi), 0.5);
  const auto scaled = [&](const Point& corner) {
    return add(middle, scale(sub(corner, middle), params.box_scale));
  };
  add_box(b, BoxGrid(scaled(lo), scaled(hi), params.box_size));
  return b.take();
}

Mesh crossing_plates_surface(const CrossingPlatesParams& params) {
  SurfaceBuilder b;
  for (std::size_t q = 0; q < kQuadrantSigns.size(); ++q) {
    add_quadrant_side(b, params, kQuadrantSigns[q][0], kQuadrantSigns[q][1],
                      static_cast<std::int32_t>(q) + 1);
  }
  if (params.rim_strips) add_rim_strips(b, params);
  add_box(b, BoxGrid({-3.0, -3.0, -3.0}, {3.0, 3.0, 3.0}, params.box_size));
  return b.take();
}

}  // namespace afmesh
