#include "core/sizing/spec_size_field.h"

#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

namespace afmesh {
namespace {

// A cell's sources are copied into one contiguous set and evaluated in Eigen blocks when the cell
// keeps at least kDenseCellSources sources and holds at least kDenseCellPoints points of a
// batch. Otherwise each point walks the cell's list alone: with few sources per cell a point
// typically stops after one to four of them, fewer than one block.
constexpr Index kDenseCellSources = 4 * SourceSet::kBlock;
constexpr Index kDenseCellPoints = 4;

bool finite_box(const Box& box) {
  for (int k = 0; k < 3; ++k) {
    if (!std::isfinite(box.lo[k]) || !std::isfinite(box.hi[k]) || box.lo[k] > box.hi[k]) {
      return false;
    }
  }
  return true;
}

// `box` grown on every side by 1% of its largest extent, or by `fallback` for a single point.
Box padded(const Box& box, double fallback) {
  double largest = 0.0;
  for (int k = 0; k < 3; ++k) largest = std::max(largest, box.hi[k] - box.lo[k]);
  const double pad = largest > 0.0 ? 0.01 * largest : fallback;
  return grown(box, pad);
}

}  // namespace

absl::StatusOr<SpecSizeField> SpecSizeField::create(const SizeSpec& spec, const Box& domain,
                                                    const SpecSizeFieldParams& params) {
  if (absl::Status s = validate_size_spec(spec); !s.ok()) return s;
  if (!finite_box(domain)) {
    return absl::InvalidArgumentError(
        "the size field's domain box must be finite and non-empty (lo <= hi on every axis)");
  }
  const Box box = padded(domain, spec.max_size);
  SpecSizeField field;
  field.max_size_ = spec.max_size;
  field.growth_ = spec.growth;
  if (spec.background) {
    absl::StatusOr<BackgroundGrid> grid = BackgroundGrid::from_spec(*spec.background);
    if (!grid.ok()) return grid.status();
    field.background_ = *std::move(grid);
  } else {
    field.background_ = BackgroundGrid::box_grid(box, spec.max_size);
  }
  field.sources_ = SourceSet(spec.sources);
  if (params.prune_sources && field.sources_.count() > 0) {
    field.cells_ = SourceCells(field.sources_, box, spec.max_size, params.max_pruning_cells);
    for (Index c = 0; c < field.cells_.cell_count(); ++c) {
      const Index kept = static_cast<Index>(field.cells_.sources(c).size());
      field.dense_cells_ = field.dense_cells_ || kept >= kDenseCellSources;
    }
  }
  return field;
}

SpecSizeField::SpecSizeField(const SpecSizeField& other)
    : SizeField(other),
      max_size_(other.max_size_),
      growth_(other.growth_),
      background_(other.background_),
      sources_(other.sources_),
      cells_(other.cells_),
      dense_cells_(other.dense_cells_),
      last_tet_(other.last_tet_.load(std::memory_order_relaxed)) {}

SpecSizeField::SpecSizeField(SpecSizeField&& other) noexcept
    : max_size_(other.max_size_),
      growth_(other.growth_),
      background_(std::move(other.background_)),
      sources_(std::move(other.sources_)),
      cells_(std::move(other.cells_)),
      dense_cells_(other.dense_cells_),
      last_tet_(other.last_tet_.load(std::memory_order_relaxed)) {}

SpecSizeField& SpecSizeField::operator=(const SpecSizeField& other) {
  SpecSizeField copy(other);
  return *this = std::move(copy);
}

SpecSizeField& SpecSizeField::operator=(SpecSizeField&& other) noexcept {
  max_size_ = other.max_size_;
  growth_ = other.growth_;
  background_ = std::move(other.background_);
  sources_ = std::move(other.sources_);
  cells_ = std::move(other.cells_);
  dense_cells_ = other.dense_cells_;
  last_tet_.store(other.last_tet_.load(std::memory_order_relaxed), std::memory_order_relaxed);
  return *this;
}

// min(upper, every source at x), through x's pruning cell when it has one.
double SpecSizeField::source_minimum(const Point& x, double upper) const {
  const Index cell = cells_.cell_of(x);
  if (cell == kInvalidIndex) return sources_.min_size(x, upper);
  return cell_minimum(cell, x, upper);
}

// min(upper, the sources of `cell` at x), walking its list until a lower bound reaches the
// minimum so far.
double SpecSizeField::cell_minimum(Index cell, const Point& x, double upper) const {
  const std::span<const Index> ids = cells_.sources(cell);
  const std::span<const double> lower = cells_.lower_bounds(cell);
  double current = upper;
  for (std::size_t k = 0; k < ids.size() && lower[k] < current; ++k) {
    current = std::min(current, sources_.size(ids[k], x));
  }
  return current;
}

double SpecSizeField::size_at(const Point& x) const {
  BackgroundGrid::Hint hint{last_tet_.load(std::memory_order_relaxed)};
  const double upper = std::min(max_size_, background_.size_at(x, &hint));
  last_tet_.store(hint.tet, std::memory_order_relaxed);
  return source_minimum(x, upper);
}

// For the points xs[points[i]] of one cell: out[p] = min(out[p], the cell's sources at xs[p]).
void SpecSizeField::cell_minima(Index cell, std::span<const Point> xs,
                                std::span<const Index> points, std::span<double> out) const {
  if (static_cast<Index>(points.size()) < kDenseCellPoints ||
      static_cast<Index>(cells_.sources(cell).size()) < kDenseCellSources) {
    for (Index p : points) out[p] = cell_minimum(cell, xs[p], out[p]);
    return;
  }
  const SourceSet local = sources_.gather(cells_.sources(cell));
  const std::span<const double> lower = cells_.lower_bounds(cell);
  for (Index p : points) out[p] = local.min_size_bounded(xs[p], out[p], lower);
}

void SpecSizeField::sizes_at(std::span<const Point> xs, std::span<double> out) const {
  BackgroundGrid::Hint hint{last_tet_.load(std::memory_order_relaxed)};
  for (std::size_t i = 0; i < xs.size(); ++i) {
    out[i] = std::min(max_size_, background_.size_at(xs[i], &hint));
  }
  last_tet_.store(hint.tet, std::memory_order_relaxed);
  if (sources_.count() == 0) return;
  if (dense_cells_) {
    minima_by_cell(xs, out);
    return;
  }
  for (std::size_t i = 0; i < xs.size(); ++i) out[i] = source_minimum(xs[i], out[i]);
}

// out[i] = min(out[i], every source at xs[i]), the points grouped by pruning cell (a counting
// sort; the points outside every cell first, evaluated against all sources).
void SpecSizeField::minima_by_cell(std::span<const Point> xs, std::span<double> out) const {
  const Index n = static_cast<Index>(xs.size());
  const Index cells = cells_.cell_count();
  std::vector<Index> bucket(n), end(cells + 2, 0);  // bucket 0: outside; c + 1: cell c
  for (Index i = 0; i < n; ++i) {
    bucket[i] = cells_.cell_of(xs[i]) + 1;
    ++end[bucket[i] + 1];
  }
  for (Index b = 0; b <= cells; ++b) end[b + 1] += end[b];  // end[b]: start of bucket b
  std::vector<Index> order(n);
  for (Index i = 0; i < n; ++i) order[end[bucket[i]]++] = i;  // end[b]: now the end of bucket b

  for (Index i = 0; i < end[0]; ++i) {
    const Index p = order[i];
    out[p] = sources_.min_size(xs[p], out[p]);
  }
  for (Index c = 0; c < cells; ++c) {
    const std::span<const Index> points(order.data() + end[c], end[c + 1] - end[c]);
    if (!points.empty()) cell_minima(c, xs, points, out);
  }
}

absl::StatusOr<std::unique_ptr<SizeField>> make_size_field(const std::optional<SizeSpec>& spec,
                                                           double size,
                                                           const std::vector<Point>& points) {
  if (!spec) return std::make_unique<UniformSize>(size);
  Box domain = empty_box();
  for (const Point& p : points) enclose(domain, p);
  absl::StatusOr<SpecSizeField> field = SpecSizeField::create(*spec, domain);
  if (!field.ok()) return field.status();
  return std::make_unique<SpecSizeField>(*std::move(field));
}

}  // namespace afmesh
