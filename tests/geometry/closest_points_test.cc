// Closest points of segments and triangles (closest_points.h) against hand-computed cases and
// a dense sampling of the shapes.
#include "core/geometry/closest_points.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

#include "core/geometry/intersect.h"
#include "core/geometry/vec.h"

namespace afmesh {
namespace {

void expect_point_near(const Point& a, const Point& b, double tolerance = 1e-12) {
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(a[k], b[k], tolerance) << "coordinate " << k;
}

TEST(ClosestPoints, PointOnTriangleInEachRegion) {
  const Point a{0, 0, 0}, b{2, 0, 0}, c{0, 2, 0};
  expect_point_near(closest_point_on_triangle({0.5, 0.5, 3}, a, b, c), {0.5, 0.5, 0});  // face
  expect_point_near(closest_point_on_triangle({-1, -1, 1}, a, b, c), a);                // vertex a
  expect_point_near(closest_point_on_triangle({5, -1, 0}, a, b, c), b);                 // vertex b
  expect_point_near(closest_point_on_triangle({-1, 5, 0}, a, b, c), c);                 // vertex c
  expect_point_near(closest_point_on_triangle({1, -3, 0}, a, b, c), {1, 0, 0});         // edge ab
  expect_point_near(closest_point_on_triangle({-3, 1, 0}, a, b, c), {0, 1, 0});         // edge ca
  expect_point_near(closest_point_on_triangle({2, 2, 1}, a, b, c), {1, 1, 0});          // edge bc
}

TEST(ClosestPoints, DegenerateTriangleIsItsSegment) {
  expect_point_near(closest_point_on_triangle({1, 1, 0}, {0, 0, 0}, {1, 0, 0}, {2, 0, 0}),
                    {1, 0, 0});
  expect_point_near(closest_point_on_segment({3, 3, 3}, {1, 1, 1}, {1, 1, 1}), {1, 1, 1});
}

TEST(ClosestPoints, SegmentsCrossingSkewAndParallel) {
  ClosestPair skew = closest_points_segments({-1, 0, 0}, {1, 0, 0}, {0, -1, 1}, {0, 1, 1});
  expect_point_near(skew.first, {0, 0, 0});
  expect_point_near(skew.second, {0, 0, 1});
  EXPECT_DOUBLE_EQ(skew.squared_distance, 1.0);
  const ClosestPair parallel = closest_points_segments({0, 0, 0}, {1, 0, 0}, {0.5, 2, 0}, {3, 2, 0});
  EXPECT_DOUBLE_EQ(parallel.squared_distance, 4.0);
  const ClosestPair ends = closest_points_segments({0, 0, 0}, {1, 0, 0}, {2, 1, 0}, {3, 5, 0});
  expect_point_near(ends.first, {1, 0, 0});
  expect_point_near(ends.second, {2, 1, 0});
}

// The distance of two disjoint triangles is never more than that of any sampled point pair,
// and a sampled pair comes close to it.
TEST(ClosestPoints, TriangleDistanceMatchesSampling) {
  std::mt19937 random(7);
  std::uniform_real_distribution<double> coordinate(-1.0, 1.0);
  const auto random_point = [&] { return Point{coordinate(random), coordinate(random), coordinate(random)}; };
  int tested = 0;
  for (int round = 0; round < 200 && tested < 60; ++round) {
    const Point a0 = random_point(), a1 = random_point(), a2 = random_point();
    const Point shift{coordinate(random) * 2, coordinate(random) * 2, 1.5};
    const Point b0 = add(random_point(), shift), b1 = add(random_point(), shift),
                b2 = add(random_point(), shift);
    if (triangles_intersect(a0, a1, a2, b0, b1, b2)) continue;
    ++tested;
    const ClosestPair pair = closest_points_triangles(a0, a1, a2, b0, b1, b2);
    const double d = std::sqrt(pair.squared_distance);
    EXPECT_NEAR(std::sqrt(squared_distance(pair.first,
                                           closest_point_on_triangle(pair.first, a0, a1, a2))),
                0.0, 1e-12);  // on the first triangle
    double sampled = 1e300;
    constexpr int kSteps = 24;
    for (int i = 0; i <= kSteps; ++i) {
      for (int j = 0; i + j <= kSteps; ++j) {
        const double u = static_cast<double>(i) / kSteps, v = static_cast<double>(j) / kSteps;
        const Point p = add(a0, add(scale(sub(a1, a0), u), scale(sub(a2, a0), v)));
        const Point q = closest_point_on_triangle(p, b0, b1, b2);
        sampled = std::min(sampled, distance(p, q));
      }
    }
    EXPECT_LE(d, sampled + 1e-12);
    EXPECT_LE(sampled - d, 0.1);  // the grid is 1/24 of a triangle of size <= 3.5
  }
  EXPECT_GE(tested, 30);
}

TEST(ClosestPoints, RayMeetsTriangleAtItsParameterOrMisses) {
  const Point a{0, 0, 1}, b{2, 0, 1}, c{0, 2, 1};
  EXPECT_NEAR(ray_triangle_parameter({0.5, 0.5, 0}, {0, 0, 1}, a, b, c), 1.0, 1e-15);
  EXPECT_NEAR(ray_triangle_parameter({0.5, 0.5, 0}, {0, 0, 4}, a, b, c), 0.25, 1e-15);
  EXPECT_NEAR(ray_triangle_parameter({0.5, 0.5, 3}, {0, 0, -1}, c, b, a), 2.0, 1e-15);
  const double miss = std::numeric_limits<double>::infinity();
  EXPECT_EQ(ray_triangle_parameter({0.5, 0.5, 2}, {0, 0, 1}, a, b, c), miss);   // behind
  EXPECT_EQ(ray_triangle_parameter({1.5, 1.5, 0}, {0, 0, 1}, a, b, c), miss);   // beside
  EXPECT_EQ(ray_triangle_parameter({0.5, 0.5, 1}, {1, 0, 0}, a, b, c), miss);   // in its plane
  EXPECT_EQ(ray_triangle_parameter({0.5, 0.5, 0}, {0, 0, 1}, a, b, {1, 0, 1}), miss);  // flat
}

}  // namespace
}  // namespace afmesh
