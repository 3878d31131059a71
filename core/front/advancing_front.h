// The front of an advancing-front loop, in any of its two dimensions (paper §1 and §3): the
// items that separate the meshed region from the region still to be meshed. An item is a
// simplex of `Arity` points: a triangle (face) of the volume front (Arity 3, steps F6-F10), a
// segment (side) of the surface front (Arity 2, steps S1-S10). The front holds
//  - the priority queue of F6 / S1 (front_queue.h),
//  - per front point, the list of its live items, which tells in O(1) (a point has a handful of
//    front items) whether a new element's face or side closes an item already on the front
//    (F10 / S10),
//  - the bins over front points and items for the close-point and crossing searches (F7.2,
//    F7.3 / S5, S6; front_bins.h).
//
// Items are oriented: a face (a, b, c) has (b-a)x(c-a) pointing into the unmeshed space; a side
// (a, b) has the unmeshed part of its surface patch on its left, seen from the patch's normal.
// Two items are the same when one is an even permutation of the other (a rotation of a face;
// only the identity for a side, whose reverse looks the other way).
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <vector>

#include "core/front/front_bins.h"
#include "core/front/front_queue.h"
#include "core/mesh/mesh.h"

namespace afmesh {

template <std::size_t Arity>
struct FrontItem {
  static_assert(Arity == 2 || Arity == 3);
  using Simplex = std::array<Index, Arity>;
  Simplex v = filled(kInvalidIndex);
  Index env = 0;              // crossing environment (paper §2); 0 = none
  std::uint32_t stamp = 0;    // bumped when the slot is reused, invalidates old queue entries
  std::uint8_t attempts = 0;  // failed attempts to delete this item (raises its queue class)
  bool alive = false;
  // next[k]: the next live item in the list of the point v[k] (kInvalidIndex ends it).
  Simplex next = filled(kInvalidIndex);

 private:
  static constexpr Simplex filled(Index x) {
    Simplex s{};
    for (Index& i : s) i = x;
    return s;
  }
};

template <std::size_t Arity>
class AdvancingFront {
 public:
  using Item = FrontItem<Arity>;
  using Simplex = typename Item::Simplex;

  // `points` is the mesher's point array; it must outlive the front and may grow (never move
  // points that are on the front). `domain`, `cell_size` and `max_cells` set up the bins
  // (FrontBins).
  AdvancingFront(const std::vector<Point>& points, const Box& domain, double cell_size,
                 std::int64_t max_cells = FrontBins::kDefaultMaxCells);

  // Adds item `v` (oriented towards the unmeshed space) with queue key `size` (the size of the
  // element it would form); returns its id.
  Index add(const Simplex& v, double size, Index env = 0);
  // Removes a live item (its points leave the bins when they have no other front item).
  void remove(Index f);
  // Puts a live item back into the queue after a failed attempt, one class later.
  void defer(Index f, double size);
  // Puts a live item back into the queue as a fresh item (class 0), after its surroundings
  // were re-opened.
  void requeue(Index f, double size);

  // The live item v, in this orientation (up to an even permutation), if any. Where the two
  // sides of a thin region cross (paper §2), faces of the two sides' elements can share their
  // three points with opposite meshed sides, so the orientation tells them apart.
  std::optional<Index> find(const Simplex& v) const;

  // F6 / S1: pops the item to delete next (FrontQueue's order); nullopt when the front is
  // empty.
  std::optional<Index> pop();

  const Item& item(Index f) const { return items_[f]; }
  // Calls fn(f) for each live item with point p as a corner (none when p is not on the front).
  template <typename Fn>
  void for_each_item_at(Index p, Fn&& fn) const {
    if (!on_front(p)) return;
    for (Index g = first_item_[p]; g != kInvalidIndex;) {
      const Item& item = items_[g];
      std::size_t k = 0;
      while (k + 1 < Arity && item.v[k] != p) ++k;
      const Index next = item.next[k];
      fn(g);
      g = next;
    }
  }
  std::int64_t size() const { return live_; }
  bool on_front(Index p) const {
    return p < static_cast<Index>(first_item_.size()) && first_item_[p] != kInvalidIndex;
  }
  const FrontBins& bins() const { return bins_; }
  // Moves the live points and items into adaptive bins (FrontBins::Adaptive: an octree), for a
  // front whose element sizes turn out to span orders of magnitude. Queries then answer the same
  // sets (in another order).
  void use_adaptive_bins();
  bool adaptive_bins() const { return bins_.adaptive(); }

 private:
  Box box_of(const Simplex& v) const;
  // Item f joins (leaves) the list of its corner k's point; the point enters (leaves) the bins
  // with its first (last) item.
  void point_joins(Index f, std::size_t k);
  void point_leaves(Index f, std::size_t k);

  const std::vector<Point>& points_;
  std::vector<Item> items_;
  std::vector<Index> free_;
  std::int64_t live_ = 0;
  FrontQueue queue_;
  std::vector<Index> first_item_;  // per point: the first live item of its list, or kInvalidIndex
  Box domain_;                     // the bins' domain
  FrontBins bins_;
};

extern template class AdvancingFront<2>;
extern template class AdvancingFront<3>;

}  // namespace afmesh
