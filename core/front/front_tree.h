// An octree over the active front, for fronts whose element sizes span orders of magnitude within
// one search structure (not in the paper, whose fronts search bins of about the element size).
//
// FrontBins is a uniform grid: a query visits the cells of its box and every entry in them, so it
// costs O(1) only where the elements are about the cell's size. A surface patch whose sizes run
// from the size asked down to a thousandth of it (a scanned head's folds, OCCT's head.stl: sizes
// 0.00086 in a patch of cells 1.3 wide) puts thousands of points in a cell, and each of its front's
// queries walks them all (head.stl's front ran for over five minutes). Here a point sits in a leaf
// of at most kLeafPoints points, split into eight as it fills, and an item (a side of the surface
// front) in the deepest node at least as wide as the item (at most twice), so a query visits O(log N) nodes plus
// those that hold what it asks for, whatever the sizes. Each node keeps the number of points below
// it and a box enclosing every item ever stored below it (not shrunk when items leave: a bound,
// never too small), so empty or distant subtrees are skipped.
//
// The answers are those of FrontBins: every point inside the query box (the points the tree
// visits are filtered by their exact position) and every item whose box overlaps it, each once, in
// an order fixed by the history of insertions and removals (deterministic, not sorted).
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "core/mesh/mesh.h"
#include "core/spatial/box.h"

namespace afmesh {

class FrontTree {
 public:
  // `domain` bounds the points that will be inserted; points outside it are placed in the nodes
  // at its border (queries stay correct: they look up positions clamped the same way).
  explicit FrontTree(const Box& domain);

  void insert_point(Index p, const Point& x);
  void erase_point(Index p, const Point& x);
  void insert_item(Index f, const Box& box);
  void erase_item(Index f, const Box& box);

  // Calls fn(p) for every point inside the closed box `box`, each once. fn must not change the
  // tree.
  template <typename Fn>
  void for_each_point_near(const Box& box, Fn&& fn) const;
  // Calls fn(f) for every item whose box overlaps `box`, each once, until fn returns true;
  // returns whether it did. fn must not change the tree.
  template <typename Fn>
  bool find_item_near(const Box& box, Fn&& fn) const;

 private:
  static constexpr std::size_t kLeafPoints = 16;
  static constexpr int kMaxDepth = 40;
  struct Node {
    Point lo{};
    double size = 0.0;
    int depth = 0;
    Index first_child = kInvalidIndex;  // eight consecutive nodes, or none
    std::int64_t points_below = 0;
    Box items_bound;  // encloses every item ever stored at or below this node
    std::vector<Index> points;
    std::vector<Index> items;
  };
  // x clamped into the root's cube.
  Point clamped(const Point& x) const;
  // The child of node n whose octant holds the (clamped) position x.
  Index child_at(Index n, const Point& x) const;
  // Gives node n its eight children and moves its points into them.
  void split(Index n);
  // The node an item of box `box` is stored at: the deepest whose cube holds the box's (clamped)
  // centre and whose children would be narrower than the box's largest extent. When `insert`,
  // creates the nodes on the way and grows their items_bound by the box; else kInvalidIndex when
  // the path does not exist.
  Index item_node(const Box& box, bool insert);

  std::vector<Node> nodes_;
  std::vector<Point> point_at_;  // the position each point was inserted with
  std::vector<Box> item_box_;    // the box each item was inserted with
};

template <typename Fn>
void FrontTree::for_each_point_near(const Box& box, Fn&& fn) const {
  Box q;
  q.lo = clamped(box.lo);
  q.hi = clamped(box.hi);
  // Depth-first: at most 7 siblings wait per level.
  std::array<Index, 8 * (kMaxDepth + 1)> stack;
  std::size_t top = 0;
  stack[top++] = 0;
  while (top > 0) {
    const Node& n = nodes_[stack[--top]];
    if (n.points_below == 0) continue;
    if (n.first_child == kInvalidIndex) {
      for (const Index p : n.points) {
        const Point& x = point_at_[p];
        if (box.lo[0] <= x[0] && x[0] <= box.hi[0] && box.lo[1] <= x[1] && x[1] <= box.hi[1] &&
            box.lo[2] <= x[2] && x[2] <= box.hi[2])
          fn(p);
      }
      continue;
    }
    // The children the clamped box reaches, by the comparison child_at places points with (so
    // rounding in the children's corners cannot lose a point on their boundary).
    int lower = 0, upper = 0;
    for (int a = 0; a < 3; ++a) {
      const double mid = n.lo[a] + 0.5 * n.size;
      if (q.lo[a] < mid) lower |= 1 << a;
      if (q.hi[a] >= mid) upper |= 1 << a;
    }
    for (int octant = 7; octant >= 0; --octant)
      if ((~octant & 7 & ~lower) == 0 && (octant & ~upper) == 0)
        stack[top++] = n.first_child + octant;
  }
}

template <typename Fn>
bool FrontTree::find_item_near(const Box& box, Fn&& fn) const {
  std::array<Index, 8 * (kMaxDepth + 1)> stack;
  std::size_t top = 0;
  stack[top++] = 0;
  while (top > 0) {
    const Node& n = nodes_[stack[--top]];
    if (!boxes_overlap(n.items_bound, box)) continue;
    for (const Index f : n.items)
      if (boxes_overlap(item_box_[f], box) && fn(f)) return true;
    if (n.first_child != kInvalidIndex)
      for (Index c = n.first_child + 7; c >= n.first_child; --c) stack[top++] = c;
  }
  return false;
}

}  // namespace afmesh
