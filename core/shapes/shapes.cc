#include "core/shapes/shapes.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "absl/container/flat_hash_map.h"
#include "absl/container/flat_hash_set.h"

namespace afmesh {
namespace {

// Points on a lattice, created once per lattice coordinate.
class LatticePoints {
 public:
  LatticePoints(Mesh& mesh, double step, const Point& origin)
      : mesh_(mesh), step_(step), origin_(origin) {}
  Index at(int i, int j, int k) {
    auto [it, inserted] = index_.try_emplace(std::array<int, 3>{i, j, k}, 0);
    if (inserted) {
      it->second = static_cast<Index>(mesh_.points.size());
      mesh_.points.push_back({origin_[0] + i * step_, origin_[1] + j * step_, origin_[2] + k * step_});
    }
    return it->second;
  }

 private:
  Mesh& mesh_;
  double step_;
  Point origin_;
  absl::flat_hash_map<std::array<int, 3>, Index> index_;
};

void add_quad(Mesh& m, Index a, Index b, Index c, Index d) {  // a b c d counter-clockwise
  m.triangles.push_back({a, b, c});
  m.triangles.push_back({a, c, d});
}

int divisions(double length, double h) {
  return std::max(1, static_cast<int>(std::lround(length / h)));
}

}  // namespace

Mesh voxel_surface(const std::vector<std::array<int, 3>>& cells, double voxel_size,
                   const Point& origin, int n) {
  Mesh m;
  LatticePoints lattice(m, voxel_size / n, origin);
  absl::flat_hash_set<std::array<int, 3>> filled(cells.begin(), cells.end());
  std::vector<std::array<int, 3>> sorted(cells.begin(), cells.end());
  std::sort(sorted.begin(), sorted.end());
  for (const auto& c : sorted) {
    for (int axis = 0; axis < 3; ++axis) {
      for (int side = 0; side < 2; ++side) {
        std::array<int, 3> nb = c;
        nb[axis] += side ? 1 : -1;
        if (filled.contains(nb)) continue;
        // Face of the voxel at axis = c[axis] + side, outward normal along ±axis.
        const int u = (axis + 1) % 3, v = (axis + 2) % 3;
        for (int a = 0; a < n; ++a) {
          for (int b = 0; b < n; ++b) {
            auto corner = [&](int da, int db) {
              std::array<int, 3> q{};
              q[axis] = (c[axis] + side) * n;
              q[u] = c[u] * n + a + da;
              q[v] = c[v] * n + b + db;
              return lattice.at(q[0], q[1], q[2]);
            };
            // (u, v, axis) is right-handed: counter-clockwise in (u, v) faces +axis.
            if (side)
              add_quad(m, corner(0, 0), corner(1, 0), corner(1, 1), corner(0, 1));
            else
              add_quad(m, corner(0, 0), corner(0, 1), corner(1, 1), corner(1, 0));
          }
        }
      }
    }
  }
  m.triangle_tags.assign(m.triangles.size(), 0);
  return m;
}

Mesh box_tets(const Point& lo, const Point& hi, int n) {
  Mesh mesh;
  const int m = n + 1;
  mesh.points.reserve(static_cast<std::size_t>(m) * m * m);
  for (int k = 0; k < m; ++k) {
    for (int j = 0; j < m; ++j) {
      for (int i = 0; i < m; ++i) {
        const std::array<int, 3> ijk = {i, j, k};
        Point p;
        for (int a = 0; a < 3; ++a) {
          p[a] = ijk[a] == n ? hi[a] : lo[a] + (hi[a] - lo[a]) * ijk[a] / n;
        }
        mesh.points.push_back(p);
      }
    }
  }
  const auto at = [m](int i, int j, int k) { return static_cast<Index>((k * m + j) * m + i); };
  // The six axis orders (a, b, c); the tet lo, lo + e_a, lo + e_a + e_b, hi has
  // det[e_a, e_b, e_c] = the order's parity, so odd orders swap their last two points.
  constexpr std::array<std::array<int, 3>, 6> kOrders = {
      {{0, 1, 2}, {1, 2, 0}, {2, 0, 1}, {0, 2, 1}, {2, 1, 0}, {1, 0, 2}}};
  mesh.tets.reserve(6 * static_cast<std::size_t>(n) * n * n);
  for (int k = 0; k < n; ++k) {
    for (int j = 0; j < n; ++j) {
      for (int i = 0; i < n; ++i) {
        for (int o = 0; o < 6; ++o) {
          std::array<int, 3> c = {i, j, k};
          const Index v0 = at(c[0], c[1], c[2]);
          ++c[kOrders[o][0]];
          const Index v1 = at(c[0], c[1], c[2]);
          ++c[kOrders[o][1]];
          const Index v2 = at(c[0], c[1], c[2]);
          const Index v3 = at(i + 1, j + 1, k + 1);
          mesh.tets.push_back(o < 3 ? Tet{v0, v1, v2, v3} : Tet{v0, v1, v3, v2});
        }
      }
    }
  }
  mesh.tet_tags.assign(mesh.tets.size(), 0);
  return mesh;
}

Mesh box_surface(const Point& lo, const Point& hi, double h) {
  // A single voxel stretched to the box: divide each axis on its own.
  const std::array<int, 3> n{divisions(hi[0] - lo[0], h), divisions(hi[1] - lo[1], h),
                             divisions(hi[2] - lo[2], h)};
  Mesh m;
  absl::flat_hash_map<std::array<int, 3>, Index> index;
  auto at = [&](std::array<int, 3> q) {
    auto [it, inserted] = index.try_emplace(q, 0);
    if (inserted) {
      it->second = static_cast<Index>(m.points.size());
      Point p;
      for (int a = 0; a < 3; ++a) p[a] = lo[a] + (hi[a] - lo[a]) * q[a] / n[a];
      m.points.push_back(p);
    }
    return it->second;
  };
  for (int axis = 0; axis < 3; ++axis) {
    const int u = (axis + 1) % 3, v = (axis + 2) % 3;
    for (int side = 0; side < 2; ++side) {
      for (int a = 0; a < n[u]; ++a) {
        for (int b = 0; b < n[v]; ++b) {
          auto corner = [&](int da, int db) {
            std::array<int, 3> q{};
            q[axis] = side * n[axis];
            q[u] = a + da;
            q[v] = b + db;
            return at(q);
          };
          if (side)
            add_quad(m, corner(0, 0), corner(1, 0), corner(1, 1), corner(0, 1));
          else
            add_quad(m, corner(0, 0), corner(0, 1), corner(1, 1), corner(1, 0));
        }
      }
    }
  }
  m.triangle_tags.assign(m.triangles.size(), 0);
  return m;
}

Mesh l_block_with_hole_surface(double unit, double h) {
  // Seen from +z, one voxel layer (X filled, . the through-hole):
  //   y=4  X X
  //   y=3  X X
  //   y=2  X X X X
  //   y=1  X X . X
  //   y=0  X X X X
  std::vector<std::array<int, 3>> cells;
  for (int x = 0; x < 4; ++x)
    for (int y = 0; y < 3; ++y)
      if (!(x == 2 && y == 1)) cells.push_back({x, y, 0});
  for (int x = 0; x < 2; ++x)
    for (int y = 3; y < 5; ++y) cells.push_back({x, y, 0});
  return voxel_surface(cells, unit, {0, 0, 0}, divisions(unit, h));
}

Mesh sphere_surface(const Point& center, double radius, double h) {
  const double t = (1.0 + std::sqrt(5.0)) / 2.0;
  const std::array<Point, 12> ico = {{{-1, t, 0}, {1, t, 0}, {-1, -t, 0}, {1, -t, 0},
                                      {0, -1, t}, {0, 1, t}, {0, -1, -t}, {0, 1, -t},
                                      {t, 0, -1}, {t, 0, 1}, {-t, 0, -1}, {-t, 0, 1}}};
  const std::array<Triangle, 20> faces = {{{0, 11, 5}, {0, 5, 1}, {0, 1, 7}, {0, 7, 10},
                                           {0, 10, 11}, {1, 5, 9}, {5, 11, 4}, {11, 10, 2},
                                           {10, 7, 6}, {7, 1, 8}, {3, 9, 4}, {3, 4, 2},
                                           {3, 2, 6}, {3, 6, 8}, {3, 8, 9}, {4, 9, 5},
                                           {2, 4, 11}, {6, 2, 10}, {8, 6, 7}, {9, 8, 1}}};
  // Icosahedron edge is 2 on the circumradius sqrt(1 + t^2).
  const double edge = 2.0 * radius / std::sqrt(1.0 + t * t);
  const int n = divisions(edge, h);
  Mesh m;
  // A point is named by its barycentric weights over the icosahedron's vertices, written with
  // the vertices in ascending order, so a point on a shared edge is created once and computed
  // the same way from either face.
  using Key = std::array<int, 6>;  // (vertex, weight) × up to 3, unused slots -1
  absl::flat_hash_map<Key, Index> index;
  auto point_at = [&](const Triangle& f, int i, int j) {
    std::array<std::pair<int, int>, 3> w = {{{f[0], n - i - j}, {f[1], i}, {f[2], j}}};
    std::sort(w.begin(), w.end());
    Key key{-1, -1, -1, -1, -1, -1};
    int used = 0;
    for (auto [vtx, weight] : w)
      if (weight > 0) key[2 * used] = vtx, key[2 * used + 1] = weight, ++used;
    auto [it, inserted] = index.try_emplace(key, 0);
    if (inserted) {
      it->second = static_cast<Index>(m.points.size());
      Point p{0, 0, 0};
      for (int s = 0; s < used; ++s)
        for (int a = 0; a < 3; ++a) p[a] += ico[key[2 * s]][a] * key[2 * s + 1];
      const double len = std::sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]);
      for (int a = 0; a < 3; ++a) p[a] = center[a] + radius * p[a] / len;
      m.points.push_back(p);
    }
    return it->second;
  };
  for (const Triangle& f : faces) {
    for (int i = 0; i < n; ++i) {
      for (int j = 0; i + j < n; ++j) {
        m.triangles.push_back({point_at(f, i, j), point_at(f, i + 1, j), point_at(f, i, j + 1)});
        if (i + j + 1 < n)
          m.triangles.push_back(
              {point_at(f, i + 1, j), point_at(f, i + 1, j + 1), point_at(f, i, j + 1)});
      }
    }
  }
  m.triangle_tags.assign(m.triangles.size(), 0);
  return m;
}

Mesh torus_surface(double major_radius, double minor_radius, double h) {
  const double pi = std::numbers::pi;
  const int nu = std::max(3, divisions(2 * pi * major_radius, h));
  const int nv = std::max(3, divisions(2 * pi * minor_radius, h));
  Mesh m;
  for (int i = 0; i < nu; ++i) {
    const double u = 2 * pi * i / nu;
    for (int j = 0; j < nv; ++j) {
      const double v = 2 * pi * j / nv;
      const double rho = major_radius + minor_radius * std::cos(v);
      m.points.push_back({rho * std::cos(u), rho * std::sin(u), minor_radius * std::sin(v)});
    }
  }
  auto at = [&](int i, int j) { return static_cast<Index>((i % nu) * nv + (j % nv)); };
  for (int i = 0; i < nu; ++i)
    for (int j = 0; j < nv; ++j)  // d/du × d/dv points out of the tube
      add_quad(m, at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1));
  m.triangle_tags.assign(m.triangles.size(), 0);
  return m;
}

Mesh schoenhardt_prism_surface() {
  Mesh m;
  const double pi = std::numbers::pi;
  for (int level = 0; level < 2; ++level)
    for (int i = 0; i < 3; ++i) {
      const double a = pi / 2 + 2 * pi * i / 3 + level * pi / 6;
      m.points.push_back({std::cos(a), std::sin(a), static_cast<double>(level)});
    }
  m.triangles = {{0, 2, 1}, {3, 4, 5}, {0, 1, 4}, {0, 4, 3}, {1, 2, 5}, {1, 5, 4}, {2, 0, 3}, {2, 3, 5}};
  m.triangle_tags.assign(m.triangles.size(), 0);
  return m;
}

}  // namespace afmesh
