// Tests of the static AABB tree: overlap queries and overlapping pairs against brute force.
#include "core/spatial/aabb_tree.h"

#include <gtest/gtest.h>

#include <limits>
#include <random>
#include <utility>
#include <vector>

namespace afmesh {
namespace {

// n boxes with corners uniform in [0, 1]^3 and sides up to `max_side`, from a fixed seed.
std::vector<Box> random_boxes(int n, double max_side, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::vector<Box> boxes(n);
  for (Box& b : boxes) {
    for (int k = 0; k < 3; ++k) {
      b.lo[k] = unit(rng);
      b.hi[k] = b.lo[k] + max_side * unit(rng);
    }
  }
  return boxes;
}

std::vector<std::pair<Index, Index>> brute_force_pairs(const std::vector<Box>& boxes) {
  std::vector<std::pair<Index, Index>> pairs;
  for (Index i = 0; i < static_cast<Index>(boxes.size()); ++i) {
    for (Index j = i + 1; j < static_cast<Index>(boxes.size()); ++j) {
      if (boxes_overlap(boxes[i], boxes[j])) pairs.emplace_back(i, j);
    }
  }
  return pairs;
}

std::vector<Index> brute_force_query(const std::vector<Box>& boxes, const Box& q) {
  std::vector<Index> ids;
  for (Index i = 0; i < static_cast<Index>(boxes.size()); ++i) {
    if (boxes_overlap(boxes[i], q)) ids.push_back(i);
  }
  return ids;
}

TEST(AabbTree, OverlappingPairsEqualBruteForceOnRandomBoxes) {
  for (unsigned seed : {1u, 2u, 3u}) {
    for (int leaf_size : {1, 4, 16}) {
      const std::vector<Box> boxes = random_boxes(700, 0.08, seed);
      const AabbTree tree(boxes, leaf_size);
      const auto expected = brute_force_pairs(boxes);
      ASSERT_FALSE(expected.empty());
      EXPECT_EQ(tree.overlapping_pairs(), expected) << "seed " << seed << " leaf " << leaf_size;
    }
  }
}

TEST(AabbTree, PairCallbackReportsEachPairOnceWithSmallerIdFirst) {
  const std::vector<Box> boxes = random_boxes(400, 0.1, 7);
  const AabbTree tree(boxes);
  std::vector<std::pair<Index, Index>> seen;
  tree.for_each_overlapping_pair([&](Index i, Index j) { seen.emplace_back(i, j); });
  for (const auto& [i, j] : seen) EXPECT_LT(i, j);
  std::sort(seen.begin(), seen.end());
  EXPECT_EQ(std::adjacent_find(seen.begin(), seen.end()), seen.end());
  EXPECT_EQ(seen, brute_force_pairs(boxes));
}

TEST(AabbTree, QueryEqualsBruteForceOnRandomBoxes) {
  const std::vector<Box> boxes = random_boxes(1000, 0.05, 11);
  const AabbTree tree(boxes);
  const std::vector<Box> queries = random_boxes(200, 0.3, 12);
  for (const Box& q : queries) EXPECT_EQ(tree.overlapping(q), brute_force_query(boxes, q));
}

TEST(AabbTree, CallbackOrderIsDeterministic) {
  const std::vector<Box> boxes = random_boxes(500, 0.1, 5);
  const AabbTree first(boxes);
  const AabbTree second(boxes);
  std::vector<std::pair<Index, Index>> a, b;
  first.for_each_overlapping_pair([&](Index i, Index j) { a.emplace_back(i, j); });
  second.for_each_overlapping_pair([&](Index i, Index j) { b.emplace_back(i, j); });
  EXPECT_EQ(a, b);
}

TEST(AabbTree, TouchingBoxesOverlap) {
  const std::vector<Box> boxes = {
      Box{{0, 0, 0}, {1, 1, 1}},  // shares the face x = 1 with box 1
      Box{{1, 0, 0}, {2, 1, 1}},  // shares only the corner (2, 1, 1) with box 2
      Box{{2, 1, 1}, {3, 2, 2}},
      Box{{5, 5, 5}, {6, 6, 6}},  // apart from all
  };
  const AabbTree tree(boxes, 1);
  const std::vector<std::pair<Index, Index>> expected = {{0, 1}, {1, 2}};
  EXPECT_EQ(tree.overlapping_pairs(), expected);
  EXPECT_EQ(tree.overlapping(Box{{3, 2, 2}, {4, 4, 4}}), std::vector<Index>{2});
}

TEST(AabbTree, IdenticalBoxesGiveAllPairs) {
  const std::vector<Box> boxes(9, Box{{0, 0, 0}, {1, 1, 1}});
  const AabbTree tree(boxes, 2);
  EXPECT_EQ(tree.overlapping_pairs().size(), 9u * 8u / 2u);
  EXPECT_EQ(tree.overlapping_pairs(), brute_force_pairs(boxes));
}

TEST(AabbTree, DegeneratePointBoxesOverlapOnlyWhenEqual) {
  const std::vector<Box> boxes = {
      Box{{0, 0, 0}, {0, 0, 0}}, Box{{0, 0, 0}, {0, 0, 0}}, Box{{1, 0, 0}, {1, 0, 0}}};
  const AabbTree tree(boxes);
  const std::vector<std::pair<Index, Index>> expected = {{0, 1}};
  EXPECT_EQ(tree.overlapping_pairs(), expected);
}

TEST(AabbTree, EmptyBoxesAreNeverReported) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const std::vector<Box> boxes = {
      empty_box(), Box{{0, 0, 0}, {1, 1, 1}}, Box{{nan, 0, 0}, {1, 1, 1}},
      Box{{0.5, 0.5, 0.5}, {2, 2, 2}}};
  const AabbTree tree(boxes);
  EXPECT_EQ(tree.size(), 4);
  const std::vector<std::pair<Index, Index>> expected = {{1, 3}};
  EXPECT_EQ(tree.overlapping_pairs(), expected);
  EXPECT_EQ(tree.overlapping(Box{{-1, -1, -1}, {3, 3, 3}}), (std::vector<Index>{1, 3}));
  EXPECT_TRUE(tree.overlapping(empty_box()).empty());
}

TEST(AabbTree, EmptyTreeReportsNothing) {
  const AabbTree tree;
  EXPECT_EQ(tree.size(), 0);
  EXPECT_TRUE(tree.overlapping_pairs().empty());
  EXPECT_TRUE(tree.overlapping(Box{{0, 0, 0}, {1, 1, 1}}).empty());
}

TEST(AabbTree, TriangleBoxesEncloseTheirCorners) {
  const std::vector<Point> points = {{0, 0, 0}, {2, -1, 0}, {1, 3, -4}, {5, 5, 5}};
  const std::vector<Triangle> triangles = {{0, 1, 2}, {1, 3, 2}};
  const std::vector<Box> boxes = triangle_boxes(points, triangles);
  ASSERT_EQ(boxes.size(), 2u);
  EXPECT_EQ(boxes[0].lo, (Point{0, -1, -4}));
  EXPECT_EQ(boxes[0].hi, (Point{2, 3, 0}));
  EXPECT_EQ(boxes[1].lo, (Point{1, -1, -4}));
  EXPECT_EQ(boxes[1].hi, (Point{5, 5, 5}));
  Mesh mesh;
  mesh.points = points;
  mesh.triangles = triangles;
  const std::vector<Box> mesh_boxes = triangle_boxes(mesh);
  ASSERT_EQ(mesh_boxes.size(), 2u);
  EXPECT_EQ(mesh_boxes[1].lo, boxes[1].lo);
  EXPECT_EQ(mesh_boxes[1].hi, boxes[1].hi);
}

// The distance to a box's centre bounds the distance to the box from above, so it is a valid
// measure for `nearest`; the query must find the same id as a scan over all boxes.
TEST(AabbTree, NearestEqualsBruteForceOnRandomBoxes) {
  const std::vector<Box> boxes = random_boxes(1000, 0.05, 21);
  const auto centre_distance = [&](const Point& x, Index i) {
    double sum = 0.0;
    for (int k = 0; k < 3; ++k) {
      const double d = x[k] - 0.5 * (boxes[i].lo[k] + boxes[i].hi[k]);
      sum += d * d;
    }
    return sum;
  };
  for (int leaf_size : {1, 4, 16}) {
    const AabbTree tree(boxes, leaf_size);
    const std::vector<Box> queries = random_boxes(200, 0.0, 22);
    for (const Box& q : queries) {
      Index expected = 0;
      for (Index i = 1; i < static_cast<Index>(boxes.size()); ++i) {
        if (centre_distance(q.lo, i) < centre_distance(q.lo, expected)) expected = i;
      }
      const AabbTree::Nearest found =
          tree.nearest(q.lo, [&](Index i) { return centre_distance(q.lo, i); });
      EXPECT_EQ(found.id, expected);
      EXPECT_EQ(found.squared_distance, centre_distance(q.lo, expected));
    }
  }
}

TEST(AabbTree, NearestTiesGoToTheSmallerId) {
  const std::vector<Box> boxes(9, Box{{0, 0, 0}, {1, 1, 1}});
  const AabbTree tree(boxes, 2);
  const AabbTree::Nearest found = tree.nearest({0.5, 0.5, 0.5}, [](Index) { return 1.0; });
  EXPECT_EQ(found.id, 0);
  EXPECT_EQ(AabbTree().nearest({0, 0, 0}, [](Index) { return 0.0; }).id, kInvalidIndex);
}

}  // namespace
}  // namespace afmesh
