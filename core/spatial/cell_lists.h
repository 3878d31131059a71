// Many short lists in one pool: the storage behind the bins of an advancing front (not in the
// paper; the bins are the search structure of steps F7.2, F7.3 and S5, S6).
//
// Each of `cell_count` cells holds a list of trivially copyable items with the semantics of a
// std::vector used as a bag: push_back appends, erase moves the list's last item into the place
// of the erased one, and iteration goes in list order. The lists live in fixed chunks of
// `kChunk` items taken from one pool (a free list reuses the chunks of lists that shrank), so a
// bins of 10^5-10^6 cells is four allocations, not one or two per cell: tearing it down takes
// microseconds instead of the tens of milliseconds that freeing each cell's vector took after a
// cancelled 2M-tet job (issue 12, part 3).
//
// A list of n items spans ceil(n / kChunk) chunks linked in order; item i is in chunk i / kChunk.
// Lists are short (a cell holds the few front items near it), so walking the chain is cheap.
#pragma once

#include <cassert>
#include <cstddef>
#include <cstdint>
#include <type_traits>
#include <vector>

namespace afmesh {

template <typename T, std::size_t kChunk>
class CellLists {
  static_assert(std::is_trivially_copyable_v<T>);
  static_assert(kChunk > 0);

 public:
  CellLists() = default;
  explicit CellLists(std::size_t cell_count) : cells_(cell_count) {}

  std::size_t cell_count() const { return cells_.size(); }
  std::size_t size(std::size_t cell) const { return cells_[cell].count; }
  bool empty(std::size_t cell) const { return cells_[cell].count == 0; }

  void push_back(std::size_t cell, const T& item) {
    Cell& c = cells_[cell];
    if (c.count % kChunk == 0) {
      const std::uint32_t fresh = take_chunk();
      if (c.count == 0) {
        c.first = fresh;
      } else {
        chunks_[chunk_at(c, c.count / kChunk - 1)].next = fresh;
      }
    }
    chunks_[chunk_at(c, c.count / kChunk)].items[c.count % kChunk] = item;
    ++c.count;
  }

  // Erases the first item of the list for which match(item) is true, moving the last item into
  // its place (std::vector's swap-and-pop); false when none matches.
  template <typename Match>
  bool erase_first(std::size_t cell, Match&& match) {
    Cell& c = cells_[cell];
    std::uint32_t chunk = c.first;
    for (std::uint32_t i = 0; i < c.count; ++i) {
      if (i > 0 && i % kChunk == 0) chunk = chunks_[chunk].next;
      T& item = chunks_[chunk].items[i % kChunk];
      if (!match(item)) continue;
      const std::uint32_t last = c.count - 1;
      const std::uint32_t last_chunk = chunk_at(c, last / kChunk);
      item = chunks_[last_chunk].items[last % kChunk];
      --c.count;
      if (c.count % kChunk == 0) {  // the last chunk is empty now: back to the pool
        free_.push_back(last_chunk);
        if (c.count == 0) {
          c.first = kNone;
        } else {
          chunks_[chunk_at(c, c.count / kChunk - 1)].next = kNone;
        }
      }
      return true;
    }
    return false;
  }

  // Calls fn(items, n) for each run of n consecutive items of the list, in list order, until fn
  // returns true; returns whether it did. fn must not change the lists.
  template <typename Fn>
  bool find_run(std::size_t cell, Fn&& fn) const {
    const Cell& c = cells_[cell];
    std::uint32_t chunk = c.first;
    for (std::uint32_t begin = 0; begin < c.count; begin += kChunk) {
      const Chunk& k = chunks_[chunk];
      const std::uint32_t n = c.count - begin < kChunk ? c.count - begin : kChunk;
      if (fn(k.items, static_cast<std::size_t>(n))) return true;
      chunk = k.next;
    }
    return false;
  }

  // Calls fn(item) for each item of the list, in list order. fn must not change the lists.
  template <typename Fn>
  void for_each(std::size_t cell, Fn&& fn) const {
    find_run(cell, [&](const T* items, std::size_t n) {
      for (std::size_t i = 0; i < n; ++i) fn(items[i]);
      return false;
    });
  }

 private:
  static constexpr std::uint32_t kNone = UINT32_MAX;
  struct Cell {
    std::uint32_t first = kNone;  // the list's first chunk
    std::uint32_t count = 0;      // items in the list
  };
  struct Chunk {
    T items[kChunk];
    std::uint32_t next = kNone;  // the list's next chunk
  };

  // The index of the list's k-th chunk (it must exist).
  std::uint32_t chunk_at(const Cell& c, std::uint32_t k) const {
    std::uint32_t chunk = c.first;
    for (; k > 0; --k) chunk = chunks_[chunk].next;
    assert(chunk != kNone);
    return chunk;
  }
  std::uint32_t take_chunk() {
    if (!free_.empty()) {
      const std::uint32_t chunk = free_.back();
      free_.pop_back();
      chunks_[chunk].next = kNone;
      return chunk;
    }
    chunks_.emplace_back();
    return static_cast<std::uint32_t>(chunks_.size() - 1);
  }

  std::vector<Cell> cells_;
  std::vector<Chunk> chunks_;
  std::vector<std::uint32_t> free_;  // chunks of no list
};

}  // namespace afmesh
