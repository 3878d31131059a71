// Grading a surface to a size field (core/shapes/graded_surface.h): every edge ends within the
// bound, the surface stays a closed, oriented manifold of the same shape, tags and triangle
// shapes are kept, and bad input is refused.
#include "core/shapes/graded_surface.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "absl/strings/match.h"
#include "core/geometry/vec.h"
#include "core/shapes/shapes.h"
#include "core/sizing/spec_size_field.h"
#include "core/volume/generate_volume_mesh.h"

namespace afmesh {
namespace {

// A size growing linearly with the distance to a point.
class RadialSize final : public SizeField {
 public:
  RadialSize(const Point& centre, double at_centre, double slope)
      : centre_(centre), at_centre_(at_centre), slope_(slope) {}
  double size_at(const Point& x) const override {
    return at_centre_ + slope_ * distance(x, centre_);
  }

 private:
  Point centre_;
  double at_centre_, slope_;
};

// Largest edge length / (max_ratio × size at its midpoint) over the surface.
double worst_edge_ratio(const Mesh& mesh, const SizeField& size, double max_ratio) {
  double worst = 0.0;
  for (const Triangle& t : mesh.triangles) {
    for (int k = 0; k < 3; ++k) {
      const Point& a = mesh.points[t[k]];
      const Point& b = mesh.points[t[(k + 1) % 3]];
      worst = std::max(worst, distance(a, b) / (max_ratio * size.size_at(lerp(a, b, 0.5))));
    }
  }
  return worst;
}

double area(const Mesh& mesh) {
  double sum = 0.0;
  for (const Triangle& t : mesh.triangles) {
    sum += 0.5 * norm(cross(sub(mesh.points[t[1]], mesh.points[t[0]]),
                            sub(mesh.points[t[2]], mesh.points[t[0]])));
  }
  return sum;
}

// Six times the enclosed volume (divergence theorem over outward triangles).
double six_volume(const Mesh& mesh) {
  double sum = 0.0;
  for (const Triangle& t : mesh.triangles) {
    sum += dot(mesh.points[t[0]], cross(mesh.points[t[1]], mesh.points[t[2]]));
  }
  return sum;
}

double smallest_angle_deg(const Mesh& mesh) {
  double smallest = 180.0;
  for (const Triangle& t : mesh.triangles) {
    for (int k = 0; k < 3; ++k) {
      const Point u = sub(mesh.points[t[(k + 1) % 3]], mesh.points[t[k]]);
      const Point v = sub(mesh.points[t[(k + 2) % 3]], mesh.points[t[k]]);
      smallest =
          std::min(smallest, std::acos(dot(u, v) / (norm(u) * norm(v))) * 180.0 / std::numbers::pi);
    }
  }
  return smallest;
}

// The unit cube's surface with each face's triangles tagged 1..6 by outward normal direction.
Mesh tagged_cube(double h) {
  Mesh cube = box_surface({0, 0, 0}, {1, 1, 1}, h);
  for (std::size_t i = 0; i < cube.triangles.size(); ++i) {
    const Triangle& t = cube.triangles[i];
    const Point n =
        cross(sub(cube.points[t[1]], cube.points[t[0]]), sub(cube.points[t[2]], cube.points[t[0]]));
    for (int axis = 0; axis < 3; ++axis) {
      if (n[axis] != 0.0) cube.triangle_tags[i] = 1 + 2 * axis + (n[axis] > 0 ? 1 : 0);
    }
  }
  return cube;
}

// The tag tagged_cube gives a triangle of the graded cube (all its points on one face).
Index face_tag(const Mesh& mesh, const Triangle& t) {
  for (int axis = 0; axis < 3; ++axis) {
    for (const double side : {0.0, 1.0}) {
      if (mesh.points[t[0]][axis] == side && mesh.points[t[1]][axis] == side &&
          mesh.points[t[2]][axis] == side) {
        return 1 + 2 * axis + (side == 1.0 ? 1 : 0);
      }
    }
  }
  return -1;
}

TEST(GradedSurface, CubeGradedToARadialFieldKeepsShapeTagsAndRightTriangles) {
  const Mesh cube = tagged_cube(0.25);
  const RadialSize size({0, 0, 0}, 0.02, 0.2);
  absl::StatusOr<Mesh> graded = grade_surface(cube, size);
  ASSERT_TRUE(graded.ok()) << graded.status();
  EXPECT_GT(graded->triangles.size(), 3 * cube.triangles.size());
  EXPECT_LE(worst_edge_ratio(*graded, size, std::numbers::sqrt2), 1.0);
  EXPECT_TRUE(validate_front(*graded).ok()) << validate_front(*graded);
  EXPECT_NEAR(area(*graded), 6.0, 1e-12);
  EXPECT_NEAR(six_volume(*graded), 6.0, 1e-12);
  // Input points first, unchanged; every triangle on the face (and with the tag) it came from.
  for (std::size_t p = 0; p < cube.points.size(); ++p) EXPECT_EQ(graded->points[p], cube.points[p]);
  ASSERT_EQ(graded->triangle_tags.size(), graded->triangles.size());
  for (std::size_t i = 0; i < graded->triangles.size(); ++i) {
    EXPECT_EQ(graded->triangle_tags[i], face_tag(*graded, graded->triangles[i])) << i;
  }
  // Longest-edge bisection of right isosceles triangles gives right isosceles triangles.
  EXPECT_NEAR(smallest_angle_deg(*graded), 45.0, 1e-6);
}

TEST(GradedSurface, EdgesShrinkTowardsTheSmallSizes) {
  const RadialSize size({0, 0, 0}, 0.02, 0.2);
  absl::StatusOr<Mesh> graded = grade_surface(tagged_cube(0.25), size);
  ASSERT_TRUE(graded.ok()) << graded.status();
  double near_corner = 1.0, far_corner = 0.0;
  for (const Triangle& t : graded->triangles) {
    const Point& a = graded->points[t[0]];
    const Point& b = graded->points[t[1]];
    const double r = norm(lerp(a, b, 0.5));
    if (r < 0.1) near_corner = std::min(near_corner, distance(a, b));
    if (r > 1.5) far_corner = std::max(far_corner, distance(a, b));
  }
  EXPECT_LT(near_corner, 0.05);
  EXPECT_GT(far_corner, 0.2);
}

TEST(GradedSurface, SphereStaysAClosedOrientedManifoldWithinTheBound) {
  const Mesh sphere = sphere_surface({0.1, 0.2, 0.3}, 1.0, 0.4);
  const RadialSize size({1.1, 0.2, 0.3}, 0.03, 0.3);  // a point on the sphere
  GradedSurfaceParams params;
  params.max_ratio = 1.0;
  absl::StatusOr<Mesh> graded = grade_surface(sphere, size, params);
  ASSERT_TRUE(graded.ok()) << graded.status();
  EXPECT_LE(worst_edge_ratio(*graded, size, 1.0), 1.0);
  EXPECT_TRUE(validate_front(*graded).ok()) << validate_front(*graded);
  EXPECT_NEAR(six_volume(*graded), six_volume(sphere), 1e-12 * six_volume(sphere));
  // Bisection never makes an angle smaller than half the smallest input angle.
  EXPECT_GE(smallest_angle_deg(*graded), 0.5 * smallest_angle_deg(sphere));
}

TEST(GradedSurface, IsDeterministicAndLeavesFineSurfacesAlone) {
  const SizeSpec spec{.max_size = 0.3,
                      .growth = 1.0,
                      .sources = {SizeSource{{{0.5, 0.5, 1.0}}, 0.04, 0.0, 0.3, PowerLaw{1.5}}},
                      .background = std::nullopt};
  absl::StatusOr<SpecSizeField> field = SpecSizeField::create(spec, Box{{0, 0, 0}, {1, 1, 1}});
  ASSERT_TRUE(field.ok());
  absl::StatusOr<Mesh> first = grade_surface(tagged_cube(0.3), *field);
  absl::StatusOr<Mesh> second = grade_surface(tagged_cube(0.3), *field);
  ASSERT_TRUE(first.ok() && second.ok());
  EXPECT_EQ(first->points, second->points);
  EXPECT_EQ(first->triangles, second->triangles);
  EXPECT_EQ(first->triangle_tags, second->triangle_tags);
  const Mesh fine = tagged_cube(0.1);
  absl::StatusOr<Mesh> same = grade_surface(fine, UniformSize(0.5));
  ASSERT_TRUE(same.ok());
  EXPECT_EQ(same->points, fine.points);
  EXPECT_EQ(same->triangles, fine.triangles);
}

TEST(GradedSurface, RefusesBadInputAndRunawayRefinement) {
  Mesh fan;  // three triangles on the edge (0, 1)
  fan.points = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}};
  fan.triangles = {{0, 1, 2}, {1, 0, 3}, {0, 1, 4}};
  fan.triangle_tags = {0, 0, 0};
  EXPECT_TRUE(absl::StrContains(grade_surface(fan, UniformSize(1)).status().message(),
                                "in more than two triangles"));
  fan.triangles = {{0, 1, 7}};
  fan.triangle_tags = {0};
  EXPECT_EQ(grade_surface(fan, UniformSize(1)).status().code(), absl::StatusCode::kInvalidArgument);
  GradedSurfaceParams params;
  params.max_triangles = 1000;
  EXPECT_EQ(grade_surface(tagged_cube(0.5), UniformSize(0.01), params).status().code(),
            absl::StatusCode::kResourceExhausted);
  params.max_ratio = 0.0;
  EXPECT_EQ(grade_surface(tagged_cube(0.5), UniformSize(1), params).status().code(),
            absl::StatusCode::kInvalidArgument);
}

}  // namespace
}  // namespace afmesh
