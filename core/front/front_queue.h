// The queue of an advancing front: step F6 of the volume front and S1 of the surface front
// (paper §1, §3): the item (face or side) forming the smallest new element is deleted next, so
// that large elements do not cross regions of small ones.
//
// Entries are popped by class (0 for a fresh item; an item that failed `k` times waits in class
// k, behind every fresher item), then items of a crossing environment first (paper §2: "the
// faces marked as belonging to an environment are given the highest priority"), then smallest
// size, then lowest id. An entry carries the item's stamp; the front drops entries whose item
// was removed or re-queued since (stale entries stay until popped).
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "core/mesh/mesh.h"

namespace afmesh {

struct FrontQueueEntry {
  std::uint32_t cls;  // failed attempts of the item when queued
  bool unmarked;      // the item has no crossing environment (it goes after marked ones)
  double size;        // the size of the element the item forms
  Index item;
  std::uint32_t stamp;
};

// One 4-ary heap of 16-byte items per (class, marked) group, so a heap node's children share a
// cache line and the heaps stay shallow on a large front (not in the paper).
class FrontQueue {
 public:
  bool empty() const { return count_ == 0; }
  void push(const FrontQueueEntry& e);
  FrontQueueEntry pop();  // the queue must not be empty

 private:
  struct Item {
    double size;
    Index item;
    std::uint32_t stamp;
    bool before(const Item& o) const {
      if (size != o.size) return size < o.size;
      return item < o.item;
    }
  };
  std::vector<std::vector<Item>> groups_;  // by 2·class + unmarked
  std::size_t lowest_ = 0;                 // no group below this one holds items
  std::size_t count_ = 0;
};

}  // namespace afmesh
