// Tests of the index-only mesh structure helpers behind validation.
#include "core/quality/mesh_topology.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <span>
#include <tuple>

#include "core/quality/measures.h"
#include "tests/quality/test_meshes.h"

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

// Every face use of the listed tets, sorted by (key, tet, corner), with the parity found by
// counting inversions: the reference for for_each_tet_face.
std::vector<FaceUse> face_uses_by_brute_force(const std::vector<Tet>& tets,
                                              const std::vector<Index>& ids) {
  std::vector<FaceUse> uses;
  for (Index id : ids) {
    for (int corner = 0; corner < 4; ++corner) {
      const Triangle face = tet_face(tets[id], corner);
      Triangle key = face;
      std::sort(key.begin(), key.end());
      const int inversions = (face[0] > face[1]) + (face[0] > face[2]) + (face[1] > face[2]);
      uses.push_back({key, id, static_cast<std::int8_t>(corner), inversions % 2 == 0});
    }
  }
  std::sort(uses.begin(), uses.end(), [](const FaceUse& x, const FaceUse& y) {
    return std::tie(x.key, x.tet, x.corner) < std::tie(y.key, y.tet, y.corner);
  });
  return uses;
}

TEST(MeshTopology, ForEachTetFaceVisitsFacesLikeABruteForceSort) {
  const Mesh grid = testing::cube_grid(4);
  std::vector<Index> ids;  // every tet but each seventh, so that some faces lose a use
  for (Index t = 0; t < static_cast<Index>(grid.tets.size()); ++t) {
    if (t % 7 != 3) ids.push_back(t);
  }
  std::vector<FaceUse> visited;
  std::size_t groups = 0;
  for_each_tet_face(grid.tets, ids, [&](std::span<const FaceUse> uses) {
    ASSERT_FALSE(uses.empty());
    for (const FaceUse& use : uses) EXPECT_EQ(use.key, uses[0].key);
    if (!visited.empty()) {
      EXPECT_LT(visited.back().key, uses[0].key);
    }
    visited.insert(visited.end(), uses.begin(), uses.end());
    ++groups;
  });
  const std::vector<FaceUse> expected = face_uses_by_brute_force(grid.tets, ids);
  ASSERT_EQ(visited.size(), expected.size());
  for (std::size_t i = 0; i < expected.size(); ++i) {
    EXPECT_EQ(visited[i].key, expected[i].key) << i;
    EXPECT_EQ(visited[i].tet, expected[i].tet) << i;
    EXPECT_EQ(visited[i].corner, expected[i].corner) << i;
    EXPECT_EQ(visited[i].even, expected[i].even) << i;
  }
  EXPECT_LT(groups, expected.size());  // interior faces come as groups of two
  const std::vector<FaceUse> sorted = sorted_face_uses(grid.tets, ids);
  ASSERT_EQ(sorted.size(), expected.size());
  for (std::size_t i = 0; i < expected.size(); ++i) {
    EXPECT_EQ(std::tie(sorted[i].key, sorted[i].tet, sorted[i].corner),
              std::tie(expected[i].key, expected[i].tet, expected[i].corner))
        << i;
  }
}

TEST(MeshTopology, ForEachTetFaceOfNoTetsVisitsNothing) {
  int visits = 0;
  for_each_tet_face({}, {}, [&](std::span<const FaceUse>) { ++visits; });
  EXPECT_EQ(visits, 0);
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

// The boundary of tet (0, 1, 2, 3), outward: every edge has two triangles traversing it in
// opposite directions.
std::vector<Triangle> tet_boundary() { return {{0, 2, 1}, {0, 1, 3}, {1, 2, 3}, {0, 3, 2}}; }

// The triangle on edge (a, b) other than t, by brute force.
Index other_on_edge(const std::vector<Triangle>& triangles, Index t, Index a, Index b) {
  for (Index u = 0; u < static_cast<Index>(triangles.size()); ++u) {
    if (u == t) continue;
    const Triangle& v = triangles[u];
    const bool has_a = v[0] == a || v[1] == a || v[2] == a;
    const bool has_b = v[0] == b || v[1] == b || v[2] == b;
    if (has_a && has_b) return u;
  }
  return kInvalidIndex;
}

TEST(MeshTopology, EdgeNeighboursOfAClosedSurfaceAgreeInOrientation) {
  const std::vector<Triangle> triangles = tet_boundary();
  const EdgeNeighbours n = triangle_edge_neighbours(triangles);
  for (Index t = 0; t < 4; ++t) {
    for (int k = 0; k < 3; ++k) {
      const Index a = triangles[t][k], b = triangles[t][(k + 1) % 3];
      EXPECT_EQ(n.across[t][k], other_on_edge(triangles, t, a, b)) << t << " " << k;
      EXPECT_FALSE(n.same_way[t][k]) << t << " " << k;
    }
  }
}

TEST(MeshTopology, EdgeNeighboursMarkAFlippedTriangleOnAllItsEdges) {
  std::vector<Triangle> triangles = tet_boundary();
  std::swap(triangles[2][1], triangles[2][2]);
  const EdgeNeighbours n = triangle_edge_neighbours(triangles);
  for (Index t = 0; t < 4; ++t) {
    for (int k = 0; k < 3; ++k) {
      const bool touches_flipped = t == 2 || n.across[t][k] == 2;
      EXPECT_EQ(n.same_way[t][k], touches_flipped) << t << " " << k;
    }
  }
}

TEST(MeshTopology, EdgeNeighboursAreInvalidOnOpenAndNonManifoldEdges) {
  // Three triangles on edge (0, 1) and one open edge elsewhere.
  const std::vector<Triangle> triangles = {{0, 1, 2}, {1, 0, 3}, {0, 1, 4}};
  const EdgeNeighbours n = triangle_edge_neighbours(triangles);
  EXPECT_EQ(n.across[0][0], kInvalidIndex);  // (0, 1): three uses
  EXPECT_EQ(n.across[0][1], kInvalidIndex);  // (1, 2): one use
  EXPECT_EQ(n.across[1][0], kInvalidIndex);
  EXPECT_EQ(n.across[2][2], kInvalidIndex);  // (4, 0): one use
}

}  // namespace
}  // namespace afmesh
