// Sides along a discrete line (paper §1, step F3: "generate sides along the lines that connect
// surface patches. These sides form an initial front for the triangulation of the surface
// patches").
//
// A line is a polyline of input points from corner to corner (features.h). Its sides follow the
// wanted size h(x) of a SizeField (core/sizing/size_field.h): with s the arc length along the
// polyline and I = ∫ ds / h(s) the line's length in units of the local size,
//   n = max(min_sides, round(I)) sides (params.min_sides: 1, or 3 for a closed loop, which
// fewer sides cannot bound), and the end of side j at the s_j where ∫_0^{s_j} ds/h = j I / n,
// so every side spans the same share of the size-scaled length (a side is about h long where h
// varies slowly). The paper gives no rule for the count or the placement; these are ours. The
// ends stay fixed at the corners (bit for bit: corners are shared by the lines and patches that
// meet there); the other points lie on the polyline's segments.
//
// The integral is evaluated by the trapezoidal rule on 1/h over pieces of each segment no longer
// than h / samples_per_size (h taken at the piece's start), so it needs about
// samples_per_size · n + (segments) size queries. Within a piece 1/h is taken linear, and the
// s_j are found by solving that piece's quadratic exactly: for a uniform size they are equally
// spaced to rounding. Sums use compensated summation, so long lines do not drift.
//
// Sizes attached to the corners (paper §4.2): "assigning to the end-points of lines a point size
// that is related to the minimum length of the lines surrounding it [...] is a natural way to
// assign proper element sizes to regions where small lines occur". `line_end_sizes` gives each
// line's corners the length of the shortest line ending there; split_line bounds the size by
// them, grown along the line by the growth factor c_i of eq. 15 in its continuous form: sides
// growing by c_i per side from a corner of size h_A reach h_A + (c_i - 1) s at arc length s.
#pragma once

#include <limits>
#include <span>
#include <vector>

#include "absl/status/statusor.h"
#include "core/mesh/mesh.h"
#include "core/sizing/size_field.h"
#include "core/surface/discrete_surface.h"
#include "core/surface/features.h"

namespace afmesh {

struct SplitLineParams {
  // Integration pieces per local size (>= 1). 8 keeps the error of the trapezoidal rule on a
  // size field that changes by its own value over ~one size below 1% of a side.
  int samples_per_size = 8;
  // Added to the polyline's points before the size field is asked: a polyline in the local frame
  // of a DiscreteSurface passes surface.origin(), since size fields work in global coordinates.
  Point field_origin{0.0, 0.0, 0.0};
  // Sizes attached to the first and the last point (> 0; +infinity: none) and their growth c_i
  // (>= 1; 1 keeps the corner's size along the whole line, the paper's uniform case). The size
  // at arc length s of a line of length L is at most
  //   min(start_size + (growth - 1) s, end_size + (growth - 1) (L - s)).
  double start_size = std::numeric_limits<double>::infinity();
  double end_size = std::numeric_limits<double>::infinity();
  double growth = 1.0;
  // Refuse (RESOURCE_EXHAUSTED) a line that would need more than this many sides: a size field
  // far too fine for the line is a mistake to report, not to allocate.
  Index max_sides = 10'000'000;
  // At least this many sides (>= 1, at most max_sides), however coarse the size: 3 for a closed
  // loop, whose one side would run from its corner to itself and whose two would enclose
  // nothing.
  Index min_sides = 1;
};

// The points that split a polyline into sides, n + 1 of them for n sides.
struct LineSplit {
  std::vector<Point> points;       // (n+1)×3: points[0] = polyline.front(), points[n] = back()
  std::vector<double> arc_length;  // n+1: s of each point along the polyline (0 ... length)
  std::vector<Index> segment;      // n+1: the polyline segment [i, i+1] each point lies on
};

// The sizes of a line's two ends (paper §4.2).
struct LineEndSizes {
  double start = 0.0;  // at vertices.front()
  double end = 0.0;    // at vertices.back()
};

// For every line of `features` (over `surface`), the length of the shortest line ending at each of
// its corners (a closed loop counts its whole length), in the units of the points: the
// start_size and end_size to split it with. features.lines.size() values.
std::vector<LineEndSizes> line_end_sizes(const DiscreteSurface& surface,
                                         const SurfaceFeatures& features);

// Splits `polyline` (P×3, P >= 2; consecutive points may coincide, a closed loop repeats its
// first point at the end) into sides following `sizes`, as above. INVALID_ARGUMENT for fewer
// than two points, a non-finite coordinate, a polyline of zero length, a size that is not a
// finite number > 0, or params out of range (samples_per_size, max_sides or min_sides below 1,
// min_sides over max_sides, end sizes not > 0, growth below 1); RESOURCE_EXHAUSTED past
// params.max_sides.
absl::StatusOr<LineSplit> split_line(std::span<const Point> polyline, const SizeField& sizes,
                                     const SplitLineParams& params = {});

}  // namespace afmesh
