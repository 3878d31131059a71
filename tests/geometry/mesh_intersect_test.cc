#include <gtest/gtest.h>

#include <array>
#include <random>
#include <vector>

#include "core/geometry/intersect.h"
#include "core/geometry/predicates.h"

namespace afmesh {
namespace {

// Fixture points: a reference triangle (0, 1, 2) in z = 0 (x, y >= 0, x + y <= 4), and the tet
// (0, 1, 2, 3) above it.
class MeshIntersect : public ::testing::Test {
 protected:
  Index add(const Point& p) {
    points_.push_back(p);
    return Index(points_.size() - 1);
  }

  bool improper(const Triangle& t, const Triangle& u) const {
    return triangles_intersect_improperly(points_, t, u);
  }

  std::vector<Point> points_ = {{0, 0, 0}, {4, 0, 0}, {0, 4, 0}, {0, 0, 4}};
  const Triangle reference_ = {0, 1, 2};
  const Tet tet_ = {0, 1, 2, 3};
};

// ----- triangles_intersect_improperly ----------------------------------------------------------

TEST_F(MeshIntersect, NoSharedVertexAnyContactIsImproper) {
  const Index p = add({1, 1, 0}), q = add({1, 1, 2}), r = add({2, 1, 2});
  EXPECT_TRUE(improper(reference_, {p, q, r}));  // a vertex touches the face
  const Index s = add({1, 1, 1}), t = add({2, 1, 1}), u = add({1, 2, 1});
  EXPECT_FALSE(improper(reference_, {s, t, u}));
  // A distinct vertex at the location of vertex 0 counts as contact.
  const Index twin = add({0, 0, 0}), w = add({-1, -1, -1}), x = add({-1, -2, -1});
  EXPECT_TRUE(improper(reference_, {twin, w, x}));
}

TEST_F(MeshIntersect, OneSharedVertex) {
  // A fan around vertex 0, touching only there.
  const Index f1 = add({0, -1, 1}), f2 = add({0, 0, -4});
  EXPECT_FALSE(improper(reference_, {0, f1, f2}));
  // The other triangle's opposite edge pierces the face.
  const Index below = add({1, 1, -1}), top = add({1, 1, 1});
  EXPECT_TRUE(improper(reference_, {0, below, top}));
  // Coplanar, inside the reference's corner wedge.
  const Index w1 = add({2, 1, 0}), w2 = add({1, 2, 0});
  EXPECT_TRUE(improper(reference_, {0, w1, w2}));
  // Coplanar, in the opposite wedge: touching only at 0.
  const Index o1 = add({-1, 0, 0}), o2 = add({0, -1, 0});
  EXPECT_FALSE(improper(reference_, {0, o1, o2}));
  // Coplanar and sharing the direction of edge 0-1 from the other side: a common segment.
  const Index c1 = add({2, 0, 0}), c2 = add({1, -1, 0});
  EXPECT_TRUE(improper(reference_, {0, c1, c2}));
  // In another plane, along edge 0-1 (same direction): overlap on a segment.
  const Index s1 = add({2, 0, 0}), s2 = add({2, 0, 3});
  EXPECT_TRUE(improper(reference_, {0, s1, s2}));
  // Along the edge line in the opposite direction: only 0.
  const Index r1 = add({-2, 0, 0}), r2 = add({-2, 0, 3});
  EXPECT_FALSE(improper(reference_, {0, r1, r2}));
  // A plane through 0 that cuts the reference's plane along a line outside the reference.
  const Index n1 = add({-1, -1, -1}), n2 = add({-1, -1, 1});
  EXPECT_FALSE(improper(reference_, {0, n1, n2}));
}

TEST_F(MeshIntersect, OneSharedVertexWithFlatTriangles) {
  // Flat triangle through 0 (0 between its other vertices) crossing the face: improper.
  const Index in = add({1, 1, 0}), out = add({-1, -1, 0});
  EXPECT_TRUE(improper(reference_, {0, in, out}));
  // Flat triangle along a line leaving the reference at 0.
  const Index away1 = add({-1, -1, 0}), away2 = add({-2, -2, 0});
  EXPECT_FALSE(improper(reference_, {0, away1, away2}));
  // Flat triangle along a line through 0, off the plane.
  const Index up = add({1, 1, 1}), down = add({-1, -1, -1});
  EXPECT_FALSE(improper(reference_, {0, up, down}));
  // Both flat, along one line from 0 in the same direction: overlap.
  const Index a1 = add({1, 0, 0}), a2 = add({3, 0, 0});
  const Index b1 = add({2, 0, 0}), b2 = add({-5, 0, 0});
  EXPECT_TRUE(improper({0, a1, a2}, {0, b1, b2}));
  // Both flat, on one line but in opposite directions from 0.
  const Index c1 = add({-1, 0, 0}), c2 = add({-3, 0, 0});
  EXPECT_FALSE(improper({0, a1, a2}, {0, c1, c2}));
}

TEST_F(MeshIntersect, SharedEdge) {
  const Index across = add({4, 4, 0});
  EXPECT_FALSE(improper(reference_, {1, across, 2}));  // coplanar neighbours
  EXPECT_FALSE(improper(reference_, {0, 1, 3}));       // dihedral
  const Index folded = add({1, 1, 0});
  EXPECT_TRUE(improper(reference_, {0, 1, folded}));  // folded onto the reference
  const Index beyond = add({9, 9, 0});
  EXPECT_FALSE(improper(reference_, {1, 2, beyond}));  // coplanar, other side of 1-2
  const Index other_side_far = add({-1, 9, 0});
  EXPECT_FALSE(improper(reference_, {0, 2, other_side_far}));  // x < 0 side of 0-2
  const Index overlap_far = add({9, 1, 0});
  EXPECT_TRUE(improper(reference_, {0, 1, overlap_far}));  // same side of 0-1, overlapping
}

TEST_F(MeshIntersect, SharedEdgeWithFlatTriangles) {
  const Index mid = add({2, 0, 0});
  EXPECT_FALSE(improper(reference_, {0, 1, mid}));  // flat triangle equal to the edge
  const Index past = add({6, 0, 0});
  EXPECT_FALSE(improper(reference_, {0, 1, past}));  // extends the edge outside the reference
  const Index past_other = add({7, 0, 0});
  EXPECT_TRUE(improper({0, 1, past}, {0, 1, past_other}));  // two flat extensions overlap
  const Index before = add({-3, 0, 0});
  EXPECT_FALSE(improper({0, 1, past}, {0, 1, before}));  // extensions on opposite ends
}

TEST_F(MeshIntersect, IdenticalTrianglesAreImproper) {
  EXPECT_TRUE(improper(reference_, {2, 0, 1}));
  EXPECT_TRUE(improper(reference_, {1, 0, 2}));
}

// Random index triangles over a small grid of points (many shared vertices, touching and
// coplanar pairs): the answer must not depend on the order of the two triangles, on rotations or
// reflections of their index triples, and with no shared index it must equal triangles_intersect.
TEST_F(MeshIntersect, ImproperIsSymmetricAndOrderInvariantOnRandomGridMeshes) {
  std::mt19937_64 rng(71);
  std::uniform_int_distribution<int> coordinate(0, 2);
  points_.clear();
  for (int i = 0; i < 12; ++i) {
    add({double(coordinate(rng)), double(coordinate(rng)), double(coordinate(rng))});
  }
  std::uniform_int_distribution<Index> index(0, 11);
  const auto random_triangle = [&]() {
    Triangle t;
    do {
      t = {index(rng), index(rng), index(rng)};
    } while (t[0] == t[1] || t[1] == t[2] || t[0] == t[2]);
    return t;
  };
  int improper_count = 0;
  for (int trial = 0; trial < 4000; ++trial) {
    const Triangle t = random_triangle(), u = random_triangle();
    const bool base = improper(t, u);
    improper_count += base;
    ASSERT_EQ(improper(u, t), base) << "trial " << trial;
    ASSERT_EQ(improper({t[1], t[2], t[0]}, u), base) << "trial " << trial;
    ASSERT_EQ(improper({t[2], t[1], t[0]}, {u[2], u[0], u[1]}), base) << "trial " << trial;
    int shared = 0;
    for (const Index i : t) shared += i == u[0] || i == u[1] || i == u[2];
    if (shared == 0) {
      ASSERT_EQ(base, triangles_intersect(points_[t[0]], points_[t[1]], points_[t[2]],
                                          points_[u[0]], points_[u[1]], points_[u[2]]));
    }
  }
  EXPECT_GT(improper_count, 200);
  EXPECT_LT(improper_count, 3800);
}

// ----- segment_triangle_intersect_improperly ---------------------------------------------------

TEST_F(MeshIntersect, SegmentAgainstTriangle) {
  const auto improper_edge = [&](Index p, Index q, const Triangle& t) {
    return segment_triangle_intersect_improperly(points_, p, q, t);
  };
  EXPECT_FALSE(improper_edge(0, 1, reference_));  // an edge of the triangle
  EXPECT_FALSE(improper_edge(1, 0, reference_));
  const Index away = add({-1, -1, -1});
  EXPECT_FALSE(improper_edge(0, away, reference_));
  const Index inside = add({1, 1, 0});
  EXPECT_TRUE(improper_edge(0, inside, reference_));  // into the face from a shared vertex
  EXPECT_TRUE(improper_edge(inside, 0, reference_));
  const Index along = add({2, 0, 0}), back = add({-2, 0, 0});
  EXPECT_TRUE(improper_edge(0, along, reference_));  // along an edge
  EXPECT_FALSE(improper_edge(0, back, reference_));
  const Index across = add({3, 3, 0});
  EXPECT_TRUE(improper_edge(0, across, reference_));  // across the face to beyond edge 1-2
  const Index below = add({1, 1, -1}), above = add({1, 1, 1});
  EXPECT_TRUE(improper_edge(below, above, reference_));  // no shared vertex, crossing
  const Index high = add({1, 1, 2});
  EXPECT_FALSE(improper_edge(above, high, reference_));
  // Flat triangle (0, 1, mid): from 0 along it, and away from it.
  const Index mid = add({2, 0, 0}), sideways = add({0, 1, 0}), short_along = add({1, 0, 0});
  EXPECT_TRUE(improper_edge(0, short_along, {0, 1, mid}));
  EXPECT_FALSE(improper_edge(0, sideways, {0, 1, mid}));
}

// ----- tet_triangle_intersect_improperly -------------------------------------------------------

TEST_F(MeshIntersect, TetAgainstTriangle) {
  const auto improper_tet = [&](const Triangle& t) {
    return tet_triangle_intersect_improperly(points_, tet_, t);
  };
  EXPECT_FALSE(improper_tet({0, 1, 2}));  // a face of the tet
  EXPECT_FALSE(improper_tet({3, 2, 1}));
  const Index outside_edge = add({2, -3, 1});
  EXPECT_FALSE(improper_tet({0, 1, outside_edge}));  // shares edge 0-1, outside
  const Index inside = add({1, 1, 1});
  EXPECT_TRUE(improper_tet({0, 1, inside}));  // shares edge 0-1, folds into the tet
  const Index o1 = add({-1, -1, 0}), o2 = add({-1, 0, -1});
  EXPECT_FALSE(improper_tet({0, o1, o2}));  // shares vertex 0, outside
  const Index low = add({1, 1, -1}), high = add({1, 1, 3});
  EXPECT_TRUE(improper_tet({0, low, high}));  // shares vertex 0, opposite edge through the tet
  const Index f1 = add({10, 10, 10}), f2 = add({11, 10, 10}), f3 = add({10, 11, 10});
  EXPECT_FALSE(improper_tet({f1, f2, f3}));  // far away
  const Index b1 = add({-10, -10, 1}), b2 = add({20, -10, 1}), b3 = add({-10, 20, 1});
  EXPECT_TRUE(improper_tet({b1, b2, b3}));  // a big triangle slicing the tet
  const Index i1 = add({0.5, 0.5, 0.5}), i2 = add({1, 0.5, 0.5}), i3 = add({0.5, 1, 0.5});
  EXPECT_TRUE(improper_tet({i1, i2, i3}));  // entirely inside
  const Index t1 = add({1, 1, 0}), t2 = add({2, 1, -1}), t3 = add({1, 2, -1});
  EXPECT_TRUE(improper_tet({t1, t2, t3}));  // touches the bottom face at one point
  const Index p1 = add({-2, 1, 0}), p2 = add({-1, -2, 0});
  EXPECT_FALSE(improper_tet({0, p1, p2}));  // in the bottom face's plane, outside, at vertex 0
  const Index q1 = add({2, 0.5, 0});
  EXPECT_TRUE(improper_tet({0, t1, q1}));  // in the bottom face's plane, overlapping it
  const Index e1 = add({4, 4, 4});
  EXPECT_FALSE(improper_tet({1, 2, e1}));  // shares edge 1-2, outside the slanted face
  const Index flat = add({1, 1, 0});
  EXPECT_TRUE(tet_triangle_intersect_improperly(points_, {0, 1, 2, flat}, {f1, f2, f3}));
}

// Tets and triangles on a small integer grid (touching and coplanar cases are frequent). Without
// shared vertices the closed sets meet iff a triangle vertex lies in the closed tet, a triangle
// edge meets a tet face, or a tet edge meets the triangle: an independent decomposition that must
// agree. The answer must also not depend on the tet's or the triangle's vertex order.
TEST_F(MeshIntersect, TetTriangleAgreesWithEdgeDecompositionOnGridShapes) {
  std::mt19937_64 rng(72);
  std::uniform_int_distribution<int> coordinate(0, 3);
  points_.clear();
  for (int i = 0; i < 7; ++i) {
    add({double(coordinate(rng)), double(coordinate(rng)), double(coordinate(rng))});
  }
  const auto at = [&](Index i) -> const Point& { return points_[i]; };
  int checked = 0;
  int intersecting = 0;
  while (checked < 3000) {
    for (Index i = 0; i < 7; ++i) {
      points_[i] = {double(coordinate(rng)), double(coordinate(rng)), double(coordinate(rng))};
    }
    const Tet tet = {0, 1, 2, 3};
    const Triangle t = {4, 5, 6};
    if (orient3d(at(0), at(1), at(2), at(3)) == 0) continue;
    ++checked;
    bool meets = false;
    for (const Index v : t) meets = meets || point_in_tet(at(v), at(0), at(1), at(2), at(3)) >= 0;
    const std::array<std::array<Index, 2>, 6> tet_edges = {
        {{0, 1}, {0, 2}, {0, 3}, {1, 2}, {1, 3}, {2, 3}}};
    for (const auto& [p, q] : tet_edges) {
      meets = meets || segment_triangle_intersect(at(p), at(q), at(4), at(5), at(6));
    }
    const std::array<Triangle, 4> faces = {Triangle{1, 2, 3}, Triangle{0, 2, 3}, Triangle{0, 1, 3},
                                           Triangle{0, 1, 2}};
    const std::array<std::array<Index, 2>, 3> triangle_edges = {{{4, 5}, {5, 6}, {6, 4}}};
    for (const Triangle& f : faces) {
      for (const auto& [p, q] : triangle_edges) {
        meets = meets || segment_triangle_intersect(at(p), at(q), at(f[0]), at(f[1]), at(f[2]));
      }
    }
    intersecting += meets;
    ASSERT_EQ(tet_triangle_intersect_improperly(points_, tet, t), meets) << "case " << checked;
    ASSERT_EQ(tet_triangle_intersect_improperly(points_, {1, 0, 2, 3}, {5, 6, 4}), meets);
    ASSERT_EQ(tet_triangle_intersect_improperly(points_, {3, 2, 0, 1}, {6, 5, 4}), meets);
  }
  EXPECT_GT(intersecting, 300);
  EXPECT_LT(intersecting, 2700);
}

}  // namespace
}  // namespace afmesh
