#include "core/front/advancing_front.h"

namespace afmesh {
namespace {

template <std::size_t Arity>
std::size_t corner_of(const std::array<Index, Arity>& v, Index p) {
  std::size_t k = 0;
  while (k + 1 < Arity && v[k] != p) ++k;
  return k;
}

}  // namespace

template <std::size_t Arity>
AdvancingFront<Arity>::AdvancingFront(const std::vector<Point>& points, const Box& domain,
                                      double cell_size, std::int64_t max_cells)
    : points_(points), domain_(domain), bins_(domain, cell_size, max_cells) {}

template <std::size_t Arity>
void AdvancingFront<Arity>::use_adaptive_bins() {
  if (bins_.adaptive()) return;
  FrontBins tree(domain_, bins_.cell_size(), FrontBins::Adaptive{});
  for (Index p = 0; p < static_cast<Index>(first_item_.size()); ++p)
    if (first_item_[p] != kInvalidIndex) tree.insert_point(p, points_[p]);
  for (Index f = 0; f < static_cast<Index>(items_.size()); ++f)
    if (items_[f].alive) tree.insert_item(f, box_of(items_[f].v));
  bins_ = std::move(tree);
}

template <std::size_t Arity>
Box AdvancingFront<Arity>::box_of(const Simplex& v) const {
  Box b{points_[v[0]], points_[v[0]]};
  for (std::size_t k = 1; k < Arity; ++k) enclose(b, points_[v[k]]);
  return b;
}

template <std::size_t Arity>
void AdvancingFront<Arity>::point_joins(Index f, std::size_t k) {
  const Index p = items_[f].v[k];
  if (p >= static_cast<Index>(first_item_.size())) first_item_.resize(p + 1, kInvalidIndex);
  if (first_item_[p] == kInvalidIndex) bins_.insert_point(p, points_[p]);
  items_[f].next[k] = first_item_[p];
  first_item_[p] = f;
}

template <std::size_t Arity>
void AdvancingFront<Arity>::point_leaves(Index f, std::size_t k) {
  const Index p = items_[f].v[k];
  Index* link = &first_item_[p];
  while (*link != f) {
    Item& g = items_[*link];
    link = &g.next[corner_of<Arity>(g.v, p)];
  }
  *link = items_[f].next[k];
  if (first_item_[p] == kInvalidIndex) bins_.erase_point(p, points_[p]);
}

template <std::size_t Arity>
Index AdvancingFront<Arity>::add(const Simplex& v, double size, Index env) {
  Index f;
  if (!free_.empty()) {
    f = free_.back();
    free_.pop_back();
  } else {
    f = static_cast<Index>(items_.size());
    items_.emplace_back();
  }
  Item& item = items_[f];
  item.v = v;
  item.env = env;
  item.attempts = 0;
  item.alive = true;
  ++item.stamp;
  ++live_;
  queue_.push({0, env == 0, size, f, item.stamp});
  bins_.insert_item(f, box_of(v));
  for (std::size_t k = 0; k < Arity; ++k) point_joins(f, k);
  return f;
}

template <std::size_t Arity>
void AdvancingFront<Arity>::remove(Index f) {
  Item& item = items_[f];
  item.alive = false;
  --live_;
  bins_.erase_item(f, box_of(item.v));  // the points never move: the box it went in with
  for (std::size_t k = 0; k < Arity; ++k) point_leaves(f, k);
  free_.push_back(f);
}

template <std::size_t Arity>
void AdvancingFront<Arity>::defer(Index f, double size) {
  Item& item = items_[f];
  if (item.attempts < 255) ++item.attempts;
  queue_.push({item.attempts, item.env == 0, size, f, item.stamp});
}

template <std::size_t Arity>
void AdvancingFront<Arity>::requeue(Index f, double size) {
  Item& item = items_[f];
  item.attempts = 0;
  ++item.stamp;
  queue_.push({0, item.env == 0, size, f, item.stamp});
}

template <std::size_t Arity>
std::optional<Index> AdvancingFront<Arity>::find(const Simplex& v) const {
  for (const Index p : v)
    if (!on_front(p)) return std::nullopt;
  const Index a = v[0];
  for (Index g = first_item_[a]; g != kInvalidIndex;) {
    const Item& item = items_[g];
    const Simplex& w = item.v;
    const std::size_t k = corner_of<Arity>(w, a);
    // w rotated to start at a: the same face for Arity 3; for a side, only k == 0 is v itself.
    bool same = Arity == 3 || k == 0;
    for (std::size_t i = 1; same && i < Arity; ++i) same = w[(k + i) % Arity] == v[i];
    if (same) return g;
    g = item.next[k];
  }
  return std::nullopt;
}

template <std::size_t Arity>
std::optional<Index> AdvancingFront<Arity>::pop() {
  while (!queue_.empty()) {
    const FrontQueueEntry e = queue_.pop();
    const Item& item = items_[e.item];
    if (item.alive && item.stamp == e.stamp && item.attempts == e.cls) return e.item;
  }
  return std::nullopt;
}

template class AdvancingFront<2>;
template class AdvancingFront<3>;

}  // namespace afmesh
