#include "core/front/front_tree.h"

#include <algorithm>
#include <cmath>

namespace afmesh {

FrontTree::FrontTree(const Box& domain) {
  Node root;
  double extent = 0.0;
  for (int a = 0; a < 3; ++a) extent = std::max(extent, domain.hi[a] - domain.lo[a]);
  if (!(extent > 0.0) || !std::isfinite(extent)) extent = 1.0;
  // A cube a little larger than the domain, so that points on its high faces fall inside.
  root.size = extent * (1.0 + 1e-9) + 1e-300;
  for (int a = 0; a < 3; ++a) root.lo[a] = std::isfinite(domain.lo[a]) ? domain.lo[a] : 0.0;
  root.items_bound = empty_box();
  nodes_.push_back(root);
}

Point FrontTree::clamped(const Point& x) const {
  const Node& root = nodes_[0];
  Point c;
  for (int a = 0; a < 3; ++a) {
    const double v = x[a];
    c[a] = v >= root.lo[a] ? (v <= root.lo[a] + root.size ? v : root.lo[a] + root.size)
                           : root.lo[a];  // also NaN
  }
  return c;
}

Index FrontTree::child_at(Index n, const Point& x) const {
  const Node& node = nodes_[n];
  const double half = 0.5 * node.size;
  int octant = 0;
  for (int a = 0; a < 3; ++a)
    if (x[a] >= node.lo[a] + half) octant |= 1 << a;
  return node.first_child + octant;
}

void FrontTree::split(Index n) {
  const Index first = static_cast<Index>(nodes_.size());
  for (int octant = 0; octant < 8; ++octant) {
    Node child;
    child.size = 0.5 * nodes_[n].size;
    child.depth = nodes_[n].depth + 1;
    for (int a = 0; a < 3; ++a)
      child.lo[a] = nodes_[n].lo[a] + ((octant >> a & 1) ? child.size : 0.0);
    child.items_bound = empty_box();
    nodes_.push_back(std::move(child));
  }
  nodes_[n].first_child = first;
  std::vector<Index> points;
  points.swap(nodes_[n].points);
  for (const Index p : points) {
    Node& child = nodes_[child_at(n, clamped(point_at_[p]))];
    child.points.push_back(p);
    ++child.points_below;
  }
}

void FrontTree::insert_point(Index p, const Point& x) {
  if (p >= static_cast<Index>(point_at_.size())) point_at_.resize(p + 1);
  point_at_[p] = x;
  const Point c = clamped(x);
  Index n = 0;
  for (;;) {
    ++nodes_[n].points_below;
    if (nodes_[n].first_child == kInvalidIndex) break;
    n = child_at(n, c);
  }
  nodes_[n].points.push_back(p);
  if (nodes_[n].points.size() > kLeafPoints && nodes_[n].depth < kMaxDepth) split(n);
}

void FrontTree::erase_point(Index p, const Point& x) {
  const Point c = clamped(x);
  Index n = 0;
  for (;;) {
    --nodes_[n].points_below;
    if (nodes_[n].first_child == kInvalidIndex) break;
    n = child_at(n, c);
  }
  std::vector<Index>& here = nodes_[n].points;
  const auto it = std::find(here.begin(), here.end(), p);
  if (it != here.end()) {
    *it = here.back();
    here.pop_back();
  }
}

Index FrontTree::item_node(const Box& box, bool insert) {
  double extent = 0.0;
  Point centre;
  for (int a = 0; a < 3; ++a) {
    extent = std::max(extent, box.hi[a] - box.lo[a]);
    centre[a] = 0.5 * (box.lo[a] + box.hi[a]);
  }
  centre = clamped(centre);
  Index n = 0;
  for (;;) {
    if (insert) enclose(nodes_[n].items_bound, box);
    // Children of half this size hold the item when it is no wider than they are.
    if (nodes_[n].depth >= kMaxDepth || 0.5 * nodes_[n].size < extent) return n;
    if (nodes_[n].first_child == kInvalidIndex) {
      if (!insert) return kInvalidIndex;
      split(n);
    }
    n = child_at(n, centre);
  }
}

void FrontTree::insert_item(Index f, const Box& box) {
  if (f >= static_cast<Index>(item_box_.size())) item_box_.resize(f + 1);
  item_box_[f] = box;
  nodes_[item_node(box, /*insert=*/true)].items.push_back(f);
}

void FrontTree::erase_item(Index f, const Box& box) {
  const Index n = item_node(box, /*insert=*/false);
  if (n == kInvalidIndex) return;
  std::vector<Index>& here = nodes_[n].items;
  const auto it = std::find(here.begin(), here.end(), f);
  if (it != here.end()) {
    *it = here.back();
    here.pop_back();
  }
}

}  // namespace afmesh
