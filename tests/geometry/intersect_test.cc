#include "core/geometry/intersect.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <random>

#include "core/geometry/predicates.h"
#include "tests/geometry/test_support.h"

namespace afmesh {
namespace {

// The reference triangle in the plane z = 0: x >= 0, y >= 0, x + y <= 4.
const Point kA{0, 0, 0}, kB{4, 0, 0}, kC{0, 4, 0};

double above(double x) { return std::nextafter(x, 1e300); }
double below(double x) { return std::nextafter(x, -1e300); }

bool hits_reference(const Point& p, const Point& q) {
  return segment_triangle_intersect(p, q, kA, kB, kC);
}

bool crosses_reference(const Point& p, const Point& q) {
  return segment_crosses_triangle_interior(p, q, kA, kB, kC);
}

// ----- point and segment tests -----------------------------------------------------------------

TEST(PointOnSegment, EndsInteriorAndOffLine) {
  const Point p{0, 0, 0}, q{2, 4, 6};
  EXPECT_TRUE(point_on_segment(p, p, q));
  EXPECT_TRUE(point_on_segment(q, p, q));
  EXPECT_TRUE(point_on_segment(Point{1, 2, 3}, p, q));
  EXPECT_FALSE(point_on_segment(Point{3, 6, 9}, p, q));  // on the line, beyond q
  EXPECT_FALSE(point_on_segment(Point{1, 2, above(3)}, p, q));
  EXPECT_TRUE(point_on_segment(p, p, p));
  EXPECT_FALSE(point_on_segment(q, p, p));
}

TEST(SegmentsIntersect, CrossingTouchingCollinearSkewAndDegenerate) {
  const Point o{0, 0, 0}, x2{2, 0, 0}, y1{1, -1, 0}, y1up{1, 1, 0};
  EXPECT_TRUE(segments_intersect(o, x2, y1, y1up));                        // crossing
  EXPECT_TRUE(segments_intersect(o, x2, x2, Point{3, 5, 0}));              // shared end
  EXPECT_TRUE(segments_intersect(o, x2, Point{1, 0, 0}, Point{1, 3, 0}));  // T junction
  EXPECT_TRUE(segments_intersect(o, x2, Point{1, 0, 0}, Point{5, 0, 0}));  // collinear overlap
  EXPECT_TRUE(segments_intersect(o, x2, x2, Point{5, 0, 0}));              // end to end
  EXPECT_FALSE(segments_intersect(o, x2, Point{above(2), 0, 0}, Point{5, 0, 0}));
  EXPECT_FALSE(segments_intersect(o, x2, Point{1, -1, 1}, Point{1, 1, 1}));  // skew
  EXPECT_FALSE(segments_intersect(o, x2, Point{0, 1, 0}, Point{2, 1, 0}));   // parallel
  EXPECT_FALSE(
      segments_intersect(o, x2, Point{3, -1, 0}, Point{3, 1, 0}));  // line crosses, not segment
  EXPECT_TRUE(segments_intersect(o, x2, Point{1.5, 0, 0}, Point{1.5, 0, 0}));  // point on it
  EXPECT_FALSE(segments_intersect(o, x2, Point{1.5, 1e-300, 0}, Point{1.5, 1e-300, 0}));
  EXPECT_TRUE(segments_intersect(o, o, o, o));
  // Coplanar in a tilted plane (normal (1, 1, 1)): crossing at (1, 0, -1).
  EXPECT_TRUE(
      segments_intersect(Point{0, 0, 0}, Point{2, 0, -2}, Point{1, 1, -2}, Point{1, -1, 0}));
}

TEST(PointInTriangle, InsideBoundaryOutsideAndOffPlane) {
  EXPECT_TRUE(point_in_triangle(Point{1, 1, 0}, kA, kB, kC));
  EXPECT_TRUE(point_in_triangle(Point{2, 2, 0}, kA, kB, kC));  // on the hypotenuse
  EXPECT_TRUE(point_in_triangle(kC, kA, kB, kC));
  EXPECT_FALSE(point_in_triangle(Point{2, above(2), 0}, kA, kB, kC));
  EXPECT_FALSE(point_in_triangle(Point{1, 1, 0x1p-1074}, kA, kB, kC));
  // Collinear triangle: the segment from (0, 0, 0) to (4, 4, 4).
  const Point m{2, 2, 2}, e{4, 4, 4};
  EXPECT_TRUE(point_in_triangle(Point{3, 3, 3}, kA, m, e));
  EXPECT_FALSE(point_in_triangle(Point{5, 5, 5}, kA, m, e));
}

// ----- segment against triangle ----------------------------------------------------------------

TEST(SegmentTriangleIntersect, OffPlaneCases) {
  EXPECT_TRUE(hits_reference(Point{1, 1, -1}, Point{1, 1, 1}));   // through the interior
  EXPECT_TRUE(hits_reference(Point{2, 0, -1}, Point{2, 0, 1}));   // through an edge
  EXPECT_TRUE(hits_reference(Point{0, 0, -1}, Point{0, 0, 1}));   // through a vertex
  EXPECT_TRUE(hits_reference(Point{1, 1, 0}, Point{1, 1, 5}));    // end point on the face
  EXPECT_TRUE(hits_reference(Point{2, 2, 0}, Point{7, 1, 5}));    // end point on an edge
  EXPECT_FALSE(hits_reference(Point{5, 5, 0}, Point{5, 5, 3}));   // end point in plane, outside
  EXPECT_FALSE(hits_reference(Point{3, 3, -1}, Point{3, 3, 1}));  // crosses the plane outside
  EXPECT_FALSE(hits_reference(Point{1, 1, 1}, Point{2, 1, 1}));   // parallel, off the plane
  EXPECT_FALSE(hits_reference(Point{1, 1, 0x1p-1074}, Point{1, 1, 1}));  // stops one ulp short
  EXPECT_FALSE(hits_reference(Point{5, 0, 0}, Point{5, 0, 3}));          // starts on an edge's line
  // Passing the plane one subnormal step beside the vertex (0, 0, 0), and exactly through it.
  const double d = 0x1p-1060, step = 0x1p-1074;
  EXPECT_FALSE(hits_reference(Point{-d - step, -1, -1}, Point{d - step, 1, 1}));
  EXPECT_TRUE(hits_reference(Point{-d, -1, -1}, Point{d, 1, 1}));
}

TEST(SegmentTriangleIntersect, CoplanarCases) {
  EXPECT_TRUE(hits_reference(Point{-1, 1, 0}, Point{5, 1, 0}));         // across the triangle
  EXPECT_TRUE(hits_reference(Point{0.5, 0.5, 0}, Point{1, 1, 0}));      // inside
  EXPECT_FALSE(hits_reference(Point{5, 5, 0}, Point{6, 6, 0}));         // disjoint
  EXPECT_TRUE(hits_reference(Point{4, 0, 0}, Point{6, 0, 0}));          // touches a vertex
  EXPECT_TRUE(hits_reference(Point{1, 0, 0}, Point{2, 0, 0}));          // along an edge
  EXPECT_TRUE(hits_reference(Point{-1, 5, 0}, Point{5, -1, 0}));        // along the hypotenuse
  EXPECT_FALSE(hits_reference(Point{2, above(2), 0}, Point{5, 5, 0}));  // one ulp outside
  EXPECT_TRUE(hits_reference(Point{2, 2, 0}, Point{5, 5, 0}));
  EXPECT_TRUE(hits_reference(Point{1, 1, 0}, Point{1, 1, 0}));  // a point inside
  EXPECT_FALSE(hits_reference(Point{1, 1, 1e-300}, Point{1, 1, 1e-300}));
}

TEST(SegmentTriangleIntersect, DegenerateTriangle) {
  const Point a{0, 0, 0}, m{2, 2, 2}, e{4, 4, 4};
  EXPECT_TRUE(segment_triangle_intersect(Point{2, 2, 0}, Point{2, 2, 4}, a, m, e));
  EXPECT_FALSE(segment_triangle_intersect(Point{0, 4, 0}, Point{4, 0, 0}, a, m, e));
  EXPECT_TRUE(segment_triangle_intersect(Point{4, 4, 4}, Point{9, 0, 0}, a, e, m));
  EXPECT_FALSE(
      segment_triangle_intersect(Point{1, 1, 1}, Point{3, 3, 3}, a, a, Point{0.5, 0.5, 0.5}));
}

TEST(SegmentCrossesTriangleInterior, OnlyTheStrictTransversalCase) {
  EXPECT_TRUE(crosses_reference(Point{1, 1, -1}, Point{1, 1, 1}));
  EXPECT_TRUE(crosses_reference(Point{1, 1, 1}, Point{1, 1, -1}));
  EXPECT_FALSE(crosses_reference(Point{2, 0, -1}, Point{2, 0, 1}));  // edge
  EXPECT_FALSE(crosses_reference(Point{0, 0, -1}, Point{0, 0, 1}));  // vertex
  EXPECT_FALSE(crosses_reference(Point{1, 1, 0}, Point{1, 1, 5}));   // end point on the face
  EXPECT_FALSE(crosses_reference(Point{-1, 1, 0}, Point{5, 1, 0}));  // coplanar
  EXPECT_FALSE(crosses_reference(Point{3, 3, -1}, Point{3, 3, 1}));  // outside
  EXPECT_FALSE(segment_crosses_triangle_interior(Point{1, 1, -1}, Point{1, 1, 1}, kA, kB,
                                                 Point{8, 0, 0}));  // flat triangle
}

// ----- triangle against triangle ---------------------------------------------------------------

bool meets_reference(const Point& a, const Point& b, const Point& c) {
  return triangles_intersect(kA, kB, kC, a, b, c);
}

TEST(TrianglesIntersect, NonCoplanarCases) {
  EXPECT_TRUE(meets_reference(Point{1, 1, -1}, Point{2, 1, 1}, Point{1, 2, 1}));  // piercing
  EXPECT_TRUE(meets_reference(Point{1, 1, 0}, Point{1, 1, 2}, Point{2, 1, 2}));   // vertex on face
  EXPECT_TRUE(meets_reference(Point{4, 0, 0}, Point{5, 0, 1}, Point{5, 1, 1}));  // vertex on vertex
  EXPECT_TRUE(meets_reference(Point{1, 0, 0}, Point{3, 0, 0}, Point{2, 0, 2}));  // along an edge
  EXPECT_TRUE(meets_reference(Point{2, -1, 1}, Point{2, 1, -1}, Point{2, -1, -3}));  // edge on edge
  EXPECT_FALSE(meets_reference(Point{0, 0, 1}, Point{4, 0, 1}, Point{0, 4, 1}));  // parallel planes
  EXPECT_FALSE(meets_reference(Point{1, 1, 0x1p-1074}, Point{2, 1, 1}, Point{1, 2, 1}));
  EXPECT_FALSE(
      meets_reference(Point{3, 3, -1}, Point{4, 3, 1}, Point{3, 4, 1}));  // crosses plane outside
  // The other triangle's plane (x + y = -1) has the reference strictly on one side.
  EXPECT_FALSE(meets_reference(Point{2, -3, -1}, Point{2, -3, 1}, Point{-3, 2, 0}));
}

TEST(TrianglesIntersect, CoplanarCases) {
  EXPECT_TRUE(meets_reference(Point{1, 1, 0}, Point{5, 1, 0}, Point{1, 5, 0}));          // overlap
  EXPECT_TRUE(meets_reference(Point{0.5, 0.5, 0}, Point{1, 0.5, 0}, Point{0.5, 1, 0}));  // inside
  EXPECT_TRUE(meets_reference(Point{-1, -1, 0}, Point{9, -1, 0}, Point{-1, 9, 0}));      // contains
  EXPECT_FALSE(meets_reference(Point{3, 3, 0}, Point{5, 3, 0}, Point{3, 5, 0}));         // disjoint
  EXPECT_TRUE(meets_reference(Point{4, 0, 0}, Point{6, 0, 0}, Point{5, -1, 0}));  // at a vertex
  EXPECT_TRUE(meets_reference(Point{4, 0, 0}, Point{0, 4, 0}, Point{4, 4, 0}));   // shared edge
  EXPECT_FALSE(meets_reference(Point{2, above(2), 0}, Point{5, 2, 0}, Point{2, 5, 0}));  // one ulp
  EXPECT_TRUE(meets_reference(Point{2, 2, 0}, Point{5, 2, 0}, Point{2, 5, 0}));
  EXPECT_TRUE(
      meets_reference(Point{-1, 1, 0}, Point{5, 1, 0}, Point{5, 2, 0}));  // thin strip across
}

TEST(TrianglesIntersect, DegenerateTrianglesActAsSegmentsAndPoints) {
  const Point p{1, 1, -1}, q{1, 1, 1};
  EXPECT_TRUE(triangles_intersect(p, q, q, kA, kB, kC));
  EXPECT_TRUE(triangles_intersect(p, Point{1, 1, 0.5}, q, kA, kB, kC));
  EXPECT_FALSE(triangles_intersect(Point{1, 1, 1}, Point{1, 1, 2}, Point{1, 1, 3}, kA, kB, kC));
  EXPECT_TRUE(triangles_intersect(Point{1, 1, 0}, Point{1, 1, 0}, Point{1, 1, 0}, kA, kB, kC));
  EXPECT_FALSE(triangles_intersect(Point{1, 1, 1}, Point{1, 1, 1}, Point{1, 1, 1}, kA, kB, kC));
}

// Vertices drawn from a 4×4×4 integer grid, so touching, coplanar and degenerate pairs are
// frequent. The answer must not depend on the order of the triangles or of their vertices, and a
// flat triangle must behave as its segment (the segment test) or point (the point test).
TEST(TrianglesIntersect, SymmetricAndPermutationInvariantOnGridTriangles) {
  std::mt19937_64 rng(61);
  std::uniform_int_distribution<int> coordinate(0, 3);
  const auto grid_point = [&]() {
    return Point{double(coordinate(rng)), double(coordinate(rng)), double(coordinate(rng))};
  };
  int intersecting = 0;
  for (int trial = 0; trial < 4000; ++trial) {
    std::array<Point, 3> t = {grid_point(), grid_point(), grid_point()};
    std::array<Point, 3> u = {grid_point(), grid_point(), grid_point()};
    const bool base = triangles_intersect(t[0], t[1], t[2], u[0], u[1], u[2]);
    intersecting += base;
    ASSERT_EQ(triangles_intersect(u[0], u[1], u[2], t[0], t[1], t[2]), base) << "trial " << trial;
    std::array<int, 3> p = {0, 1, 2};
    do {
      ASSERT_EQ(triangles_intersect(t[p[0]], t[p[1]], t[p[2]], u[0], u[1], u[2]), base);
      ASSERT_EQ(triangles_intersect(t[0], t[1], t[2], u[p[0]], u[p[1]], u[p[2]]), base);
    } while (std::next_permutation(p.begin(), p.end()));
    ASSERT_EQ(triangles_intersect(t[0], t[1], t[1], u[0], u[1], u[2]),
              segment_triangle_intersect(t[0], t[1], u[0], u[1], u[2]));
    ASSERT_EQ(triangles_intersect(t[0], t[0], t[0], u[0], u[1], u[2]),
              point_in_triangle(t[0], u[0], u[1], u[2]));
  }
  EXPECT_GT(intersecting, 400);
  EXPECT_LT(intersecting, 3600);
}

// A point built as an exact barycentric combination (dyadic weights) lies in the triangle, so a
// triangle having it as a vertex must meet it; pushed off the plane by one ulp on the side away
// from the other vertices, it must not.
TEST(TrianglesIntersect, TouchingAtAnExactInteriorPointAndOneUlpAway) {
  std::mt19937_64 rng(62);
  for (int trial = 0; trial < 2000; ++trial) {
    const auto a = testing::to_point(testing::random_int_point(rng, 1000));
    const auto b = testing::to_point(testing::random_int_point(rng, 1000));
    const auto c = testing::to_point(testing::random_int_point(rng, 1000));
    if (collinear(a, b, c)) continue;
    Point touch;
    for (int k = 0; k < 3; ++k) touch[k] = (a[k] + b[k] + 2 * c[k]) / 4;
    ASSERT_TRUE(point_in_triangle(touch, a, b, c));
    // Two more vertices 1000 units away along an axis that leaves the plane.
    int axis = 0;
    while (axis < 2) {
      Point probe = touch;
      probe[axis] += 1000;
      if (orient3d(a, b, c, probe) != 0) break;
      ++axis;
    }
    Point far1 = touch, far2 = touch;
    far1[axis] += 1000;
    far2[axis] += 1000;
    far2[(axis + 1) % 3] += 1;
    ASSERT_NE(orient3d(a, b, c, far1), 0);
    ASSERT_TRUE(triangles_intersect(a, b, c, touch, far1, far2)) << "trial " << trial;
    Point lifted = touch;
    lifted[axis] = std::nextafter(touch[axis], far1[axis]);
    if (orient3d(a, b, c, lifted) == orient3d(a, b, c, far1) &&
        orient3d(a, b, c, far2) == orient3d(a, b, c, far1)) {
      ASSERT_FALSE(triangles_intersect(a, b, c, lifted, far1, far2)) << "trial " << trial;
    }
  }
}

// ----- point in tet ----------------------------------------------------------------------------

TEST(PointInTet, InsideBoundaryOutsideBothOrientationsAndFlat) {
  const Point a{0, 0, 0}, b{1, 0, 0}, c{0, 1, 0}, d{0, 0, 1};
  for (const bool swapped : {false, true}) {
    const auto classify = [&](const Point& p) {
      return swapped ? point_in_tet(p, b, a, c, d) : point_in_tet(p, a, b, c, d);
    };
    EXPECT_EQ(classify(Point{0.1, 0.1, 0.1}), 1);
    EXPECT_EQ(classify(Point{0.2, 0.2, 0}), 0);      // on a face
    EXPECT_EQ(classify(Point{0.25, 0.25, 0.5}), 0);  // on the slanted face
    EXPECT_EQ(classify(Point{0.5, 0, 0}), 0);        // on an edge
    EXPECT_EQ(classify(a), 0);                       // a vertex
    EXPECT_EQ(classify(Point{1, 1, 1}), -1);
    EXPECT_EQ(classify(Point{-0x1p-1074, 0.1, 0.1}), -1);
    EXPECT_EQ(classify(Point{0.25, 0.25, above(0.5)}), -1);
    EXPECT_EQ(classify(Point{0.25, 0.25, below(0.5)}), 1);
  }
  const Point e{1, 1, 0};  // a, b, c, e are coplanar: a flat tet
  EXPECT_EQ(point_in_tet(Point{0.5, 0.5, 0}, a, b, c, e), 0);
  EXPECT_EQ(point_in_tet(Point{0.9, 0.9, 0}, a, b, c, e), 0);
  EXPECT_EQ(point_in_tet(Point{0.5, 0.5, 1}, a, b, c, e), -1);
  EXPECT_EQ(point_in_tet(Point{2, 2, 0}, a, b, c, e), -1);
}

}  // namespace
}  // namespace afmesh
