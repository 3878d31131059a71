// Nearest-point queries over a fixed set of points: a kd-tree (background grid, outside points).
//
// Built once by median splits along the widest axis (std::nth_element, O(n log n)); nodes and
// the point permutation live in two arrays. A query descends to the leaf of x, then visits the
// other sides whose splitting plane is no farther than the best distance so far.
#pragma once

#include <vector>

#include "core/mesh/mesh.h"

namespace afmesh {

class PointKdTree {
 public:
  PointKdTree() = default;

  // `points`: N×3, finite.
  explicit PointKdTree(std::vector<Point> points);

  // The index of the point nearest to x (Euclidean); among equally near points the smallest
  // index, so the answer depends only on the points and x (also when x is so far from them
  // that every squared distance overflows: then the smallest index). kInvalidIndex when there
  // are none.
  Index nearest(const Point& x) const;

 private:
  static constexpr Index kLeafSize = 8;

  // A leaf (axis < 0) holds order_[begin, end); an inner node splits at order_[mid]'s
  // coordinate `split` on `axis`: [begin, mid) on the low side, [mid, end) on the high side.
  struct Node {
    Index begin = 0, end = 0;
    int axis = -1;
    double split = 0.0;
    Index low = kInvalidIndex, high = kInvalidIndex;
  };

  Index build(Index begin, Index end);
  void search(Index node, const Point& x, Index& best, double& best_d2) const;

  std::vector<Point> points_;
  std::vector<Index> order_;
  std::vector<Node> nodes_;  // nodes_[0] is the root when not empty
};

}  // namespace afmesh
