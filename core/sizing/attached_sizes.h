// Sizes attached to the input's points (paper §4.2, eq. 15).
//
// Every point of the input front carries a size delta_A. The paper assigns to the end points of
// lines "a point size that is related to the minimum length of the lines surrounding it", so
// that small input features get small elements without any source; by default each boundary
// point takes the shortest of its boundary edges (EdgeLengthRule::kMinimum; kMean, the mean of
// those lengths, is smoother on graded input). A user may override the size of single points or
// of every point of a tag (patch).
//
// A point created by the front then gets (eq. 15)
//   delta = min(delta_bg, delta_s, c_i · min(delta_A, delta_B, delta_C))
// where delta_bg and delta_s come from the SizeField and A, B, C are the face being deleted.
#pragma once

#include <algorithm>
#include <span>
#include <vector>

#include "absl/container/flat_hash_map.h"
#include "absl/status/statusor.h"
#include "core/mesh/mesh.h"

namespace afmesh {

enum class EdgeLengthRule {
  kMinimum,  // the shortest incident boundary edge (the paper's choice)
  kMean,     // the mean length of the incident boundary edges
};

struct AttachedSizeParams {
  // How a boundary point's default size follows from its incident edges.
  EdgeLengthRule rule = EdgeLengthRule::kMinimum;
  // Size (> 0) of every point of the triangles with a given tag (triangle_tags); a point on
  // several such tags gets the smallest. Replaces the edge-length default.
  absl::flat_hash_map<Index, double> tag_sizes;
  // Size (> 0) of single points by index; replaces both the tag size and the default.
  absl::flat_hash_map<Index, double> point_sizes;
};

// The attached size of every point of `surface` (N values for N points): the point override,
// else the smallest tag size of its triangles, else the edge-length rule over the edges of its
// triangles. A point on no triangle and without override gets +infinity (no bound in eq. 15).
// INVALID_ARGUMENT names the offending entry: a triangle index out of range, an override for a
// point out of range, or an override size that is not a finite number > 0.
absl::StatusOr<std::vector<double>> attached_point_sizes(const Mesh& surface,
                                                         const AttachedSizeParams& params = {});

// Eq. 15's last term: c_i · min(delta_A, delta_B, ...), the smallest attached size among
// `corners` (the points of the face or side being deleted, or of an end-game pocket; not empty)
// grown by `growth` = c_i. point_size[p] is delta_p.
inline double grown_corner_size(double growth, const std::vector<double>& point_size,
                                std::span<const Index> corners) {
  double smallest = point_size[corners[0]];
  for (const Index p : corners.subspan(1)) smallest = std::min(smallest, point_size[p]);
  return growth * smallest;
}

// Eq. 15: the size of a new point, min(field_size, c_i · min over the corners), with
// field_size = min(delta_bg, delta_s) (SizeField::size_at at the new point). One rule for the
// volume front, the surface front and the end game.
inline double new_point_size(double field_size, double growth,
                             const std::vector<double>& point_size,
                             std::span<const Index> corners) {
  return std::min(field_size, grown_corner_size(growth, point_size, corners));
}

// Eq. 15 over a distance (its continuous form; ours, not the paper's words): sizes that grow
// by c_i = `growth` from one element to the next, starting from delta, reach
// delta + (c_i - 1) d at distance d. The bound of a size attached at a point on the sizes around
// it: along a line (split_lines.h), over the input's edges (grade_point_sizes), inside a patch
// re-triangulated from its input (patch_from_input.h).
inline double size_grown_over(double delta, double growth, double distance) {
  return delta + (growth - 1.0) * distance;
}

}  // namespace afmesh
