// Bins over the active front (the search structure of steps F7.2 and F7.3 of the volume front,
// S5 and S6 of the surface front).
//
// Only points and items (faces of the volume front, sides of the surface front) that are on
// the current front live here; they leave when they leave the front, so a query visits O(1)
// cells holding O(1) entries each and the front loop stays O(N log N) overall. The bins are a
// dense uniform grid over the front's bounding box; a point sits in the one cell containing it,
// an item in every cell its bounding box overlaps, so a box query finds every item whose
// bounding box meets the query box (never a false negative). Each cell keeps, beside each item
// id, the part of the item's box inside the cell in 1/255ths of the cell (rounded outward), so
// an item query filters by box overlap while it walks the cell's memory in order and returns
// few items that miss the box. A query lists an item only in the lowest cell (per axis) shared
// by the item's and the query's cell ranges, where their boxes' overlap begins, so it lists each
// item once without marking what it listed. Made adaptive (FrontBins::Adaptive), the bins are an
// octree instead (front_tree.h), for fronts whose element sizes span orders of magnitude: the
// same answers but that points are listed only when inside the box and items only when their
// boxes overlap it.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <memory>
#include <vector>

#include "core/front/front_tree.h"
#include "core/mesh/mesh.h"
#include "core/spatial/box.h"
#include "core/spatial/cell_lists.h"

namespace afmesh {

class FrontBins {
 public:
  // `domain` bounds every point that will ever be inserted (points outside are clamped into the
  // border cells, which keeps queries correct). `cell_size` > 0 is the wanted edge of a cell;
  // it is enlarged so the grid has at most `max_cells` cells.
  static constexpr std::int64_t kDefaultMaxCells = std::int64_t{1} << 22;
  FrontBins(const Box& domain, double cell_size, std::int64_t max_cells = kDefaultMaxCells);
  // Adaptive bins: an octree (front_tree.h) in lieu of the grid, for fronts whose element sizes
  // span orders of magnitude (the cell size is then only reported).
  struct Adaptive {};
  FrontBins(const Box& domain, double cell_size, Adaptive);

  void insert_point(Index p, const Point& x);
  void erase_point(Index p, const Point& x);
  void insert_item(Index f, const Box& box);
  void erase_item(Index f, const Box& box);

  // Calls fn(p) for every point in cells overlapping `box` (a superset of the points inside
  // `box`; callers test exact containment), each once, in an order fixed by the history of
  // insertions and removals (deterministic, not sorted). fn must not change the bins.
  template <typename Fn>
  void for_each_point_near(const Box& box, Fn&& fn) const {
    if (tree_) return tree_->for_each_point_near(box, fn);
    for_each_cell(cells_of(box), [&](std::int64_t c, std::int64_t, std::int64_t, std::int64_t) {
      point_cells_.for_each(static_cast<std::size_t>(c), fn);
    });
  }
  // Appends the points of for_each_point_near to `out`.
  void points_near(const Box& box, std::vector<Index>& out) const;
  // Calls fn(f) for every item whose bounding box overlaps `box` (and a few whose box misses it
  // by less than 1/255 of a cell), each once, in a deterministic order (not sorted), until fn
  // returns true; returns whether it did. fn must not change the bins.
  template <typename Fn>
  bool find_item_near(const Box& box, Fn&& fn) const;
  // Appends to `out` the items find_item_near visits.
  void items_near(const Box& box, std::vector<Index>& out) const;

  double cell_size() const { return cell_; }
  bool adaptive() const { return tree_ != nullptr; }

 private:
  using CellRange = std::array<std::array<std::int64_t, 2>, 3>;  // [axis][lo, hi] inclusive
  // x along `axis` in cells from the grid's origin (monotone in x).
  double scaled(double x, int axis) const { return (x - origin_[axis]) * inverse_cell_; }
  // The cell holding scaled coordinate t: floor(t), clamped into the grid.
  std::int64_t cell_of_scaled(double t, int axis) const {
    const double c = std::floor(t);
    if (!(c > 0)) return 0;  // also catches NaN
    return std::min(static_cast<std::int64_t>(c), dims_[axis] - 1);
  }
  std::int64_t cell_coord(double x, int axis) const { return cell_of_scaled(scaled(x, axis), axis); }
  CellRange cells_of(const Box& box) const {
    CellRange r;
    for (int a = 0; a < 3; ++a) r[a] = {cell_coord(box.lo[a], a), cell_coord(box.hi[a], a)};
    return r;
  }
  std::int64_t cell_index(std::int64_t i, std::int64_t j, std::int64_t k) const {
    return (k * dims_[1] + j) * dims_[0] + i;
  }
  // The cell holding point x.
  std::size_t point_cell(const Point& x) const {
    return static_cast<std::size_t>(
        cell_index(cell_coord(x[0], 0), cell_coord(x[1], 1), cell_coord(x[2], 2)));
  }
  // Calls fn(cell index, i, j, k) for each cell of the range.
  template <typename Fn>
  void for_each_cell(const CellRange& r, Fn&& fn) const {
    for (std::int64_t k = r[2][0]; k <= r[2][1]; ++k)
      for (std::int64_t j = r[1][0]; j <= r[1][1]; ++j)
        for (std::int64_t i = r[0][0]; i <= r[0][1]; ++i) fn(cell_index(i, j, k), i, j, k);
  }
  Point origin_{};
  double cell_ = 1.0;
  double inverse_cell_ = 1.0;  // 1 / cell_: cell coordinates by multiplication
  std::array<std::int64_t, 3> dims_{1, 1, 1};
  // The cells' lists in flat storage (cell_lists.h), chunks of 64 and 256 bytes.
  CellLists<Index, 15> point_cells_;
  // An item's entry in a cell: its id and the part of its bounding box inside the cell, in units
  // of 1/255 of the cell from the cell's low corner, rounded outward, packed for a branch-free
  // overlap test: three 9-bit lanes (x, y, z) per word,
  //   lo: the low ends, and in bits 27..29 whether the item's cell range starts before this cell
  //       along x, y, z;
  //   hi: the high ends, each with its lane's top bit (256) set.
  // Subtracting a lane of one word from that of the other leaves the top bit set exactly when
  // the difference is >= 0 (see items_near).
  struct ItemEntry {
    std::uint32_t lo, hi;
    Index item;
  };
  static constexpr std::size_t kItemRun = 21;  // item entries per chunk of item_cells_
  static constexpr std::uint32_t kLanes = 0x07FFFFFF;  // the three 9-bit lanes
  static constexpr std::uint32_t kTops = (1u << 8) | (1u << 17) | (1u << 26);
  static constexpr std::uint32_t kStartsBefore = 1u << 27;  // shifted by the axis
  using CellBox = std::array<std::array<std::uint8_t, 2>, 3>;  // [axis][lo, hi]
  // The box's cell range r and its bounds in the first and last cells of r along each axis:
  // ends[a][0] its low end within cell r[a][0], ends[a][1] its high end within cell r[a][1], in
  // 1/255ths of the cell from the scaled coordinate's fraction, rounded outward with half a unit
  // of slack (monotone in the coordinate, so two boxes that overlap overlap in these units too).
  void span_of(const Box& box, CellRange& r, CellBox& ends) const {
    for (int a = 0; a < 3; ++a) {
      const double t_lo = scaled(box.lo[a], a), t_hi = scaled(box.hi[a], a);
      r[a] = {cell_of_scaled(t_lo, a), cell_of_scaled(t_hi, a)};
      const double lo = std::floor((t_lo - static_cast<double>(r[a][0])) * 255.0 - 0.5);
      const double hi = std::ceil((t_hi - static_cast<double>(r[a][1])) * 255.0 + 0.5);
      ends[a][0] = static_cast<std::uint8_t>(std::clamp(lo, 0.0, 255.0));  // NaN-free: boxes
      ends[a][1] = static_cast<std::uint8_t>(std::clamp(hi, 0.0, 255.0));  // hold finite points
    }
  }
  // The part of the box inside cell (i, j, k) of its range, packed as ItemEntry::lo and ::hi (the
  // ends in the first and last cells, the whole cell 0..255 between them), and the cell's
  // starts-before bits.
  static std::array<std::uint32_t, 2> cell_words(const CellBox& ends, const CellRange& r,
                                                 std::int64_t i, std::int64_t j, std::int64_t k);
  CellLists<ItemEntry, kItemRun> item_cells_;
  std::unique_ptr<FrontTree> tree_;  // set: adaptive bins, the grid unused
};

// Not in the paper: whether a front's bins should become adaptive (FrontBins::Adaptive, through
// AdvancingFront::use_adaptive_bins). The front counts its queries (its own unit of work: a
// crossing check, a face deletion) and the points they looked at; a window of at least `window`
// queries that looked at more than `bound` points per query says the sizes span far more than
// the cells. The surface front (S6) and the volume front (F7.3) each keep one.
struct BinsWatch {
  std::int64_t queries = 0;
  std::int64_t points = 0;
  // False until `window` queries are counted; then whether they were crowded, and a new window
  // starts.
  bool crowded(std::int64_t window, std::int64_t bound) {
    if (queries < window) return false;
    const bool over = points > bound * queries;
    queries = points = 0;
    return over;
  }
};

// An item's entry passes in cell (i, j, k) of the query's range when, on each axis, the query's
// part of the cell (q) and the item's (e) overlap: q.hi - e.lo >= 0 and e.hi - q.lo >= 0, read
// from the lanes' top bits; and the cell is the lowest of both ranges: no axis along which both
// the item's range and the query's start before this cell. The entries of a cell are filtered
// branch-free into a buffer (every entry is written, the count advances by the test's outcome)
// before fn sees them.
template <typename Fn>
bool FrontBins::find_item_near(const Box& box, Fn&& fn) const {
  if (tree_) return tree_->find_item_near(box, fn);
  CellRange r;
  CellBox ends;
  span_of(box, r, ends);
  Index passed[kItemRun];
  for (std::int64_t k = r[2][0]; k <= r[2][1]; ++k) {
    for (std::int64_t j = r[1][0]; j <= r[1][1]; ++j) {
      for (std::int64_t i = r[0][0]; i <= r[0][1]; ++i) {
        const auto c = static_cast<std::size_t>(cell_index(i, j, k));
        if (item_cells_.empty(c)) continue;
        // Not a structured binding: clang 14 (the fuzz preset) cannot capture one in a lambda.
        const std::array<std::uint32_t, 2> words = cell_words(ends, r, i, j, k);
        const std::uint32_t q_lo = words[0], q_hi = words[1];
        const std::uint32_t query_before = q_lo & ~kLanes;  // axes where the query starts before
        const std::uint32_t q_low_ends = q_lo & kLanes;
        const bool found = item_cells_.find_run(c, [&](const ItemEntry* run, std::size_t size) {
          std::size_t n = 0;
          for (std::size_t e = 0; e < size; ++e) {
            const ItemEntry& entry = run[e];
            const std::uint32_t overlap =
                (q_hi - (entry.lo & kLanes)) & (entry.hi - q_low_ends) & kTops;
            passed[n] = entry.item;
            n += (overlap | (entry.lo & query_before)) == kTops;
          }
          for (std::size_t m = 0; m < n; ++m)
            if (fn(passed[m])) return true;
          return false;
        });
        if (found) return true;
      }
    }
  }
  return false;
}

}  // namespace afmesh
