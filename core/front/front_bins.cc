#include "core/front/front_bins.h"

#include <algorithm>
#include <cmath>

namespace afmesh {

FrontBins::FrontBins(const Box& domain, double cell_size, std::int64_t max_cells)
    : origin_(domain.lo), cell_(cell_size) {
  std::array<double, 3> extent{};
  for (int a = 0; a < 3; ++a) extent[a] = std::max(domain.hi[a] - domain.lo[a], 0.0);
  // Grow the cell until the grid fits in max_cells.
  for (;;) {
    std::int64_t total = 1;
    for (int a = 0; a < 3; ++a) {
      dims_[a] = std::max<std::int64_t>(1, static_cast<std::int64_t>(std::ceil(extent[a] / cell_)));
      total *= dims_[a];
    }
    if (total <= max_cells) break;
    cell_ *= 1.25;
  }
  inverse_cell_ = 1.0 / cell_;
  const auto n = static_cast<std::size_t>(dims_[0] * dims_[1] * dims_[2]);
  point_cells_ = CellLists<Index, 15>(n);
  item_cells_ = CellLists<ItemEntry, kItemRun>(n);
}

std::array<std::uint32_t, 2> FrontBins::cell_words(const CellBox& ends, const CellRange& r,
                                                   std::int64_t i, std::int64_t j,
                                                   std::int64_t k) {
  const std::int64_t ijk[3] = {i, j, k};
  std::uint32_t lo = 0, hi = 0;
  for (int a = 0; a < 3; ++a) {
    const bool first = ijk[a] == r[a][0];
    const std::uint32_t l = first ? ends[a][0] : 0u;
    const std::uint32_t h = ijk[a] == r[a][1] ? ends[a][1] : 255u;
    lo |= l << (9 * a);
    hi |= (h | 256u) << (9 * a);
    if (!first) lo |= kStartsBefore << a;
  }
  return {lo, hi};
}

FrontBins::FrontBins(const Box& domain, double cell_size, Adaptive)
    : origin_(domain.lo),
      cell_(cell_size),
      point_cells_(1),
      item_cells_(1),
      tree_(std::make_unique<FrontTree>(domain)) {}

void FrontBins::insert_point(Index p, const Point& x) {
  if (tree_) return tree_->insert_point(p, x);
  point_cells_.push_back(point_cell(x), p);
}

void FrontBins::erase_point(Index p, const Point& x) {
  if (tree_) return tree_->erase_point(p, x);
  point_cells_.erase_first(point_cell(x), [p](Index q) { return q == p; });
}

void FrontBins::insert_item(Index f, const Box& box) {
  if (tree_) return tree_->insert_item(f, box);
  CellRange r;
  CellBox ends;
  span_of(box, r, ends);
  for_each_cell(r, [&](std::int64_t c, std::int64_t i, std::int64_t j, std::int64_t k) {
    const auto [lo, hi] = cell_words(ends, r, i, j, k);
    item_cells_.push_back(static_cast<std::size_t>(c), {lo, hi, f});
  });
}

void FrontBins::erase_item(Index f, const Box& box) {
  if (tree_) return tree_->erase_item(f, box);
  for_each_cell(cells_of(box), [&](std::int64_t c, std::int64_t, std::int64_t, std::int64_t) {
    item_cells_.erase_first(static_cast<std::size_t>(c),
                            [f](const ItemEntry& e) { return e.item == f; });
  });
}

void FrontBins::points_near(const Box& box, std::vector<Index>& out) const {
  for_each_point_near(box, [&](Index p) { out.push_back(p); });
}

void FrontBins::items_near(const Box& box, std::vector<Index>& out) const {
  find_item_near(box, [&](Index f) {
    out.push_back(f);
    return false;
  });
}

}  // namespace afmesh
