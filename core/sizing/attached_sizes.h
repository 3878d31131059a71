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

// eq. 15: min(field_size, growth · min(size_a, size_b, size_c)), with field_size =
// min(delta_bg, delta_s) (SizeField::size_at at the new point) and growth = c_i.
inline double new_point_size(double field_size, double growth, double size_a, double size_b,
                             double size_c) {
  return std::min(field_size, growth * std::min({size_a, size_b, size_c}));
}

}  // namespace afmesh
