#include "core/surface/split_lines.h"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <limits>

#include "absl/status/status.h"
#include "absl/strings/str_format.h"
#include "core/geometry/vec.h"
#include "core/quality/compensated_sum.h"
#include "core/sizing/attached_sizes.h"

namespace afmesh {
namespace {

// A piece of segment `segment` between parameters t0 and t1 (0 at its first point, 1 at its
// second), length `length`, with 1/h = g0 and g1 at its ends and ∫ ds/h = f0 at its start.
struct Piece {
  Index segment = 0;
  double t0 = 0.0;
  double t1 = 0.0;
  double length = 0.0;
  double f0 = 0.0;
  double g0 = 0.0;
  double g1 = 0.0;
};

absl::Status check_polyline(std::span<const Point> polyline, const SplitLineParams& params) {
  if (polyline.size() < 2) {
    return absl::InvalidArgumentError(
        absl::StrFormat("split line: %d points; a line needs two", polyline.size()));
  }
  if (params.samples_per_size < 1 || params.max_sides < 1 || params.min_sides < 1) {
    return absl::InvalidArgumentError(
        "split line: samples_per_size, max_sides and min_sides must be at least 1");
  }
  if (params.min_sides > params.max_sides) {
    return absl::InvalidArgumentError(absl::StrFormat(
        "split line: min_sides %d is over max_sides %d", params.min_sides, params.max_sides));
  }
  if (!(params.start_size > 0.0) || !(params.end_size > 0.0) || !(params.growth >= 1.0) ||
      !std::isfinite(params.growth)) {
    return absl::InvalidArgumentError(absl::StrFormat(
        "split line: end sizes %g and %g must be > 0 and growth %g a finite number >= 1",
        params.start_size, params.end_size, params.growth));
  }
  for (std::size_t i = 0; i < polyline.size(); ++i) {
    for (double c : polyline[i]) {
      if (!std::isfinite(c)) {
        return absl::InvalidArgumentError(
            absl::StrFormat("split line: point %d has a non-finite coordinate", i));
      }
    }
  }
  return absl::OkStatus();
}

// Arc length at every polyline point (P values; the last is the line's length).
std::vector<double> arc_lengths(std::span<const Point> polyline) {
  std::vector<double> arc(polyline.size(), 0.0);
  CompensatedSum sum;
  for (std::size_t i = 0; i + 1 < polyline.size(); ++i) {
    sum.add(distance(polyline[i], polyline[i + 1]));
    arc[i + 1] = sum.value();
  }
  return arc;
}

// 1/h at polyline point x, arc length s of a line of length `length`: h is the field's size,
// bounded by the end sizes grown along the line (§4.2, eq. 15). An error when the field's size
// is not a finite number > 0.
absl::StatusOr<double> inverse_size(const SizeField& sizes, const Point& x, double s, double length,
                                    const SplitLineParams& params) {
  const double field = sizes.size_at(add(x, params.field_origin));
  const double h =
      std::min({field, size_grown_over(params.start_size, params.growth, s),
                size_grown_over(params.end_size, params.growth, std::max(0.0, length - s))});
  if (!(field > 0.0) || !std::isfinite(field)) {
    return absl::InvalidArgumentError(absl::StrFormat(
        "split line: the size field gives %g at (%g, %g, %g); sizes must be finite and > 0", field,
        x[0], x[1], x[2]));
  }
  return 1.0 / h;
}

// The pieces of the whole polyline and ∫ ds/h over it (trapezoidal rule on each piece).
absl::StatusOr<std::vector<Piece>> integrate(std::span<const Point> polyline,
                                             const std::vector<double>& arc, const SizeField& sizes,
                                             const SplitLineParams& params, double& total) {
  std::vector<Piece> pieces;
  CompensatedSum integral;
  absl::StatusOr<double> g = inverse_size(sizes, polyline[0], 0.0, arc.back(), params);
  if (!g.ok()) return g.status();
  const double piece_limit = static_cast<double>(params.max_sides) * params.samples_per_size;
  for (Index i = 0; i + 1 < static_cast<Index>(polyline.size()); ++i) {
    const double length = distance(polyline[i], polyline[i + 1]);
    if (!(length > 0.0)) continue;
    for (double t0 = 0.0; t0 < 1.0;) {
      const double step = 1.0 / (*g * params.samples_per_size * length);
      const double t1 = t0 + step >= 1.0 ? 1.0 : t0 + step;
      const Point x1 = t1 == 1.0 ? polyline[i + 1] : lerp(polyline[i], polyline[i + 1], t1);
      const absl::StatusOr<double> g1 =
          inverse_size(sizes, x1, arc[i] + t1 * length, arc.back(), params);
      if (!g1.ok()) return g1.status();
      Piece piece{i, t0, t1, (t1 - t0) * length, integral.value(), *g, *g1};
      integral.add(piece.length * 0.5 * (piece.g0 + piece.g1));
      pieces.push_back(piece);
      if (static_cast<double>(pieces.size()) > piece_limit) {
        return absl::ResourceExhaustedError(absl::StrFormat(
            "split line: the size field asks for more than %d sides", params.max_sides));
      }
      g = g1;
      t0 = t1;
    }
  }
  if (pieces.empty()) return absl::InvalidArgumentError("split line: the polyline has no length");
  total = integral.value();
  return pieces;
}

// The parameter in [0, 1] across `piece` where ∫ ds/h reaches `target`: the root of
// f0 + length (g0 τ + (g1 - g0) τ² / 2) = target, in the form without cancellation.
double solve_in_piece(const Piece& piece, double target) {
  const double q = (target - piece.f0) / piece.length;
  const double root =
      std::sqrt(std::max(0.0, piece.g0 * piece.g0 + 2.0 * (piece.g1 - piece.g0) * q));
  return std::clamp(2.0 * q / (piece.g0 + root), 0.0, 1.0);
}

}  // namespace

absl::StatusOr<LineSplit> split_line(std::span<const Point> polyline, const SizeField& sizes,
                                     const SplitLineParams& params) {
  if (absl::Status status = check_polyline(polyline, params); !status.ok()) return status;
  const std::vector<double> segment_start = arc_lengths(polyline);
  double total = 0.0;
  absl::StatusOr<std::vector<Piece>> pieces =
      integrate(polyline, segment_start, sizes, params, total);
  if (!pieces.ok()) return pieces.status();
  const double rounded = std::max(static_cast<double>(params.min_sides), std::round(total));
  if (rounded > static_cast<double>(params.max_sides)) {
    return absl::ResourceExhaustedError(
        absl::StrFormat("split line: the size field asks for %g sides, over the limit of %d",
                        rounded, params.max_sides));
  }
  const auto n = static_cast<Index>(rounded);

  LineSplit split;
  split.points.reserve(n + 1);
  split.points.push_back(polyline.front());
  split.arc_length.push_back(0.0);
  split.segment.push_back(0);
  auto piece = pieces->begin();
  for (Index j = 1; j < n; ++j) {
    const double target = total * static_cast<double>(j) / static_cast<double>(n);
    // Targets ascend, so the piece holding each is found by moving forward.
    while (std::next(piece) != pieces->end() && std::next(piece)->f0 <= target) ++piece;
    const double t = piece->t0 + solve_in_piece(*piece, target) * (piece->t1 - piece->t0);
    const Index i = piece->segment;
    split.points.push_back(lerp(polyline[i], polyline[i + 1], t));
    split.arc_length.push_back(segment_start[i] + t * distance(polyline[i], polyline[i + 1]));
    split.segment.push_back(i);
  }
  split.points.push_back(polyline.back());
  split.arc_length.push_back(segment_start.back());
  split.segment.push_back(static_cast<Index>(polyline.size()) - 2);
  return split;
}

std::vector<LineEndSizes> line_end_sizes(const DiscreteSurface& surface,
                                         const SurfaceFeatures& features) {
  std::vector<double> length(features.lines.size(), 0.0);
  for (std::size_t l = 0; l < features.lines.size(); ++l) {
    CompensatedSum sum;
    const std::vector<Index>& v = features.lines[l].vertices;
    for (std::size_t i = 0; i + 1 < v.size(); ++i) {
      sum.add(distance(surface.local_points()[v[i]], surface.local_points()[v[i + 1]]));
    }
    length[l] = sum.value();
  }
  // The shortest line at each corner; corners are ascending by vertex.
  const auto shortest_at = [&](Index vertex) {
    const auto corner = std::lower_bound(features.corners.begin(), features.corners.end(), vertex,
                                         [](const Corner& c, Index v) { return c.vertex < v; });
    double shortest = std::numeric_limits<double>::infinity();
    for (LineId l : corner->lines) shortest = std::min(shortest, length[index_of(l)]);
    return shortest;
  };
  std::vector<LineEndSizes> sizes;
  sizes.reserve(features.lines.size());
  for (std::size_t l = 0; l < features.lines.size(); ++l) {
    const DiscreteLine& line = features.lines[l];
    sizes.push_back({shortest_at(line.vertices.front()), shortest_at(line.vertices.back())});
  }
  return sizes;
}

}  // namespace afmesh
