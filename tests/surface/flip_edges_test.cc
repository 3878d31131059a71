// Tests of the edge flips inside the patches (flip_edges.h): a flip that raises the smaller
// minimum angle of its two triangles is made, and one whose new triangles would cross another
// part of the surface is not.
#include "core/surface/flip_edges.h"

#include <gtest/gtest.h>

#include <vector>

#include "core/geometry/intersect.h"
#include "core/quality/measures.h"

namespace afmesh {
namespace {

// A roof of two thin triangles over the long diagonal (a, b), its ridge at z = 1 and its eaves
// c, d at z = 0.6: t1 = (a, b, c), t2 = (b, a, d), oriented alike (normals up), one patch. The
// flip to (a, d, c), (d, b, c) raises the smallest angle from 26.6° to 31.0° and puts the
// diagonal (c, d) 0.4 below the ridge; every other rule of the flip holds (the quadrilateral is
// convex seen from above, the new triangles turn by 21.8° from the mean normal).
struct Roof {
  std::vector<Point> points = {{-1.0, 0.0, 1.0}, {1.0, 0.0, 1.0}, {0.0, 0.3, 0.6},
                               {0.0, -0.3, 0.6}};
  std::vector<Triangle> triangles = {{0, 1, 2}, {1, 0, 3}};
  std::vector<Index> patch = {0, 0};
};

TEST(FlipEdges, AFlipRaisesTheSmallerMinimumAngle) {
  Roof roof;
  const absl::StatusOr<std::int64_t> flips =
      flip_edges(roof.points, roof.triangles, roof.patch, {});
  ASSERT_TRUE(flips.ok()) << flips.status();
  EXPECT_EQ(*flips, 1);
  EXPECT_EQ(roof.triangles, (std::vector<Triangle>{{0, 3, 2}, {3, 1, 2}}));
  for (const Triangle& t : roof.triangles)
    EXPECT_GT(triangle_min_angle_deg(roof.points[t[0]], roof.points[t[1]], roof.points[t[2]]),
              30.0);
}

TEST(FlipEdges, AnEdgeOnALineIsNotFlipped) {
  Roof roof;
  const absl::flat_hash_set<std::pair<Index, Index>> line_sides = {{Index{0}, Index{1}}};
  const absl::StatusOr<std::int64_t> flips =
      flip_edges(roof.points, roof.triangles, roof.patch, line_sides);
  ASSERT_TRUE(flips.ok()) << flips.status();
  EXPECT_EQ(*flips, 0);
}

// A sheet under the ridge (a triangle of another patch at z = 0.8, x from -0.7 to -0.3, within
// the roof's outline seen from above) does not meet the roof, but the flipped roof passes
// through z = 0.8 at x = -0.5 across it: the flip would make the surface cross itself (as on
// gmsh_t13_data with no curvature bound, a plate 2 thick meshed at 9.8). It is not made.
TEST(FlipEdges, AFlipThatWouldCrossAnotherPartOfTheSurfaceIsNotMade) {
  Roof roof;
  roof.points.insert(roof.points.end(),
                     {{-0.7, -0.05, 0.8}, {-0.3, -0.05, 0.8}, {-0.5, 0.05, 0.8}});
  roof.triangles.push_back({4, 5, 6});
  roof.patch.push_back(1);
  // The sheet meets neither triangle of the roof as it is, and the flipped roof's first triangle.
  for (int t = 0; t < 2; ++t)
    EXPECT_FALSE(triangles_intersect_improperly(roof.points, roof.triangles[t], {4, 5, 6}));
  EXPECT_TRUE(triangles_intersect_improperly(roof.points, {0, 3, 2}, {4, 5, 6}));

  const std::vector<Triangle> before = roof.triangles;
  const absl::StatusOr<std::int64_t> flips =
      flip_edges(roof.points, roof.triangles, roof.patch, {});
  ASSERT_TRUE(flips.ok()) << flips.status();
  EXPECT_EQ(*flips, 0);
  EXPECT_EQ(roof.triangles, before);
  // Untested (FlipParams::keep_uncrossed off: generate_surface_mesh's first try), it is made.
  const absl::StatusOr<std::int64_t> untested =
      flip_edges(roof.points, roof.triangles, roof.patch, {}, {.keep_uncrossed = false});
  ASSERT_TRUE(untested.ok()) << untested.status();
  EXPECT_EQ(*untested, 1);
}

}  // namespace
}  // namespace afmesh
