// Pruning of sources (paper §4.1 warns that evaluating every source dominates for N_s > 100).
//
// A box (the domain) is split into uniform cells. For each cell, a source s is kept only if its
// lower bound over the cell, L_s = size_lower_bound(s, cell), is <= U = min(max_size, upper
// bounds of every source over the cell): any other source is larger than some kept source (or
// max_size) at every point of the cell, so it never gives the minimum of eq. 14. The kept sources
// are listed in ascending L_s; an evaluation walks them and stops at the first L_s >= the
// minimum so far. Both steps skip only sources whose size is >= a value already in the minimum,
// so the result is the same double as evaluating every source.
//
// Cost: building evaluates two bounds per (cell, source); the cell count is chosen to keep that
// near a fixed budget. Storage is one list of (source, bound) per cell, in one array.
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "core/mesh/mesh.h"
#include "core/sizing/source_set.h"
#include "core/spatial/box.h"

namespace afmesh {

class SourceCells {
 public:
  // No cells: every point is outside.
  SourceCells() = default;

  // Cells over `box` (non-empty, finite), about min(max_cells, budget / sources.count()) of
  // them, as close to cubes as the box allows. max_size > 0 caps every size (eq. 14).
  SourceCells(const SourceSet& sources, const Box& box, double max_size, int max_cells = 4096,
              std::int64_t budget = std::int64_t{1} << 21);

  // The cell whose closed box contains x, or kInvalidIndex when x is outside the box (or NaN).
  // The cell's box (cell_box) contains x exactly: no rounding puts x outside it.
  Index cell_of(const Point& x) const;

  // Number of cells.
  Index cell_count() const {
    return offsets_.empty() ? 0 : static_cast<Index>(offsets_.size() - 1);
  }

  // The closed box of cell c.
  Box cell_box(Index c) const;

  // The sources kept for cell c and their lower bounds over it, ascending by bound (ties by id).
  std::span<const Index> sources(Index c) const;
  std::span<const double> lower_bounds(Index c) const;

 private:
  void choose_cells(const Box& box, Index target);
  void fill_cell(const SourceSet& sources, Index c, double max_size);

  std::array<std::vector<double>, 3> planes_;  // per axis: n_k + 1 increasing cell boundaries
  std::vector<Index> offsets_;                 // cell_count + 1, into ids_ / lower_
  std::vector<Index> ids_;
  std::vector<double> lower_;
};

}  // namespace afmesh
