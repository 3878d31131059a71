// Tests of the index-only mesh structure helpers behind validation.
#include "core/quality/mesh_topology.h"

#include <gtest/gtest.h>

#include "core/quality/measures.h"

namespace afmesh {
namespace {

TEST(MeshTopology, CanonicalRotationKeepsOrientation) {
  EXPECT_EQ(canonical_rotation({5, 2, 9}), (Triangle{2, 9, 5}));
  EXPECT_EQ(canonical_rotation({9, 5, 2}), (Triangle{2, 9, 5}));
  EXPECT_EQ(canonical_rotation({2, 9, 5}), (Triangle{2, 9, 5}));
  EXPECT_EQ(canonical_rotation({2, 5, 9}), (Triangle{2, 5, 9}));
  EXPECT_EQ(sorted_triangle({9, 2, 5}), (Triangle{2, 5, 9}));
}

// Each face of a positive tet, as (a, b, c), has its normal (b-a)x(c-a) pointing away from the
// opposite corner: the tet (a, b, c, corner) is negative.
TEST(MeshTopology, TetFacesPointOutOfAPositiveTet) {
  const std::vector<Point> points = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0.2, 0.3, 1}};
  const Tet tet = {0, 1, 2, 3};
  ASSERT_GT(tet_signed_volume(points[0], points[1], points[2], points[3]), 0.0);
  for (int corner = 0; corner < 4; ++corner) {
    const Triangle f = tet_face(tet, corner);
    EXPECT_LT(tet_signed_volume(points[f[0]], points[f[1]], points[f[2]], points[tet[corner]]),
              0.0)
        << corner;
  }
}

TEST(MeshTopology, FaceUsesOfTwoAdjacentTetsHaveOppositeParity) {
  const std::vector<Tet> tets = {{0, 1, 2, 3}, {0, 2, 1, 4}};
  const std::vector<FaceUse> uses = sorted_face_uses(tets, {0, 1});
  ASSERT_EQ(uses.size(), 8u);
  EXPECT_EQ(uses[0].key, (Triangle{0, 1, 2}));
  EXPECT_EQ(uses[1].key, (Triangle{0, 1, 2}));
  EXPECT_NE(uses[0].even, uses[1].even);
  for (std::size_t i = 1; i < uses.size(); ++i) EXPECT_LE(uses[i - 1].key, uses[i].key);
}

TEST(MeshTopology, ClosedOrientedSurfaceHasNoDefects) {
  const std::vector<Triangle> tet_surface = {{1, 2, 3}, {0, 3, 2}, {0, 1, 3}, {0, 2, 1}};
  const TriangleTopology t = analyze_triangle_topology(tet_surface);
  EXPECT_EQ(t.edge_count, 6);
  EXPECT_TRUE(t.open_edges.empty());
  EXPECT_TRUE(t.nonmanifold_edges.empty());
  EXPECT_TRUE(t.misoriented_edges.empty());
  EXPECT_TRUE(t.nonmanifold_vertices.empty());
}

// Two triangle fans sharing vertex 0 only: a bow tie.
TEST(MeshTopology, BowTieVertexHasTwoFans) {
  const std::vector<Triangle> bow_tie = {{0, 1, 2}, {0, 3, 4}};
  const TriangleTopology t = analyze_triangle_topology(bow_tie);
  ASSERT_EQ(t.nonmanifold_vertices.size(), 1u);
  EXPECT_EQ(t.nonmanifold_vertices[0].vertex, 0);
  EXPECT_EQ(t.nonmanifold_vertices[0].fan_count, 2);
  EXPECT_EQ(t.nonmanifold_vertices[0].triangles, (std::vector<Index>{0, 1}));
  EXPECT_EQ(t.open_edges.size(), 6u);
}

TEST(MeshTopology, EdgeGroupsClassifyUseCountsAndDirections) {
  // Edge (0,1): triangles 0 and 1 both run 0->1 (misoriented); edge (2,3): three triangles.
  const std::vector<Triangle> triangles = {{0, 1, 2}, {0, 1, 3}, {2, 3, 4}, {3, 2, 5}, {2, 3, 6}};
  const TriangleTopology t = analyze_triangle_topology(triangles);
  ASSERT_EQ(t.misoriented_edges.size(), 1u);
  EXPECT_EQ(t.misoriented_edges[0].a, 0);
  EXPECT_EQ(t.misoriented_edges[0].b, 1);
  EXPECT_EQ(t.misoriented_edges[0].triangles, (std::vector<Index>{0, 1}));
  ASSERT_EQ(t.nonmanifold_edges.size(), 1u);
  EXPECT_EQ(t.nonmanifold_edges[0].triangles, (std::vector<Index>{2, 3, 4}));
}

}  // namespace
}  // namespace afmesh
