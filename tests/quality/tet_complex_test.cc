// Tests of TetComplex: face adjacency, walks around edges and points, and local replacement.
#include "core/quality/tet_complex.h"

#include <gtest/gtest.h>

#include <algorithm>

#include "core/geometry/predicates.h"
#include "core/quality/measures.h"
#include "core/quality/optimise_steps.h"
#include "tests/quality/test_meshes.h"

namespace afmesh {
namespace {

TEST(TetComplex, InteriorDiagonalOfTheSixTetCubeHasAClosedPositiveRing) {
  Mesh cube = testing::six_tet_cube();
  absl::StatusOr<TetComplex> c = TetComplex::build(cube);
  ASSERT_TRUE(c.ok()) << c.status();
  EdgeRing ring;
  ASSERT_TRUE(c->edge_ring(0, 0, 7, 12, ring));
  ASSERT_EQ(ring.tets.size(), 6u);
  ASSERT_EQ(ring.ring.size(), 6u);
  for (std::size_t i = 0; i < 6; ++i) {
    const Index r0 = ring.ring[i], r1 = ring.ring[(i + 1) % 6];
    EXPECT_GT(orient3d(cube.points[0], cube.points[7], cube.points[r0], cube.points[r1]), 0);
    const Tet& t = c->tet(ring.tets[i]);
    for (Index p : {Index{0}, Index{7}, r0, r1})
      EXPECT_NE(std::find(t.begin(), t.end(), p), t.end()) << "tet " << ring.tets[i];
  }
  // Walked the other way round from the other end: the same ring, reversed.
  EdgeRing back;
  ASSERT_TRUE(c->edge_ring(0, 7, 0, 12, back));
  EXPECT_EQ(back.ring.size(), 6u);
  // A ring larger than allowed is refused.
  EXPECT_FALSE(c->edge_ring(0, 0, 7, 5, ring));
}

TEST(TetComplex, EdgesOnTheBoundaryHaveNoClosedRing) {
  Mesh cube = testing::six_tet_cube();
  absl::StatusOr<TetComplex> c = TetComplex::build(cube);
  ASSERT_TRUE(c.ok()) << c.status();
  EdgeRing ring;
  EXPECT_FALSE(c->edge_ring(0, 0, 1, 12, ring));  // a cube edge
  EXPECT_FALSE(c->edge_ring(0, 0, 3, 12, ring));  // a face diagonal
  EXPECT_FALSE(c->edge_ring(0, 1, 7, 12, ring));  // another face diagonal
}

TEST(TetComplex, BallOfAPointHoldsExactlyItsTets) {
  Mesh cube = testing::five_tet_cube();
  absl::StatusOr<TetComplex> c = TetComplex::build(cube);
  ASSERT_TRUE(c.ok()) << c.status();
  std::vector<Index> ball;
  for (Index p = 0; p < 8; ++p) {
    c->ball(p, ball);
    std::vector<Index> expected;
    for (Index t = 0; t < 5; ++t)
      if (c->corner_of(t, p) >= 0) expected.push_back(t);
    std::sort(ball.begin(), ball.end());
    EXPECT_EQ(ball, expected) << "point " << p;
  }
}

TEST(TetComplex, FaceInThreeTetsIsAnError) {
  Mesh m = testing::tet_mesh({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {0, 0, -1}, {1, 1, 1}},
                             {{0, 1, 2, 3}, {0, 1, 2, 4}, {0, 1, 2, 5}});
  const absl::StatusOr<TetComplex> c = TetComplex::build(m);
  ASSERT_FALSE(c.ok());
  EXPECT_EQ(c.status().code(), absl::StatusCode::kInvalidArgument);
  EXPECT_NE(c.status().message().find("(0, 1, 2)"), std::string::npos) << c.status();
}

TEST(TetComplex, BadIndicesAreNamed) {
  Mesh m = testing::two_tet_mesh();
  m.tets[1][3] = 5;
  absl::StatusOr<TetComplex> c = TetComplex::build(m);
  ASSERT_FALSE(c.ok());
  EXPECT_EQ(c.status().code(), absl::StatusCode::kInvalidArgument);
  EXPECT_NE(c.status().message().find("tet 1"), std::string::npos) << c.status();
  m.tets[1][3] = m.tets[1][0];
  c = TetComplex::build(m);
  ASSERT_FALSE(c.ok());
  EXPECT_NE(c.status().message().find("tet 1 repeats point"), std::string::npos) << c.status();
}

TEST(TetComplex, ReplaceMakesA23FlipAndRefusesAMismatchedCavity) {
  Mesh two = testing::two_tet_mesh();  // tets (0 1 2 3) and (0 2 1 4) share face (0 1 2)
  absl::StatusOr<TetComplex> c = TetComplex::build(two);
  ASSERT_TRUE(c.ok()) << c.status();
  std::vector<Index> created;
  const Index old[2] = {0, 1};
  // Two tets that do not have the cavity's outside faces: refused, nothing changes.
  const Tet wrong[2] = {{1, 0, 3, 4}, {2, 1, 3, 4}};
  EXPECT_FALSE(c->replace(old, wrong, created));
  EXPECT_TRUE(created.empty());
  EXPECT_TRUE(c->alive(0) && c->alive(1));
  // The 2-3 flip around the new edge 3-4.
  const Tet fresh[3] = {{1, 0, 3, 4}, {2, 1, 3, 4}, {0, 2, 3, 4}};
  for (const Tet& k : fresh)
    ASSERT_GT(orient3d(two.points[k[0]], two.points[k[1]], two.points[k[2]], two.points[k[3]]), 0);
  ASSERT_TRUE(c->replace(old, fresh, created));
  ASSERT_EQ(created.size(), 3u);
  EXPECT_EQ(c->slots(), 3);
  // Each new tet: the two faces through the edge 3-4 are shared, the other two are boundary.
  for (Index t : created) {
    int shared = 0;
    for (int i = 0; i < 4; ++i) shared += c->neighbour(t, i) != kInvalidIndex;
    EXPECT_EQ(shared, 2) << "tet " << t;
  }
  EdgeRing ring;
  ASSERT_TRUE(c->edge_ring(created[0], 3, 4, 12, ring));
  EXPECT_EQ(ring.tets.size(), 3u);
  c->compact();
  EXPECT_EQ(two.tets.size(), 3u);
  EXPECT_EQ(two.tet_tags.size(), 3u);
}

// A tet of c with the edge (a, b), or kInvalidIndex.
Index tet_on_edge(const TetComplex& c, Index a, Index b) {
  std::vector<Index> ball;
  c.ball(a, ball);
  for (Index t : ball)
    if (c.corner_of(t, b) >= 0) return t;
  return kInvalidIndex;
}

// Around a boundary edge the fan runs from one boundary face to the other, positively.
TEST(TetComplex, FanOfABoundaryEdgeRunsBetweenItsBoundaryFaces) {
  Mesh cube = testing::six_tet_cube();
  absl::StatusOr<TetComplex> c = TetComplex::build(cube);
  ASSERT_TRUE(c.ok()) << c.status();
  const Index start = tet_on_edge(*c, 0, 3);
  ASSERT_NE(start, kInvalidIndex);
  EdgeRing fan;
  ASSERT_TRUE(c->edge_fan(start, 0, 3, 12, fan));  // the diagonal of the face z = 0
  ASSERT_EQ(fan.ring.size(), fan.tets.size() + 1);
  for (std::size_t i = 0; i < fan.tets.size(); ++i)
    EXPECT_GT(orient3d(cube.points[0], cube.points[3], cube.points[fan.ring[i]],
                       cube.points[fan.ring[i + 1]]),
              0);
  // Its ends are the face's other corners, 1 and 2, in one order or the other.
  EXPECT_EQ(std::min(fan.ring.front(), fan.ring.back()), 1);
  EXPECT_EQ(std::max(fan.ring.front(), fan.ring.back()), 2);
  // An interior edge has no fan, and too small a limit is refused.
  EXPECT_FALSE(c->edge_fan(0, 0, 7, 12, fan));
  EXPECT_FALSE(c->edge_fan(start, 0, 3, 1, fan));
}

// Edge removal on the boundary turns the diagonal of the cube's face z = 0 from 0-3 to 1-2; the
// region stays the cube, with the face's new triangles on the boundary.
TEST(TetComplex, BoundaryEdgeRemovalTurnsAFaceDiagonal) {
  Mesh cube = testing::six_tet_cube();
  absl::StatusOr<TetComplex> c = TetComplex::build(cube);
  ASSERT_TRUE(c.ok()) << c.status();
  const Index start = tet_on_edge(*c, 0, 3);
  EdgeRing fan;
  ASSERT_TRUE(c->edge_fan(start, 0, 3, 12, fan));
  TopologyChange change;
  ASSERT_TRUE(propose_boundary_edge_removal(*c, fan, [](const Tet&) { return 1.0; }, change));
  EXPECT_EQ(change.fresh.size(), 2 * (fan.tets.size() - 1));
  std::vector<Index> created;
  EXPECT_FALSE(c->replace(change.old, change.fresh, created));  // the boundary would change
  ASSERT_TRUE(c->replace(change.old, change.fresh, created, /*boundary_may_change=*/true));
  c->compact();
  double volume = 0;
  bool has_12 = false, has_03 = false;
  for (const Tet& t : cube.tets) {
    ASSERT_GT(orient3d(cube.points[t[0]], cube.points[t[1]], cube.points[t[2]], cube.points[t[3]]),
              0);
    volume += tet_signed_volume(cube.points[t[0]], cube.points[t[1]], cube.points[t[2]],
                                cube.points[t[3]]);
    const auto has = [&](Index p) { return std::find(t.begin(), t.end(), p) != t.end(); };
    has_12 = has_12 || (has(1) && has(2));
    has_03 = has_03 || (has(0) && has(3));
  }
  EXPECT_NEAR(volume, 1.0, 1e-12);
  EXPECT_TRUE(has_12);
  EXPECT_FALSE(has_03);
}

// With boundary_may_change a cavity may be refilled in part: the tet left out leaves a boundary
// face on its neighbour, and a point no tet uses any more has an empty ball.
TEST(TetComplex, ReplaceMayLeaveACavityPartlyEmpty) {
  Mesh two = testing::two_tet_mesh();  // tets (0 1 2 3) and (0 2 1 4) share face (0 1 2)
  absl::StatusOr<TetComplex> c = TetComplex::build(two);
  ASSERT_TRUE(c.ok()) << c.status();
  std::vector<Index> created;
  const Index old[1] = {1};
  EXPECT_FALSE(c->replace(old, {}, created));
  ASSERT_TRUE(c->replace(old, {}, created, /*boundary_may_change=*/true));
  EXPECT_TRUE(created.empty());
  EXPECT_FALSE(c->alive(1));
  for (int i = 0; i < 4; ++i) EXPECT_EQ(c->neighbour(0, i), kInvalidIndex);
  std::vector<Index> ball;
  c->ball(4, ball);
  EXPECT_TRUE(ball.empty());
  c->ball(0, ball);
  EXPECT_EQ(ball, std::vector<Index>{0});
}

}  // namespace
}  // namespace afmesh
