// The size field of a size specification (paper §4.1–4.2):
//
//   delta(x) = min(max_size, delta_bg(x), delta_1(x), ..., delta_m(x))        (eq. 14)
//
// over the background grid (the given one, or the domain's box split into five tets with
// max_size at every corner) and the sources (eq. 1–13). The growth factor of eq. 15 is applied by
// the front with the sizes attached to its points (attached_sizes.h); growth() carries it.
//
// Evaluation: sources live in struct-of-arrays blocks evaluated with Eigen (source_set.h); with
// pruning on, the domain's box is split into cells that each list only the sources that can give
// the minimum there, by ascending lower bound (source_cells.h), and points outside the box fall
// back to every source. Pruning never changes a result: size_at and sizes_at give the same
// doubles with or without it.
//
// Thread safety: const methods may be called from several threads at once. size_at keeps the
// last background tet found as a walk start in a relaxed atomic; it only speeds up the next
// search and never changes a result.
#pragma once

#include <atomic>
#include <memory>
#include <optional>
#include <span>

#include "absl/status/statusor.h"
#include "core/mesh/mesh.h"
#include "core/sizing/background_grid.h"
#include "core/sizing/size_field.h"
#include "core/sizing/size_spec.h"
#include "core/sizing/source_cells.h"
#include "core/sizing/source_set.h"
#include "core/spatial/box.h"

namespace afmesh {

struct SpecSizeFieldParams {
  // Skip sources that cannot give the minimum (never changes a result; off to measure it).
  bool prune_sources = true;
  // Largest number of pruning cells over the domain; fewer are used when there are many sources
  // (building costs two bounds per cell and source).
  int max_pruning_cells = 4096;
};

class SpecSizeField final : public SizeField {
 public:
  // The field of `spec` over `domain`, the box the field is mostly queried in (the input's
  // bounding box). The default background grid and the pruning cells cover `domain` grown on
  // every side by 1% of its largest extent (by max_size when it is a single point); points
  // outside are still answered exactly. INVALID_ARGUMENT when validate_size_spec(spec) fails,
  // or when `domain` is empty or not finite.
  static absl::StatusOr<SpecSizeField> create(const SizeSpec& spec, const Box& domain,
                                              const SpecSizeFieldParams& params = {});

  SpecSizeField(const SpecSizeField& other);
  SpecSizeField(SpecSizeField&& other) noexcept;
  SpecSizeField& operator=(const SpecSizeField& other);
  SpecSizeField& operator=(SpecSizeField&& other) noexcept;

  // delta(x) of eq. 14 at a finite x: > 0 and <= max_size().
  double size_at(const Point& x) const override;

  // out[i] = size_at(xs[i]) bit for bit; `out` holds xs.size() values. When some pruning cell
  // keeps many sources, points are grouped by cell and such a cell holding several points has its
  // sources copied into one contiguous set evaluated in Eigen blocks; points outside every cell
  // are evaluated against all sources in Eigen blocks.
  void sizes_at(std::span<const Point> xs, std::span<double> out) const override;

  double max_size() const { return max_size_; }
  // c_i of eq. 15.
  double growth() const { return growth_; }
  const BackgroundGrid& background() const { return background_; }
  const SourceSet& sources() const { return sources_; }
  const SourceCells& cells() const { return cells_; }

 private:
  SpecSizeField() = default;

  double source_minimum(const Point& x, double upper) const;
  double cell_minimum(Index cell, const Point& x, double upper) const;
  void cell_minima(Index cell, std::span<const Point> xs, std::span<const Index> points,
                   std::span<double> out) const;
  void minima_by_cell(std::span<const Point> xs, std::span<double> out) const;

  double max_size_ = 0.0;
  double growth_ = 1.0;
  BackgroundGrid background_;
  SourceSet sources_;
  SourceCells cells_;          // empty when pruning is off
  bool dense_cells_ = false;   // some cell keeps enough sources for gathered blocks (sizes_at)
  mutable std::atomic<Index> last_tet_{kInvalidIndex};
};

// F2: the size in space for a job over the points `points`: `spec`'s sources and background
// grid (eq. 1–14) over their bounding box, or the uniform `size` when there is no spec.
absl::StatusOr<std::unique_ptr<SizeField>> make_size_field(const std::optional<SizeSpec>& spec,
                                                           double size,
                                                           const std::vector<Point>& points);

}  // namespace afmesh
