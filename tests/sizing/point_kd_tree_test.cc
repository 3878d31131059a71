// Nearest-point queries of the kd-tree against brute force, ties to the smallest index.
#include "core/sizing/point_kd_tree.h"

#include <gtest/gtest.h>

#include <random>
#include <vector>

#include "core/geometry/vec.h"

namespace afmesh {
namespace {

Index brute_nearest(const std::vector<Point>& points, const Point& x) {
  Index best = kInvalidIndex;
  double best_d2 = std::numeric_limits<double>::infinity();
  for (Index i = 0; i < static_cast<Index>(points.size()); ++i) {
    const double d2 = squared_distance(points[i], x);
    if (d2 < best_d2) {
      best = i;
      best_d2 = d2;
    }
  }
  return best;
}

TEST(PointKdTree, NearestMatchesBruteForce) {
  std::mt19937 rng(1);
  std::uniform_real_distribution<double> coord(-1.0, 1.0);
  std::vector<Point> points(500);
  for (Point& p : points) p = {coord(rng), coord(rng), 0.1 * coord(rng)};
  const PointKdTree tree(points);
  for (int i = 0; i < 2000; ++i) {
    const Point x{2 * coord(rng), 2 * coord(rng), coord(rng)};
    EXPECT_EQ(tree.nearest(x), brute_nearest(points, x));
  }
}

TEST(PointKdTree, TiesGoToTheSmallestIndex) {
  std::vector<Point> points;
  for (int copy = 0; copy < 3; ++copy)
    for (int i = 0; i < 4; ++i)
      for (int j = 0; j < 4; ++j) points.push_back({double(i), double(j), 0.0});
  const PointKdTree tree(points);
  EXPECT_EQ(tree.nearest({0.5, 0.5, 0.0}), 0);  // four corners at equal distance
  EXPECT_EQ(tree.nearest({2.0, 3.0, 1.0}), 2 * 4 + 3);
  EXPECT_EQ(tree.nearest({9.0, 9.0, 0.0}), 15);
  EXPECT_EQ(PointKdTree().nearest({0, 0, 0}), kInvalidIndex);
}

// fuzz_surface_request: a MeshSurface input with a point at x = -3.1e231 and a streamed
// background grid. Every squared distance to the grid's points overflowed to infinity, no point
// was nearer than the initial infinity, and nearest() returned kInvalidIndex, which
// BackgroundGrid::size_at used as an index.
TEST(Regression, Issue12PointsTooFarForSquaredDistancesStillHaveANearest) {
  std::vector<Point> points;
  for (int i = 0; i < 20; ++i) points.push_back({double(i % 3), double(i / 3), 0.0});
  const PointKdTree tree(points);
  EXPECT_EQ(tree.nearest({-3.1e231, 0.0, 0.0}), 0);
  EXPECT_EQ(tree.nearest({1e300, -1e300, 1e300}), 0);
}

}  // namespace
}  // namespace afmesh
