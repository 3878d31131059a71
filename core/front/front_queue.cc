#include "core/front/front_queue.h"

#include <algorithm>

namespace afmesh {

void FrontQueue::push(const FrontQueueEntry& e) {
  const std::size_t g = 2 * std::size_t{e.cls} + (e.unmarked ? 1 : 0);
  if (g >= groups_.size()) groups_.resize(g + 1);
  std::vector<Item>& heap = groups_[g];
  const Item item{e.size, e.item, e.stamp};
  std::size_t i = heap.size();
  heap.push_back(item);
  while (i > 0) {  // sift up
    const std::size_t parent = (i - 1) / 4;
    if (!item.before(heap[parent])) break;
    heap[i] = heap[parent];
    i = parent;
  }
  heap[i] = item;
  lowest_ = std::min(lowest_, g);
  ++count_;
}

FrontQueueEntry FrontQueue::pop() {
  while (groups_[lowest_].empty()) ++lowest_;
  const std::size_t g = lowest_;
  std::vector<Item>& heap = groups_[g];
  const Item top = heap.front();
  const Item last = heap.back();
  heap.pop_back();
  --count_;
  const std::size_t n = heap.size();
  if (n > 0) {
    std::size_t i = 0;
    for (;;) {  // sift `last` down from the root
      const std::size_t first = 4 * i + 1;
      if (first >= n) break;
      std::size_t best = first;
      const std::size_t end = std::min(first + 4, n);
      for (std::size_t c = first + 1; c < end; ++c)
        if (heap[c].before(heap[best])) best = c;
      if (!heap[best].before(last)) break;
      heap[i] = heap[best];
      i = best;
    }
    heap[i] = last;
  }
  return {static_cast<std::uint32_t>(g / 2), g % 2 == 1, top.size, top.item, top.stamp};
}

}  // namespace afmesh
