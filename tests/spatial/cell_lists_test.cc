// Tests of CellLists: the pooled lists behave as one std::vector per cell used as a bag
// (push_back, swap-and-pop erase, iteration in order), whatever the chunk size.
#include "core/spatial/cell_lists.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <vector>

namespace afmesh {
namespace {

template <std::size_t kChunk>
std::vector<int> items_of(const CellLists<int, kChunk>& lists, std::size_t cell) {
  std::vector<int> out;
  lists.for_each(cell, [&](int x) { out.push_back(x); });
  return out;
}

// Random pushes and erases on a few cells, checked after every step against vectors.
template <std::size_t kChunk>
void check_against_vectors(unsigned seed) {
  constexpr std::size_t kCells = 7;
  CellLists<int, kChunk> lists(kCells);
  std::vector<std::vector<int>> reference(kCells);
  std::mt19937 rng(seed);
  for (int step = 0; step < 20000; ++step) {
    const std::size_t cell = rng() % kCells;
    std::vector<int>& ref = reference[cell];
    // Grow to tens of items, then shrink to none, so chunks are taken and returned.
    const bool grow = (step / 2000) % 2 == 0 ? rng() % 4 != 0 : rng() % 4 == 0;
    if (grow || ref.empty()) {
      const int x = static_cast<int>(rng() % 50);
      lists.push_back(cell, x);
      ref.push_back(x);
    } else {
      const int x = ref[rng() % ref.size()];
      ASSERT_TRUE(lists.erase_first(cell, [x](int y) { return y == x; }));
      auto it = std::find(ref.begin(), ref.end(), x);
      *it = ref.back();
      ref.pop_back();
    }
    ASSERT_EQ(lists.size(cell), ref.size());
    ASSERT_EQ(items_of(lists, cell), ref) << "step " << step << " cell " << cell;
  }
  for (std::size_t c = 0; c < kCells; ++c) EXPECT_EQ(items_of(lists, c), reference[c]);
}

TEST(CellLists, BehaveAsVectorsUsedAsBags) {
  check_against_vectors<1>(1);
  check_against_vectors<3>(2);
  check_against_vectors<15>(3);
}

TEST(CellLists, EraseOfAMissingItemChangesNothing) {
  CellLists<int, 2> lists(2);
  for (int x : {4, 5, 6}) lists.push_back(1, x);
  EXPECT_FALSE(lists.erase_first(1, [](int y) { return y == 9; }));
  EXPECT_FALSE(lists.erase_first(0, [](int) { return true; }));
  EXPECT_EQ(items_of(lists, 1), (std::vector<int>{4, 5, 6}));
  EXPECT_TRUE(lists.empty(0));
}

TEST(CellLists, FindRunStopsWhereTheCallbackSaysAndSeesRunsInOrder) {
  CellLists<int, 4> lists(1);
  for (int x = 0; x < 10; ++x) lists.push_back(0, x);
  std::vector<std::size_t> runs;
  EXPECT_FALSE(lists.find_run(0, [&](const int* items, std::size_t n) {
    runs.push_back(n);
    EXPECT_EQ(items[0], static_cast<int>(4 * (runs.size() - 1)));
    return false;
  }));
  EXPECT_EQ(runs, (std::vector<std::size_t>{4, 4, 2}));
  int seen = 0;
  EXPECT_TRUE(lists.find_run(0, [&](const int*, std::size_t) { return ++seen == 2; }));
  EXPECT_EQ(seen, 2);
}

}  // namespace
}  // namespace afmesh
