// A static bounding-volume hierarchy over axis-aligned boxes.
//
// Built once from a fixed set of boxes, then queried for
//  - all boxes overlapping a query box (`for_each_overlap`, `overlapping`), and
//  - all overlapping pairs within the set (`for_each_overlapping_pair`, `overlapping_pairs`),
//    the broad phase of a self-intersection test, and
//  - the box holding the object nearest a point (`nearest`), by branch and bound.
//
// Layout: nodes live in one array in depth-first (pre-)order, the left child of an inner node
// directly after it and the right child at a stored index; leaves hold a range of a permutation
// array of box ids. No pointers, no per-node allocation.
//
// Construction is top-down: each node splits its boxes at the median of their centres along the
// longest axis of the centres' extent (std::nth_element, so O(n) per level and O(n log n) in
// all). Ties are broken by box id and leaf contents are sorted, so the tree, and hence every
// callback order below, depends only on the input boxes. The pair search descends both subtrees
// together and prunes disjoint node pairs, costing about O(n log n + k) for k reported pairs on
// meshes with boxes of bounded overlap.
//
// Boxes are closed (box.h): touching boxes overlap. Empty boxes (lo > hi on some axis, or NaN
// coordinates) overlap nothing and are never reported.
#pragma once

#include <cstdint>
#include <utility>
#include <vector>

#include "absl/functional/function_ref.h"
#include "core/common/progress.h"
#include "core/mesh/mesh.h"
#include "core/spatial/box.h"

namespace afmesh {

class AabbTree {
 public:
  // Default leaf capacity: a few boxes per leaf keeps the tree shallow without wasting tests.
  static constexpr int kDefaultLeafSize = 4;

  // An empty tree: every query reports nothing.
  AabbTree() = default;

  // Builds the tree over `boxes` (n boxes; box id i is boxes[i], n < 2^31). `leaf_size` >= 1 is
  // the largest number of boxes a leaf holds. With `cancel`, it is looked at while the tree is
  // built; once it is stopped the rest of the tree is left as empty leaves (queries miss them),
  // and the caller, which checks cancel->stopped(), drops the tree.
  explicit AabbTree(std::vector<Box> boxes, int leaf_size = kDefaultLeafSize,
                    CancelCheck* cancel = nullptr);

  // Number of boxes the tree was built from (empty boxes included).
  Index size() const { return static_cast<Index>(boxes_.size()); }

  // Box id i as given at construction.
  const Box& box(Index i) const { return boxes_[i]; }

  // Calls visit(id) once for every box overlapping `query`, in tree order (deterministic).
  void for_each_overlap(const Box& query, absl::FunctionRef<void(Index)> visit) const;

  // Ids of the boxes overlapping `query`, ascending.
  std::vector<Index> overlapping(const Box& query) const;

  // Calls visit(i, j) with i < j once for every pair of distinct boxes that overlap, in tree
  // order (deterministic). With `stop`, returns early (some pairs unvisited) once stop->due() is
  // true at a leaf; the caller looks at stop->stopped().
  void for_each_overlapping_pair(absl::FunctionRef<void(Index, Index)> visit,
                                 CancelCheck* stop = nullptr) const;

  // All overlapping pairs (i, j), i < j, sorted lexicographically.
  std::vector<std::pair<Index, Index>> overlapping_pairs() const;

  // The result of `nearest`: a box id (kInvalidIndex for an empty tree) and its distance.
  struct Nearest {
    Index id = kInvalidIndex;
    double squared_distance = 0.0;
  };

  // The non-empty box id i with the smallest squared_distance(i), ties to the smaller id.
  // `squared_distance(i)` is the caller's measure of the object inside box i (e.g. the squared
  // distance from x to a triangle) and must be at least the squared distance from x to box(i):
  // subtrees whose box is farther from x than the best value so far are skipped (branch and
  // bound, nearer child first), so a query near the objects costs about O(log n) calls.
  Nearest nearest(const Point& x, absl::FunctionRef<double(Index)> squared_distance) const;

 private:
  // A box's centre and id, as the construction moves them.
  struct BuildItem {
    Point centre;
    Index id;
  };
  // The axis (0, 1, 2) along which the centres of items [begin, end) spread the most.
  static int widest_axis(const std::vector<BuildItem>& items, Index begin, Index end);

  // A leaf has count > 0 and holds ids order_[first, first + count); an inner node has
  // count == 0, its left child at (own index + 1) and its right child at `right`.
  struct Node {
    Box box;
    Index first = 0;
    Index count = 0;
    Index right = kInvalidIndex;
  };

  Index build(Index begin, Index end, std::vector<BuildItem>& items, int leaf_size,
              CancelCheck* cancel);
  void query(Index node, const Box& q, absl::FunctionRef<void(Index)> visit) const;
  void pairs_within(Index node, absl::FunctionRef<void(Index, Index)> visit,
                    CancelCheck* stop) const;
  void pairs_across(Index a, Index b, absl::FunctionRef<void(Index, Index)> visit,
                    CancelCheck* stop) const;
  void nearest_in(Index node, const Point& x, absl::FunctionRef<double(Index)> squared_distance,
                  Nearest& best) const;

  std::vector<Box> boxes_;   // n boxes, by id
  std::vector<Index> order_;  // ids of the non-empty boxes, grouped by leaf
  std::vector<Node> nodes_;  // pre-order; nodes_[0] is the root when not empty
};

}  // namespace afmesh
