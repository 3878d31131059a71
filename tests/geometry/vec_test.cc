#include "core/geometry/vec.h"

#include <gtest/gtest.h>

namespace afmesh {
namespace {

TEST(Vec, BasicOperations) {
  const Point a{1, 2, 3}, b{4, 5, 6};
  EXPECT_EQ(add(a, b), (Point{5, 7, 9}));
  EXPECT_EQ(sub(b, a), (Point{3, 3, 3}));
  EXPECT_EQ(scale(a, 2.0), (Point{2, 4, 6}));
  EXPECT_DOUBLE_EQ(dot(a, b), 32.0);
  EXPECT_EQ(cross(Point{1, 0, 0}, Point{0, 1, 0}), (Point{0, 0, 1}));
  EXPECT_EQ(cross(a, b), (Point{-3, 6, -3}));
  EXPECT_DOUBLE_EQ(squared_norm(a), 14.0);
  EXPECT_DOUBLE_EQ(norm(Point{3, 4, 0}), 5.0);
  EXPECT_DOUBLE_EQ(distance(a, b), std::sqrt(27.0));
  EXPECT_DOUBLE_EQ(squared_distance(a, b), 27.0);
  EXPECT_EQ(lerp(a, b, 0.0), a);
  EXPECT_EQ(lerp(a, b, 1.0), b);
  EXPECT_EQ(lerp(a, b, 0.5), (Point{2.5, 3.5, 4.5}));
}

}  // namespace
}  // namespace afmesh
