// The 3-D front of the advancing-front loop (paper §1): the faces that separate the meshed region
// from the space still to be meshed, with
//  - the priority queue of step F6 (smallest element first, failed faces later),
//  - per front point, the list of its live faces, which tells in O(1) (a point has a handful of
//    front faces) whether a new element face closes a face already on the front (F10),
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
  // next[k]: the next live face in the list of the point v[k] (kInvalidIndex ends it).
  std::array<Index, 3> next{kInvalidIndex, kInvalidIndex, kInvalidIndex};
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

  // The live face (a, b, c), in this orientation (up to rotation), if any. Where the two sides
  // of a thin region cross (paper §2), faces of the two sides' elements can share their three
  // points with opposite meshed sides, so the orientation tells them apart.
  std::optional<Index> find(Index a, Index b, Index c) const;

  // F6: pops the face to delete next (lowest class, then faces of a crossing environment, then
  // smallest size, then lowest id);
  // nullopt when the front is empty.
  std::optional<Index> pop();

  const FrontFace& face(Index f) const { return faces_[f]; }
  std::int64_t size() const { return live_; }
  bool on_front(Index p) const {
    return p < static_cast<Index>(first_face_.size()) && first_face_[p] != kInvalidIndex;
  }
  const FrontBins& bins() const { return bins_; }

 private:
  struct QueueEntry {
    std::uint32_t cls;
    bool unmarked;  // faces of a crossing environment go first (paper §2)
    double size;
    Index face;
    std::uint32_t stamp;
  };
  // The queue of F6: entries are popped by class, then faces of a crossing environment first,
  // then smallest size, then lowest id. One 4-ary heap of 16-byte items per (class, marked)
  // group, so a heap node's children share a cache line and the heaps stay shallow on a large
  // front. Entries of removed or re-queued faces stay until popped.
  class Queue {
   public:
    bool empty() const { return count_ == 0; }
    void push(const QueueEntry& e);
    QueueEntry pop();  // the queue must not be empty

   private:
    struct Item {
      double size;
      Index face;
      std::uint32_t stamp;
      bool before(const Item& o) const {
        if (size != o.size) return size < o.size;
        return face < o.face;
      }
    };
    std::vector<std::vector<Item>> groups_;  // by 2·class + unmarked
    std::size_t lowest_ = 0;  // no group below this one holds items
    std::size_t count_ = 0;
  };
  Box box_of_face(const Triangle& v) const;
  // Face f joins (leaves) the list of its corner k's point; the point enters (leaves) the bins
  // with its first (last) face.
  void point_joins(Index f, int k);
  void point_leaves(Index f, int k);

  const std::vector<Point>& points_;
  std::vector<FrontFace> faces_;
  std::vector<Index> free_;
  std::int64_t live_ = 0;
  Queue queue_;
  std::vector<Index> first_face_;  // per point: the first live face of its list, or kInvalidIndex
  FrontBins bins_;
};

}  // namespace afmesh
