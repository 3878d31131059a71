#include "core/sizing/point_kd_tree.h"

#include <algorithm>
#include <limits>
#include <numeric>
#include <utility>

#include "core/geometry/vec.h"

namespace afmesh {

PointKdTree::PointKdTree(std::vector<Point> points) : points_(std::move(points)) {
  order_.resize(points_.size());
  std::iota(order_.begin(), order_.end(), Index{0});
  if (!points_.empty()) build(0, static_cast<Index>(order_.size()));
}

Index PointKdTree::build(Index begin, Index end) {
  const Index node = static_cast<Index>(nodes_.size());
  nodes_.push_back(Node{begin, end});
  if (end - begin <= kLeafSize) return node;
  Point lo = points_[order_[begin]], hi = lo;
  for (Index i = begin; i < end; ++i) {
    for (int k = 0; k < 3; ++k) {
      lo[k] = std::min(lo[k], points_[order_[i]][k]);
      hi[k] = std::max(hi[k], points_[order_[i]][k]);
    }
  }
  int axis = 0;
  for (int k = 1; k < 3; ++k) {
    if (hi[k] - lo[k] > hi[axis] - lo[axis]) axis = k;
  }
  const Index mid = begin + (end - begin) / 2;
  std::nth_element(order_.begin() + begin, order_.begin() + mid, order_.begin() + end,
                   [&](Index a, Index b) {
                     return std::pair(points_[a][axis], a) < std::pair(points_[b][axis], b);
                   });
  const double split = points_[order_[mid]][axis];
  const Index low = build(begin, mid);
  const Index high = build(mid, end);
  nodes_[node].axis = axis;
  nodes_[node].split = split;
  nodes_[node].low = low;
  nodes_[node].high = high;
  return node;
}

// Points on the low side have coordinate <= split and those on the high side >= split, so the
// far side holds nothing nearer than the plane distance; equal distances are still visited to
// find the smallest index.
void PointKdTree::search(Index node_id, const Point& x, Index& best, double& best_d2) const {
  const Node& node = nodes_[node_id];
  if (node.axis < 0) {
    for (Index i = node.begin; i < node.end; ++i) {
      const Index p = order_[i];
      const double d2 = squared_distance(points_[p], x);
      // The first point seen is taken whatever its distance: one so far away that d2
      // overflows to infinity is still the nearest when no point is nearer.
      if (best == kInvalidIndex || d2 < best_d2 || (d2 == best_d2 && p < best)) {
        best = p;
        best_d2 = d2;
      }
    }
    return;
  }
  const double offset = x[node.axis] - node.split;
  const Index near = offset < 0.0 ? node.low : node.high;
  const Index far = offset < 0.0 ? node.high : node.low;
  search(near, x, best, best_d2);
  if (offset * offset <= best_d2) search(far, x, best, best_d2);
}

Index PointKdTree::nearest(const Point& x) const {
  if (nodes_.empty()) return kInvalidIndex;
  Index best = kInvalidIndex;
  double best_d2 = std::numeric_limits<double>::infinity();
  search(0, x, best, best_d2);
  return best;
}

}  // namespace afmesh
