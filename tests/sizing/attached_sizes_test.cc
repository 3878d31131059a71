// Sizes attached to the input's points (eq. 15): edge-length defaults, tag and point overrides.
#include "core/sizing/attached_sizes.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <limits>
#include <vector>

namespace afmesh {
namespace {

// The closed surface of the tet (0,0,0), (2,0,0), (0,1,0), (0,0,3), outward-oriented, with
// triangle tags 10, 10, 20, 30, and an unused fifth point.
Mesh tet_surface() {
  Mesh m;
  m.points = {{0, 0, 0}, {2, 0, 0}, {0, 1, 0}, {0, 0, 3}, {5, 5, 5}};
  m.triangles = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
  m.triangle_tags = {10, 10, 20, 30};
  return m;
}

constexpr double kInf = std::numeric_limits<double>::infinity();

TEST(AttachedSizes, DefaultIsTheShortestIncidentEdge) {
  const auto sizes = attached_point_sizes(tet_surface());
  ASSERT_TRUE(sizes.ok()) << sizes.status();
  // Edges: 01 = 2, 02 = 1, 03 = 3, 12 = sqrt 5, 13 = sqrt 13, 23 = sqrt 10.
  EXPECT_DOUBLE_EQ((*sizes)[0], 1.0);
  EXPECT_DOUBLE_EQ((*sizes)[1], 2.0);
  EXPECT_DOUBLE_EQ((*sizes)[2], 1.0);
  EXPECT_DOUBLE_EQ((*sizes)[3], 3.0);
  EXPECT_EQ((*sizes)[4], kInf);
}

TEST(AttachedSizes, MeanRuleAveragesTheIncidentEdges) {
  AttachedSizeParams params;
  params.rule = EdgeLengthRule::kMean;
  const auto sizes = attached_point_sizes(tet_surface(), params);
  ASSERT_TRUE(sizes.ok());
  EXPECT_NEAR((*sizes)[0], (2.0 + 1.0 + 3.0) / 3.0, 1e-15);
  EXPECT_NEAR((*sizes)[3], (3.0 + std::sqrt(13.0) + std::sqrt(10.0)) / 3.0, 1e-15);
}

TEST(AttachedSizes, TagAndPointOverridesReplaceTheDefault) {
  AttachedSizeParams params;
  params.tag_sizes = {{20, 0.4}, {30, 0.25}};  // tag 20: points 0, 3, 2; tag 30: points 1, 2, 3
  params.point_sizes = {{3, 7.0}};
  const auto sizes = attached_point_sizes(tet_surface(), params);
  ASSERT_TRUE(sizes.ok());
  EXPECT_EQ((*sizes)[0], 0.4);
  EXPECT_EQ((*sizes)[1], 0.25);
  EXPECT_EQ((*sizes)[2], 0.25);  // on both tags: the smaller
  EXPECT_EQ((*sizes)[3], 7.0);   // the point override wins
}

TEST(AttachedSizes, BadOverridesAndTrianglesAreNamed) {
  AttachedSizeParams params;
  params.point_sizes = {{9, 1.0}};
  EXPECT_EQ(attached_point_sizes(tet_surface(), params).status().message(),
            "point_sizes names point 9, out of range [0, 5)");
  params.point_sizes = {{1, -1.0}};
  EXPECT_EQ(attached_point_sizes(tet_surface(), params).status().message(),
            "point_sizes[1] must be a finite number > 0, got -1");
  params.point_sizes.clear();
  params.tag_sizes = {{10, 0.0}};
  EXPECT_EQ(attached_point_sizes(tet_surface(), params).status().message(),
            "tag_sizes[10] must be a finite number > 0, got 0");
  Mesh bad = tet_surface();
  bad.triangles[2][1] = 8;
  EXPECT_EQ(attached_point_sizes(bad).status().message(),
            "triangles[2][1] = 8 is out of range [0, 5)");
}

TEST(AttachedSizes, NewPointSizeIsEquation15) {
  const std::vector<double> sizes = {0.5, 0.4, 0.6, kInf};
  const Triangle face{0, 1, 2};
  EXPECT_EQ(new_point_size(1.0, 1.2, sizes, face), 1.2 * 0.4);
  EXPECT_EQ(new_point_size(0.3, 1.2, sizes, face), 0.3);
  EXPECT_EQ(new_point_size(2.0, 1.0, sizes, Triangle{0, 3, 2}), 0.5);
  // A side of the surface front (two corners) and a pocket's corner list follow the same rule.
  EXPECT_EQ(new_point_size(2.0, 1.5, sizes, std::array<Index, 2>{2, 3}), 1.5 * 0.6);
  EXPECT_EQ(grown_corner_size(1.0, sizes, std::vector<Index>{3, 2, 1, 0}), 0.4);
}

}  // namespace
}  // namespace afmesh
