// Tests of the smoothing of the points inside the patches (smooth_points.h): on a sphere meshed
// by a jittered coarse triangulation whose points lie on the input, the smallest angle rises,
// every point stays on the input, no triangle turns over, anchored points stay, and the
// triangles are the same.
#include "core/surface/smooth_points.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "core/geometry/vec.h"
#include "core/quality/measures.h"
#include "core/shapes/shapes.h"
#include "core/sizing/size_field.h"
#include "tests/surface/surface_test_shapes.h"

namespace afmesh {
namespace {

class CancelledProgress final : public Progress {
 public:
  bool cancelled() const override { return true; }
};

Point normal_of(const std::vector<Point>& p, const Triangle& t) {
  const Point n = cross(sub(p[t[1]], p[t[0]]), sub(p[t[2]], p[t[0]]));
  return scale(n, 1.0 / norm(n));
}

TEST(SmoothPoints, RaisesTheSmallestAngleAndKeepsEveryPointOnTheInput) {
  const testing::SurfaceModel model = testing::surface_model(sphere_surface({0, 0, 0}, 1.0, 0.05));
  ASSERT_EQ(model.features.patches.size(), 1u);
  const UniformSize field(0.2);
  SurfaceMeshState s(model.surface, model.features, field, 1.2);
  // A coarse sphere, jittered by a third of its edges.
  testing::add_on_the_input(testing::jittered(sphere_surface({0, 0, 0}, 1.0, 0.2), 0.06, 7), s);
  // Three points anchored, as line points are: they must not move.
  for (const Index q : {0, 10, 20}) s.anchor[q] = model.surface.triangle(s.host[q])[0];
  const std::vector<Point> before = s.points;
  const std::vector<Triangle> triangles = s.triangles;
  const double smallest_before = testing::smallest_angle(s);

  const absl::StatusOr<std::int64_t> moves = smooth_points(s);
  ASSERT_TRUE(moves.ok()) << moves.status();
  std::printf("smallest angle %.2f -> %.2f after %lld moves\n", smallest_before,
              testing::smallest_angle(s), static_cast<long long>(*moves));
  EXPECT_GT(*moves, 0);
  EXPECT_GT(testing::smallest_angle(s), smallest_before + 5.0);
  EXPECT_EQ(s.triangles, triangles);
  for (const Index q : {0, 10, 20}) EXPECT_EQ(s.points[q], before[q]);
  const double turn = std::cos(30.0 * std::numbers::pi / 180.0);
  for (const Triangle& t : s.triangles)
    EXPECT_GT(dot(normal_of(s.points, t), normal_of(before, t)), turn - 1e-12);
  for (std::size_t q = 0; q < s.points.size(); ++q) {
    const Located on = model.surface.nearest_face(s.points[q]);
    EXPECT_LT(on.squared_distance, 1e-24) << "point " << q;
    EXPECT_LT(std::sqrt(model.surface.locate(s.points[q], s.host[q]).squared_distance), 1e-12);
  }
}

TEST(SmoothPoints, StopsWithCancelled) {
  const testing::SurfaceModel model = testing::surface_model(sphere_surface({0, 0, 0}, 1.0, 0.1));
  const UniformSize field(0.2);
  SurfaceMeshState s(model.surface, model.features, field, 1.2);
  testing::add_on_the_input(testing::jittered(sphere_surface({0, 0, 0}, 1.0, 0.05), 0.01, 3), s);
  CancelledProgress cancelled;
  EXPECT_EQ(smooth_points(s, {}, cancelled).status().code(), absl::StatusCode::kCancelled);
}

}  // namespace
}  // namespace afmesh
