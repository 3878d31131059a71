#include "core/spatial/aabb_tree.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace afmesh {
namespace {

// Centre of a non-empty box; a box unbounded on both sides of an axis gets centre 0 there, so
// that every centre coordinate is a number and the median split has a strict order.
Point box_centre(const Box& box) {
  Point c;
  for (int k = 0; k < 3; ++k) {
    c[k] = 0.5 * box.lo[k] + 0.5 * box.hi[k];
    if (std::isnan(c[k])) c[k] = 0.0;
  }
  return c;
}

// Largest extent of a box over its three axes: the larger node is descended first.
double box_size(const Box& box) {
  return std::max({box.hi[0] - box.lo[0], box.hi[1] - box.lo[1], box.hi[2] - box.lo[2]});
}

// Squared distance from x to the closed box (0 inside it).
double squared_distance_to_box(const Point& x, const Box& box) {
  double sum = 0.0;
  for (int k = 0; k < 3; ++k) {
    const double gap = std::max({box.lo[k] - x[k], 0.0, x[k] - box.hi[k]});
    sum += gap * gap;
  }
  return sum;
}

}  // namespace

AabbTree::AabbTree(std::vector<Box> boxes, int leaf_size, CancelCheck* cancel)
    : boxes_(std::move(boxes)) {
  // The ids with their centres side by side: the splits below read a centre for every id at
  // every level, and through an index into a separate array each read was a cache miss (the
  // tree of a 1M-face scan took 0.6 s). Same comparisons, same moves: the same tree.
  std::vector<BuildItem> items;
  for (Index i = 0; i < size(); ++i) {
    if (is_empty(boxes_[i])) continue;
    items.push_back({box_centre(boxes_[i]), i});
  }
  if (items.empty()) return;
  nodes_.reserve(2 * items.size() / std::max(leaf_size, 1) + 1);
  build(0, static_cast<Index>(items.size()), items, std::max(leaf_size, 1), cancel);
  order_.resize(items.size());
  for (std::size_t i = 0; i < items.size(); ++i) order_[i] = items[i].id;
}

int AabbTree::widest_axis(const std::vector<BuildItem>& items, Index begin, Index end) {
  Box extent = empty_box();
  for (Index i = begin; i < end; ++i) enclose(extent, items[i].centre);
  int axis = 0;
  for (int k = 1; k < 3; ++k) {
    if (extent.hi[k] - extent.lo[k] > extent.hi[axis] - extent.lo[axis]) axis = k;
  }
  return axis;
}

// Appends the subtree over items[begin, end) in pre-order and returns its root's index.
Index AabbTree::build(Index begin, Index end, std::vector<BuildItem>& items, int leaf_size,
                      CancelCheck* cancel) {
  const Index node = static_cast<Index>(nodes_.size());
  nodes_.push_back(Node{});
  if (cancel != nullptr && cancel->due()) {  // stopped: an empty leaf
    nodes_[node] = Node{empty_box(), begin, 0, kInvalidIndex};
    return node;
  }
  if (end - begin <= leaf_size) {
    std::sort(items.begin() + begin, items.begin() + end,
              [](const BuildItem& a, const BuildItem& b) { return a.id < b.id; });
    Box box = empty_box();
    for (Index i = begin; i < end; ++i) enclose(box, boxes_[items[i].id]);
    nodes_[node] = Node{box, begin, end - begin, kInvalidIndex};
    return node;
  }
  const int axis = widest_axis(items, begin, end);
  const Index mid = begin + (end - begin) / 2;
  std::nth_element(items.begin() + begin, items.begin() + mid, items.begin() + end,
                   [axis](const BuildItem& a, const BuildItem& b) {
                     if (a.centre[axis] != b.centre[axis]) return a.centre[axis] < b.centre[axis];
                     return a.id < b.id;
                   });
  build(begin, mid, items, leaf_size, cancel);
  const Index right = build(mid, end, items, leaf_size, cancel);
  nodes_[node].right = right;
  nodes_[node].box = nodes_[node + 1].box;  // inner boxes from the children, bottom-up
  enclose(nodes_[node].box, nodes_[right].box);
  return node;
}

void AabbTree::for_each_overlap(const Box& query_box, absl::FunctionRef<void(Index)> visit) const {
  if (nodes_.empty() || is_empty(query_box)) return;
  query(0, query_box, visit);
}

void AabbTree::query(Index node, const Box& q, absl::FunctionRef<void(Index)> visit) const {
  const Node& n = nodes_[node];
  if (!boxes_overlap(n.box, q)) return;
  if (n.count > 0) {
    for (Index i = n.first; i < n.first + n.count; ++i) {
      if (boxes_overlap(boxes_[order_[i]], q)) visit(order_[i]);
    }
    return;
  }
  query(node + 1, q, visit);
  query(n.right, q, visit);
}

std::vector<Index> AabbTree::overlapping(const Box& query_box) const {
  std::vector<Index> ids;
  for_each_overlap(query_box, [&](Index i) { ids.push_back(i); });
  std::sort(ids.begin(), ids.end());
  return ids;
}

void AabbTree::for_each_overlapping_pair(absl::FunctionRef<void(Index, Index)> visit,
                                         CancelCheck* stop) const {
  if (nodes_.empty()) return;
  pairs_within(0, visit, stop);
}

// Pairs with both boxes in the subtree of `node`: those within each child and those across.
void AabbTree::pairs_within(Index node, absl::FunctionRef<void(Index, Index)> visit,
                            CancelCheck* stop) const {
  const Node& n = nodes_[node];
  if (stop != nullptr && stop->stopped()) return;
  if (n.count > 0) {
    if (stop != nullptr && stop->due()) return;
    for (Index i = n.first; i < n.first + n.count; ++i) {
      for (Index j = i + 1; j < n.first + n.count; ++j) {
        if (boxes_overlap(boxes_[order_[i]], boxes_[order_[j]])) {
          visit(std::min(order_[i], order_[j]), std::max(order_[i], order_[j]));
        }
      }
    }
    return;
  }
  pairs_within(node + 1, visit, stop);
  pairs_within(n.right, visit, stop);
  pairs_across(node + 1, n.right, visit, stop);
}

// Pairs with one box under node a and the other under node b (disjoint subtrees). The larger
// inner node is split first, which keeps the two boxes compared of similar size.
void AabbTree::pairs_across(Index a, Index b, absl::FunctionRef<void(Index, Index)> visit,
                            CancelCheck* stop) const {
  const Node& na = nodes_[a];
  const Node& nb = nodes_[b];
  if (stop != nullptr && stop->stopped()) return;
  if (!boxes_overlap(na.box, nb.box)) return;
  if (na.count > 0 && nb.count > 0) {
    if (stop != nullptr && stop->due()) return;
    for (Index i = na.first; i < na.first + na.count; ++i) {
      for (Index j = nb.first; j < nb.first + nb.count; ++j) {
        if (boxes_overlap(boxes_[order_[i]], boxes_[order_[j]])) {
          visit(std::min(order_[i], order_[j]), std::max(order_[i], order_[j]));
        }
      }
    }
    return;
  }
  const bool split_a = nb.count > 0 || (na.count == 0 && box_size(na.box) >= box_size(nb.box));
  if (split_a) {
    pairs_across(a + 1, b, visit, stop);
    pairs_across(na.right, b, visit, stop);
  } else {
    pairs_across(a, b + 1, visit, stop);
    pairs_across(a, nb.right, visit, stop);
  }
}

std::vector<std::pair<Index, Index>> AabbTree::overlapping_pairs() const {
  std::vector<std::pair<Index, Index>> pairs;
  for_each_overlapping_pair([&](Index i, Index j) { pairs.emplace_back(i, j); });
  std::sort(pairs.begin(), pairs.end());
  return pairs;
}

AabbTree::Nearest AabbTree::nearest(const Point& x,
                                    absl::FunctionRef<double(Index)> squared_distance) const {
  Nearest best{kInvalidIndex, std::numeric_limits<double>::infinity()};
  if (!nodes_.empty()) nearest_in(0, x, squared_distance, best);
  return best;
}

// Branch and bound below `node`. Pruning is strict (a subtree exactly as far as the best is still
// visited), so that ties go to the smaller id whatever the order of descent.
void AabbTree::nearest_in(Index node, const Point& x,
                          absl::FunctionRef<double(Index)> squared_distance,
                          Nearest& best) const {
  const Node& n = nodes_[node];
  if (n.count > 0) {
    for (Index i = n.first; i < n.first + n.count; ++i) {
      const Index id = order_[i];
      if (squared_distance_to_box(x, boxes_[id]) > best.squared_distance) continue;
      const double d = squared_distance(id);
      if (d < best.squared_distance || (d == best.squared_distance && id < best.id)) {
        best = {id, d};
      }
    }
    return;
  }
  const double left = squared_distance_to_box(x, nodes_[node + 1].box);
  const double right = squared_distance_to_box(x, nodes_[n.right].box);
  const Index first = left <= right ? node + 1 : n.right;
  const Index second = left <= right ? n.right : node + 1;
  if (std::min(left, right) <= best.squared_distance) nearest_in(first, x, squared_distance, best);
  if (std::max(left, right) <= best.squared_distance) {
    nearest_in(second, x, squared_distance, best);
  }
}

}  // namespace afmesh
