#include "core/sizing/source_cells.h"

#include <algorithm>
#include <cmath>
#include <utility>

namespace afmesh {
namespace {

constexpr Index kMaxCellsPerAxis = 256;

// Index i with planes[i] <= v <= planes[i + 1], or kInvalidIndex outside [front, back]. The
// first guess from the uniform spacing is corrected against the stored planes, so the answer
// holds exactly.
Index slab_of(const std::vector<double>& planes, double v) {
  const Index n = static_cast<Index>(planes.size()) - 1;
  if (!(v >= planes.front() && v <= planes.back())) return kInvalidIndex;
  const double t = (v - planes.front()) / (planes.back() - planes.front());
  Index i = std::isfinite(t) ? static_cast<Index>(t * n) : 0;
  i = std::clamp<Index>(i, 0, n - 1);
  while (i > 0 && v < planes[i]) --i;
  while (i < n - 1 && v > planes[i + 1]) ++i;
  return i;
}

}  // namespace

SourceCells::SourceCells(const SourceSet& sources, const Box& box, double max_size,
                         int max_cells, std::int64_t budget) {
  const std::int64_t per_source = budget / std::max<std::int64_t>(sources.count(), 1);
  const std::int64_t most = std::max(max_cells, 1);
  choose_cells(box, static_cast<Index>(std::clamp<std::int64_t>(per_source, 1, most)));
  const Index cells = static_cast<Index>(planes_[0].size() - 1) *
                      static_cast<Index>(planes_[1].size() - 1) *
                      static_cast<Index>(planes_[2].size() - 1);
  offsets_.assign(1, 0);
  for (Index c = 0; c < cells; ++c) fill_cell(sources, c, max_size);
}

// Splits each axis into about extent / h slabs, h chosen so that there are about `target`
// cells; an axis of zero extent gets one slab.
void SourceCells::choose_cells(const Box& box, Index target) {
  double largest = 0.0;
  for (int k = 0; k < 3; ++k) largest = std::max(largest, box.hi[k] - box.lo[k]);
  double volume = 1.0;
  for (int k = 0; k < 3; ++k) volume *= std::max(box.hi[k] - box.lo[k], 1e-3 * largest);
  const double h = std::cbrt(volume / target);
  for (int k = 0; k < 3; ++k) {
    const double extent = box.hi[k] - box.lo[k];
    const double slabs = h > 0.0 ? std::ceil(extent / h) : 1.0;
    const Index n = static_cast<Index>(std::clamp(slabs, 1.0, double{kMaxCellsPerAxis}));
    planes_[k].resize(n + 1);
    for (Index i = 0; i <= n; ++i) planes_[k][i] = box.lo[k] + extent * i / n;
    planes_[k].back() = box.hi[k];
  }
}

// Appends the list of cell c: the sources whose lower bound is <= U, by ascending bound.
void SourceCells::fill_cell(const SourceSet& sources, Index c, double max_size) {
  const Box cell = cell_box(c);
  double upper = max_size;
  for (Index s = 0; s < sources.count(); ++s) {
    if (sources.smallest_size(s) < upper) {
      upper = std::min(upper, sources.size_upper_bound(s, cell));
    }
  }
  std::vector<std::pair<double, Index>> kept;
  for (Index s = 0; s < sources.count(); ++s) {
    if (sources.smallest_size(s) * (1.0 - SourceSet::kBoundMargin) > upper) continue;
    const double lower = sources.size_lower_bound(s, cell);
    if (lower <= upper) kept.emplace_back(lower, s);
  }
  std::sort(kept.begin(), kept.end());
  for (const auto& [lower, s] : kept) {
    ids_.push_back(s);
    lower_.push_back(lower);
  }
  offsets_.push_back(static_cast<Index>(ids_.size()));
}

Index SourceCells::cell_of(const Point& x) const {
  if (offsets_.empty()) return kInvalidIndex;
  Index slab[3];
  for (int k = 0; k < 3; ++k) {
    slab[k] = slab_of(planes_[k], x[k]);
    if (slab[k] == kInvalidIndex) return kInvalidIndex;
  }
  const Index ny = static_cast<Index>(planes_[1].size() - 1);
  const Index nz = static_cast<Index>(planes_[2].size() - 1);
  return (slab[0] * ny + slab[1]) * nz + slab[2];
}

Box SourceCells::cell_box(Index c) const {
  const Index ny = static_cast<Index>(planes_[1].size() - 1);
  const Index nz = static_cast<Index>(planes_[2].size() - 1);
  const Index slab[3] = {c / (ny * nz), (c / nz) % ny, c % nz};
  Box box;
  for (int k = 0; k < 3; ++k) {
    box.lo[k] = planes_[k][slab[k]];
    box.hi[k] = planes_[k][slab[k] + 1];
  }
  return box;
}

std::span<const Index> SourceCells::sources(Index c) const {
  return {ids_.data() + offsets_[c], static_cast<std::size_t>(offsets_[c + 1] - offsets_[c])};
}

std::span<const double> SourceCells::lower_bounds(Index c) const {
  return {lower_.data() + offsets_[c], static_cast<std::size_t>(offsets_[c + 1] - offsets_[c])};
}

}  // namespace afmesh
