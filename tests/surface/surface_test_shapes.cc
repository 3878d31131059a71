#include "tests/surface/surface_test_shapes.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <limits>
#include <numbers>
#include <numeric>
#include <utility>
#include <vector>

#include "core/geometry/closest_points.h"
#include "core/geometry/vec.h"
#include "core/io/mesh_io.h"
#include "core/quality/measures.h"
#include "core/shapes/graded_surface.h"
#include "core/shapes/shapes.h"
#include "core/sizing/size_field.h"

namespace afmesh::testing {
namespace {

constexpr double kPi = std::numbers::pi;

// Appends the two triangles of quad (a, b, c, d), counter-clockwise seen from its front.
void add_quad(Mesh& mesh, Index a, Index b, Index c, Index d, Index tag = 0) {
  mesh.triangles.push_back({a, b, c});
  mesh.triangles.push_back({a, c, d});
  mesh.triangle_tags.push_back(tag);
  mesh.triangle_tags.push_back(tag);
}

void add_triangle(Mesh& mesh, Index a, Index b, Index c, Index tag = 0) {
  mesh.triangles.push_back({a, b, c});
  mesh.triangle_tags.push_back(tag);
}

// Appends `around` points on the circle of radius r around (cx, cy) at height z(x, y); returns
// the first one's index.
Index add_circle(Mesh& mesh, double cx, double cy, double r, int around,
                 const std::function<double(double, double)>& z) {
  const auto first = static_cast<Index>(mesh.points.size());
  for (int j = 0; j < around; ++j) {
    const double phi = 2.0 * kPi * j / around;
    const double x = cx + r * std::cos(phi), y = cy + r * std::sin(phi);
    mesh.points.push_back({x, y, z(x, y)});
  }
  return first;
}

}  // namespace

Mesh uv_sphere(const Point& centre, double radius, int around, int rings) {
  Mesh mesh;
  mesh.points.push_back({centre[0], centre[1], centre[2] - radius});  // south pole, 0
  for (int i = 1; i <= rings; ++i) {
    const double theta = kPi * i / (rings + 1) - kPi / 2;  // latitude
    const double r = radius * std::cos(theta);
    // The middle ring lies exactly at the centre's height.
    const double z = 2 * i == rings + 1 ? centre[2] : centre[2] + radius * std::sin(theta);
    add_circle(mesh, centre[0], centre[1], r, around, [z](double, double) { return z; });
  }
  const auto north = static_cast<Index>(mesh.points.size());
  mesh.points.push_back({centre[0], centre[1], centre[2] + radius});
  const auto ring = [&](int i, int j) { return 1 + (i - 1) * around + (j % around); };
  const auto tag_of = [&](int i) { return 2 * i <= rings ? Index{2} : Index{1}; };
  for (int j = 0; j < around; ++j) {
    add_triangle(mesh, 0, ring(1, j + 1), ring(1, j), 2);
    for (int i = 1; i < rings; ++i) {
      add_quad(mesh, ring(i, j), ring(i, j + 1), ring(i + 1, j + 1), ring(i + 1, j), tag_of(i));
    }
    add_triangle(mesh, north, ring(rings, j), ring(rings, j + 1), 1);
  }
  return mesh;
}

Mesh closed_cylinder(double radius, double height, int around, int layers) {
  Mesh mesh;
  for (int i = 0; i <= layers; ++i) {
    const double z = height * i / layers;
    add_circle(mesh, 0, 0, radius, around, [z](double, double) { return z; });
  }
  const auto at = [&](int i, int j) { return i * around + (j % around); };
  for (int i = 0; i < layers; ++i) {
    for (int j = 0; j < around; ++j)
      add_quad(mesh, at(i, j), at(i, j + 1), at(i + 1, j + 1), at(i + 1, j));
  }
  const auto bottom = static_cast<Index>(mesh.points.size());
  mesh.points.push_back({0, 0, 0});
  const auto top = static_cast<Index>(mesh.points.size());
  mesh.points.push_back({0, 0, height});
  for (int j = 0; j < around; ++j) {
    add_triangle(mesh, bottom, at(0, j + 1), at(0, j));
    add_triangle(mesh, top, at(layers, j), at(layers, j + 1));
  }
  return mesh;
}

Mesh terrain_disk(double cx, double cy, double radius, int rings, int around,
                  const std::function<double(double, double)>& height) {
  Mesh mesh;
  mesh.points.push_back({cx, cy, height(cx, cy)});
  for (int i = 1; i <= rings; ++i) add_circle(mesh, cx, cy, radius * i / rings, around, height);
  const auto ring = [&](int i, int j) { return 1 + (i - 1) * around + (j % around); };
  for (int j = 0; j < around; ++j) {
    add_triangle(mesh, 0, ring(1, j), ring(1, j + 1));
    for (int i = 1; i < rings; ++i)
      add_quad(mesh, ring(i, j), ring(i + 1, j), ring(i + 1, j + 1), ring(i, j + 1));
  }
  return mesh;
}

Mesh terrain_grid(double x0, double y0, double width, double depth, int n,
                  const std::function<double(double, double)>& height) {
  Mesh mesh;
  for (int j = 0; j <= n; ++j) {
    for (int i = 0; i <= n; ++i) {
      const double x = x0 + width * i / n, y = y0 + depth * j / n;
      mesh.points.push_back({x, y, height(x, y)});
    }
  }
  const auto at = [&](int i, int j) { return j * (n + 1) + i; };
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i)
      add_quad(mesh, at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1));
  }
  return mesh;
}

Mesh three_sheet_t(int n) {
  Mesh mesh;
  // Sheet s maps grid (u, v) in [0, 1]^2 to a point; all three share u = 0 along the y axis.
  const auto point = [](int sheet, double u, double v) -> Point {
    if (sheet == 0) return {-u, v, 0.0};
    if (sheet == 1) return {u, v, 0.0};
    return {0.0, v, u};
  };
  for (int sheet = 0; sheet < 3; ++sheet) {
    const auto first = static_cast<Index>(mesh.points.size());
    for (int j = 0; j <= n; ++j) {
      for (int i = 0; i <= n; ++i) {
        // The shared column u = 0 is stored once, by sheet 0.
        if (sheet > 0 && i == 0) continue;
        mesh.points.push_back(point(sheet, static_cast<double>(i) / n, static_cast<double>(j) / n));
      }
    }
    const auto at = [&](int i, int j) -> Index {
      if (i == 0) return j * (n + 1);  // sheet 0's column u = 0
      return sheet == 0 ? first + j * (n + 1) + i : first + j * n + (i - 1);
    };
    for (int j = 0; j < n; ++j) {
      for (int i = 0; i < n; ++i)
        add_quad(mesh, at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1));
    }
  }
  return mesh;
}

Point random_direction(std::mt19937& rng) {
  std::normal_distribution<double> gauss(0.0, 1.0);
  const Point v{gauss(rng), gauss(rng), gauss(rng)};
  return scale(v, 1.0 / norm(v));
}

Mesh jittered(Mesh mesh, const std::function<double(const Point&)>& amplitude, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (Point& p : mesh.points) p = add(p, scale(random_direction(rng), amplitude(p) * unit(rng)));
  return mesh;
}

Mesh jittered(Mesh mesh, double amplitude, unsigned seed) {
  return jittered(std::move(mesh), [amplitude](const Point&) { return amplitude; }, seed);
}

namespace {

// From `smallest` at x = -1 to `largest` at x = 1, linearly.
class SizeAlongX final : public SizeField {
 public:
  SizeAlongX(double smallest, double largest) : smallest_(smallest), largest_(largest) {}
  double size_at(const Point& x) const override {
    const double t = std::clamp(0.5 * (x[0] + 1.0), 0.0, 1.0);
    return smallest_ + t * (largest_ - smallest_);
  }

 private:
  double smallest_, largest_;
};

}  // namespace

Mesh graded_noisy_sphere(double smallest, double largest, double noise, unsigned seed) {
  const SizeAlongX size(smallest, largest);
  absl::StatusOr<Mesh> graded = grade_surface(sphere_surface({0, 0, 0}, 1.0, largest), size);
  EXPECT_TRUE(graded.ok()) << graded.status();
  if (!graded.ok()) return {};
  return jittered(
      *std::move(graded), [&](const Point& x) { return noise * size.size_at(x); }, seed);
}

Mesh with_flipped_triangles(Mesh mesh, std::int64_t count, unsigned seed) {
  std::vector<std::size_t> order(mesh.triangles.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::shuffle(order.begin(), order.end(), std::mt19937(seed));
  for (std::int64_t k = 0; k < count; ++k) {
    Triangle& t = mesh.triangles[order[k]];
    std::swap(t[1], t[2]);
  }
  return mesh;
}

namespace {

// The x of `n` points inside (0, length), spaced geometrically (each gap 1.15 times the one
// before it), dense at x = 0, or at x = length when `dense_at_end`.
std::vector<double> geometric_stations(double length, int n, bool dense_at_end) {
  std::vector<double> x;
  double gap = 1.0, sum = 0.0;
  for (int i = 0; i <= n; ++i, gap *= 1.15) sum += gap;
  double at = 0.0;
  gap = length / sum;
  for (int i = 0; i < n; ++i, gap *= 1.15) x.push_back(at += gap);
  if (dense_at_end)
    for (double& v : x) v = length - v;
  std::sort(x.begin(), x.end());
  return x;
}

// Appends the strip zipped between the point rows `a` and `b` (each sorted by x, from x = 0 to
// x = length, corners included), each triangle turned to face along `outward`: at each step the
// row whose next point is nearer in x advances, as a CAD exporter zips a ruled face.
void add_zipped_strip(Mesh& mesh, const std::vector<Index>& a, const std::vector<Index>& b,
                      const Point& outward) {
  std::size_t i = 0, j = 0;
  while (i + 1 < a.size() || j + 1 < b.size()) {
    const bool advance_a =
        j + 1 == b.size() ||
        (i + 1 < a.size() && mesh.points[a[i + 1]][0] <= mesh.points[b[j + 1]][0]);
    Triangle t = advance_a ? Triangle{a[i], a[i + 1], b[j]} : Triangle{a[i], b[j + 1], b[j]};
    (advance_a ? i : j) += 1;
    const Point n = cross(sub(mesh.points[t[1]], mesh.points[t[0]]),
                          sub(mesh.points[t[2]], mesh.points[t[0]]));
    if (dot(n, outward) < 0) std::swap(t[1], t[2]);
    add_triangle(mesh, t[0], t[1], t[2]);
  }
}

}  // namespace

Mesh sliver_box(double length, double width, double height, int points_per_edge) {
  Mesh mesh;
  // The four edges along x, going round the x axis: (y, z) = (0, 0), (w, 0), (w, h), (0, h).
  const std::array<std::array<double, 2>, 4> yz = {
      {{0.0, 0.0}, {width, 0.0}, {width, height}, {0.0, height}}};
  std::array<std::vector<Index>, 4> rows;
  for (int e = 0; e < 4; ++e) {
    std::vector<double> x = geometric_stations(length, points_per_edge, e % 2 == 1);
    x.insert(x.begin(), 0.0);
    x.push_back(length);
    for (const double v : x) {
      rows[e].push_back(static_cast<Index>(mesh.points.size()));
      mesh.points.push_back({v, yz[e][0], yz[e][1]});
    }
  }
  // The long faces, between edges e and e + 1: z = 0, y = w, z = h, y = 0.
  const std::array<Point, 4> outward = {{{0, 0, -1}, {0, 1, 0}, {0, 0, 1}, {0, -1, 0}}};
  for (int e = 0; e < 4; ++e) add_zipped_strip(mesh, rows[e], rows[(e + 1) % 4], outward[e]);
  // The end faces x = 0 (normal -x: 0, 3, 2, 1 round it) and x = length (+x: 0, 1, 2, 3).
  add_quad(mesh, rows[0].front(), rows[3].front(), rows[2].front(), rows[1].front());
  add_quad(mesh, rows[0].back(), rows[1].back(), rows[2].back(), rows[3].back());
  return mesh;
}

Mesh sliver_cylinder(double radius, double height, int around) {
  Mesh mesh;
  add_circle(mesh, 0, 0, radius, around, [](double, double) { return 0.0; });
  add_circle(mesh, 0, 0, radius, around, [height](double, double) { return height; });
  const auto at = [&](int i, int j) { return i * around + (j % around); };
  for (int j = 0; j < around; ++j) add_quad(mesh, at(0, j), at(0, j + 1), at(1, j + 1), at(1, j));
  for (int j = 1; j + 1 < around; ++j) {
    add_triangle(mesh, at(0, 0), at(0, j + 1), at(0, j));
    add_triangle(mesh, at(1, 0), at(1, j), at(1, j + 1));
  }
  return mesh;
}

Mesh corpus_mesh(const std::string& name) {
  const std::filesystem::path path =
      std::filesystem::path(AFMESH_SOURCE_DIR) / ".." / "shared" / "corpus" / name;
  absl::StatusOr<Mesh> mesh = read_mesh(path.string());
  EXPECT_TRUE(mesh.ok()) << mesh.status();
  return mesh.ok() ? *std::move(mesh) : Mesh{};
}

absl::StatusOr<SurfaceResult> mesh_corpus_at_mean_edge(
    const std::string& name, const std::function<void(SurfaceParams&)>& adjust) {
  const Mesh input = corpus_mesh(name);
  if (input.triangles.empty()) return absl::NotFoundError("no corpus file " + name);
  SurfaceParams params;
  params.size = mean_edge_length(input);
  if (adjust) adjust(params);
  return generate_surface_mesh(input, params);
}

SurfaceModel surface_model(const Mesh& mesh, const FeatureParams& params) {
  absl::StatusOr<DiscreteSurface> surface = DiscreteSurface::build(mesh);
  EXPECT_TRUE(surface.ok()) << surface.status();
  absl::StatusOr<SurfaceFeatures> features = find_surface_features(*surface, params);
  EXPECT_TRUE(features.ok()) << features.status();
  return {*std::move(surface), features.ok() ? *std::move(features) : SurfaceFeatures{}};
}

void add_on_the_input(const Mesh& mesh, SurfaceMeshState& s) {
  for (const Point& x : mesh.points) {
    const Located on = s.surface.nearest_face(s.surface.to_local(x));
    s.add_point(on.closest, 0.2, on.face, kInvalidIndex);
  }
  for (const Triangle& t : mesh.triangles) s.add_triangle(t, PatchId{0});
}

double smallest_angle(const SurfaceMeshState& s) {
  double smallest = 180.0;
  for (const Triangle& t : s.triangles)
    smallest = std::min(smallest, triangle_quality(s.points, t).min_angle_deg);
  return smallest;
}

AngleCounts angle_counts(const Mesh& mesh) {
  AngleCounts counts;
  for (const Triangle& t : mesh.triangles) {
    const double smallest =
        triangle_min_angle_deg(mesh.points[t[0]], mesh.points[t[1]], mesh.points[t[2]]);
    counts.at_least_30 += smallest >= 30.0;
    counts.under_15 += smallest < 15.0;
  }
  return counts;
}

double scanned_distance(const Mesh& from, const Mesh& to) {
  double worst = 0.0;
  const auto nearest = [&](const Point& x) {
    double best = std::numeric_limits<double>::infinity();
    for (const Triangle& t : to.triangles)
      best = std::min(best, distance(x, closest_point_on_triangle(x, to.points[t[0]],
                                                                  to.points[t[1]],
                                                                  to.points[t[2]])));
    worst = std::max(worst, best);
  };
  for (const Point& p : from.points) nearest(p);
  for (const Triangle& t : from.triangles) {
    const Point &a = from.points[t[0]], &b = from.points[t[1]], &c = from.points[t[2]];
    nearest(scale(add(a, add(b, c)), 1.0 / 3.0));
    nearest(scale(add(a, b), 0.5));
    nearest(scale(add(b, c), 0.5));
    nearest(scale(add(c, a), 0.5));
  }
  return worst;
}

}  // namespace afmesh::testing
