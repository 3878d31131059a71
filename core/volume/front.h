// The 3-D front of the advancing-front loop (paper §1): the faces that separate the meshed region
// from the space still to be meshed, with
//  - the priority queue of step F6 (smallest element first, failed faces later),
//  - the face lookup table keyed by the sorted vertex triple, which tells in O(1) whether a new
//    element face closes a face already on the front (F10),
//  - the bins over front points and faces for the close-point and crossing searches (F7.2, F7.3).
//
// A front face (a, b, c) is oriented with (b-a)x(c-a) pointing into the unmeshed space, so the
// element built on it with a point p on that side is the positive tet (a, b, c, p).
#pragma once

#include <algorithm>
#include <array>
#include <cstdint>
#include <optional>
#include <vector>

#include "core/mesh/mesh.h"
#include "core/volume/front_bins.h"

namespace afmesh {

struct FrontFace {
  Triangle v{kInvalidIndex, kInvalidIndex, kInvalidIndex};
  Index env = 0;             // crossing environment (paper §2); 0 = none
  std::uint32_t stamp = 0;   // bumped when the slot is reused, invalidates old queue entries
  std::uint8_t attempts = 0; // failed attempts to delete this face (raises its queue class)
  bool alive = false;
};

// The face lookup table of the front: open addressing with linear probing and backward-shift
// deletion, from a face's sorted vertex triple to its id. 16-byte slots, no tombstones; grows
// to keep at most half its slots full. Lookups depend only on the keys, never on addresses.
class FaceLookup {
 public:
  FaceLookup() : slots_(kInitialSlots), mask_(kInitialSlots - 1) {}
  // The id stored under sorted triple k, or kInvalidIndex.
  Index find(const Triangle& k) const {
    for (std::size_t i = home(k);; i = (i + 1) & mask_) {
      const Slot& s = slots_[i];
      if (s.face == kInvalidIndex) return kInvalidIndex;
      if (s.key == k) return s.face;
    }
  }
  // Stores f under sorted triple k (replacing what was stored under k).
  void assign(const Triangle& k, Index f);
  // Removes sorted triple k if present.
  void erase(const Triangle& k);

 private:
  static constexpr std::size_t kInitialSlots = 64;
  struct Slot {
    Triangle key{};
    Index face = kInvalidIndex;  // kInvalidIndex: empty
  };
  std::size_t home(const Triangle& k) const {
    std::uint64_t h = ((std::uint64_t(std::uint32_t(k[0])) << 32) | std::uint32_t(k[1])) *
                      0x9E3779B97F4A7C15ull;
    h ^= (std::uint64_t(std::uint32_t(k[2])) + 0x632BE59BD9B4E019ull) * 0xC2B2AE3D27D4EB4Full;
    h ^= h >> 31;
    return static_cast<std::size_t>(h) & mask_;
  }
  void grow();

  std::vector<Slot> slots_;
  std::size_t mask_;
  std::size_t count_ = 0;
};

class Front {
 public:
  // `points` is the mesher's point array; it must outlive the front and may grow (never move
  // points that are on the front).
  Front(const std::vector<Point>& points, const Box& domain, double cell_size);

  // Adds face `v` (oriented into the unmeshed space) with queue key `size` (the size of the
  // element it would form); returns its id.
  Index add(const Triangle& v, double size, Index env = 0);
  // Removes a live face (its points leave the bins when they have no other front face).
  void remove(Index f);
  // Puts a live face back into the queue after a failed attempt, one class later.
  void defer(Index f, double size);
  // Puts a live face back into the queue as a fresh face (class 0), after its surroundings were
  // re-opened.
  void requeue(Index f, double size);

  // The live face with vertex set {a, b, c} in any order, if any.
  std::optional<Index> find(Index a, Index b, Index c) const;

  // F6: pops the face to delete next (lowest class, then faces of a crossing environment, then
  // smallest size, then lowest id);
  // nullopt when the front is empty.
  std::optional<Index> pop();

  const FrontFace& face(Index f) const { return faces_[f]; }
  // The bounding box of live face f (kept so the crossing check need not recompute it).
  const Box& box(Index f) const { return boxes_[f]; }
  std::int64_t size() const { return live_; }
  bool on_front(Index p) const { return p < static_cast<Index>(point_faces_.size()) && point_faces_[p] > 0; }
  const FrontBins& bins() const { return bins_; }

 private:
  struct QueueEntry {
    std::uint32_t cls;
    bool unmarked;  // faces of a crossing environment go first (paper §2)
    double size;
    Index face;
    std::uint32_t stamp;
    // True when this entry is popped before o.
    bool before(const QueueEntry& o) const {
      if (cls != o.cls) return cls < o.cls;
      if (unmarked != o.unmarked) return !unmarked;
      if (size != o.size) return size < o.size;
      return face < o.face;
    }
  };
  // The queue of F6: a 4-ary heap (half the depth of a binary one: fewer cache misses on a large
  // front), entry 0 popped first. Entries of removed or re-queued faces stay until popped.
  class Queue {
   public:
    bool empty() const { return heap_.empty(); }
    void push(const QueueEntry& e);
    QueueEntry pop();

   private:
    std::vector<QueueEntry> heap_;
  };
  // The vertex triple sorted ascending: the lookup key of the face on a, b, c in any order.
  static Triangle key_of(Index a, Index b, Index c) {
    const Index lo = std::min({a, b, c}), hi = std::max({a, b, c});
    return {lo, a ^ b ^ c ^ lo ^ hi, hi};
  }
  Box box_of_face(const Triangle& v) const;
  void point_joins(Index p);
  void point_leaves(Index p);

  const std::vector<Point>& points_;
  std::vector<FrontFace> faces_;
  std::vector<Box> boxes_;  // per face slot
  std::vector<Index> free_;
  std::int64_t live_ = 0;
  FaceLookup lookup_;
  Queue queue_;
  std::vector<std::int32_t> point_faces_;  // per point: number of live front faces using it
  FrontBins bins_;
};

}  // namespace afmesh
