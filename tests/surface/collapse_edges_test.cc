// Tests of the edge collapses inside the patches (collapse_edges.h): on a coarse sphere whose
// points lie on the input, points pulled next to a neighbour make needles and caps; the
// collapses remove them, the surface stays closed, manifold and oriented with every point on
// the input, anchored points stay, and nothing is done where both ends are anchored.
#include "core/surface/collapse_edges.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <vector>

#include "core/geometry/vec.h"
#include "core/quality/validate.h"
#include "core/shapes/shapes.h"
#include "core/sizing/size_field.h"
#include "tests/surface/surface_test_shapes.h"

namespace afmesh {
namespace {

class CancelledProgress final : public Progress {
 public:
  bool cancelled() const override { return true; }
};

// Moves point q of s to within `fraction` of its edge to point r, on the input.
void pull_towards(SurfaceMeshState& s, Index q, Index r, double fraction) {
  const Point x = add(s.points[r], scale(sub(s.points[q], s.points[r]), fraction));
  const Located on = s.surface.nearest_face(x);
  s.points[q] = on.closest;
  s.host[q] = on.face;
}

Mesh mesh_of(const SurfaceMeshState& s) {
  Mesh m;
  m.points = s.points;
  m.triangles = s.triangles;
  m.triangle_tags = s.triangle_tags;
  return m;
}

struct Needles {
  testing::SurfaceModel model = testing::surface_model(sphere_surface({0, 0, 0}, 1.0, 0.05));
  UniformSize field{0.2};
  SurfaceMeshState s{model.surface, model.features, field, 1.2};
  std::vector<Index> pulled;

  // A coarse sphere; the first corner of every 25th triangle pulled to 3% of its edge to the
  // second (each point at most once).
  Needles() {
    testing::add_on_the_input(sphere_surface({0, 0, 0}, 1.0, 0.2), s);
    std::vector<char> used(s.points.size(), 0);
    for (std::size_t t = 0; t < s.triangles.size(); t += 25) {
      const Index q = s.triangles[t][0], r = s.triangles[t][1];
      if (used[q] || used[r]) continue;
      used[q] = used[r] = 1;
      pull_towards(s, q, r, 0.03);
      pulled.push_back(q);
    }
  }
};

TEST(CollapseEdges, RemovesNeedlesAndKeepsTheSurfaceClosedAndOnTheInput) {
  Needles n;
  SurfaceMeshState& s = n.s;
  ASSERT_EQ(n.model.features.patches.size(), 1u);
  {
    const ValidationReport before = validate_surface(mesh_of(s));
    ASSERT_TRUE(before.valid()) << before.to_string();
  }
  const std::size_t points = s.points.size(), triangles = s.triangles.size();
  const double smallest_before = testing::smallest_angle(s);

  const absl::StatusOr<std::int64_t> collapses = collapse_edges(s);
  ASSERT_TRUE(collapses.ok()) << collapses.status();
  std::printf("%zu points pulled: smallest angle %.2f -> %.2f after %lld collapses\n",
              n.pulled.size(), smallest_before, testing::smallest_angle(s),
              static_cast<long long>(*collapses));
  EXPECT_GE(*collapses, static_cast<std::int64_t>(n.pulled.size()));
  EXPECT_LT(smallest_before, 5.0);
  EXPECT_GE(testing::smallest_angle(s), 15.0);
  // Each collapse removes one point and two triangles; the sphere stays a sphere.
  EXPECT_EQ(s.points.size(), points - static_cast<std::size_t>(*collapses));
  EXPECT_EQ(s.triangles.size(), triangles - 2 * static_cast<std::size_t>(*collapses));
  EXPECT_EQ(s.host.size(), s.points.size());
  EXPECT_EQ(s.anchor.size(), s.points.size());
  EXPECT_EQ(s.triangle_patch.size(), s.triangles.size());
  EXPECT_EQ(s.triangle_tags.size(), s.triangles.size());
  const ValidationReport report = validate_surface(mesh_of(s));
  EXPECT_TRUE(report.valid()) << report.to_string();
  for (std::size_t q = 0; q < s.points.size(); ++q) {
    EXPECT_LT(n.model.surface.nearest_face(s.points[q]).squared_distance, 1e-24) << "point " << q;
    EXPECT_LT(std::sqrt(n.model.surface.locate(s.points[q], s.host[q]).squared_distance), 1e-12);
  }
}

TEST(CollapseEdges, NeverRemovesAnAnchoredPoint) {
  Needles n;
  SurfaceMeshState& s = n.s;
  // Every point anchored, as line points and corners are: nothing may be collapsed.
  for (Index q = 0; q < static_cast<Index>(s.points.size()); ++q)
    s.anchor[q] = n.model.surface.triangle(s.host[q])[0];
  const std::vector<Point> points = s.points;
  const std::vector<Triangle> triangles = s.triangles;
  const absl::StatusOr<std::int64_t> collapses = collapse_edges(s);
  ASSERT_TRUE(collapses.ok()) << collapses.status();
  EXPECT_EQ(*collapses, 0);
  EXPECT_EQ(s.points, points);
  EXPECT_EQ(s.triangles, triangles);
}

TEST(CollapseEdges, StopsWithCancelled) {
  Needles n;
  CancelledProgress cancelled;
  EXPECT_EQ(collapse_edges(n.s, {}, cancelled).status().code(), absl::StatusCode::kCancelled);
}

}  // namespace
}  // namespace afmesh
