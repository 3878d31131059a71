// Grading a triangulated surface to a size field (paper §4: the volume front takes its boundary
// as given, so a graded volume mesh needs a graded boundary; this makes one from any SizeField).
//
// Longest-edge bisection (Rivara's LEPP refinement): while some edge is longer than
// max_ratio × the size at its midpoint (GradedSurfaceParams), the longest such edge is taken;
// following its longest-edge propagation path (the longest edge of an adjacent triangle, if longer,
// and so on) a terminal edge is reached, which is the longest edge of both its triangles, and it is
// split at its midpoint together with both triangles. Splitting only longest edges keeps the
// triangles' shapes (right isosceles triangles stay right isosceles), and splitting an edge in both
// of its triangles keeps the surface conforming, closed and oriented. New points lie on the input's
// flat triangles (no projection onto a curved surface); ridges and corners are kept.
//
// Deterministic: edges are taken by decreasing length, ties by their point indices.
#pragma once

#include <cstddef>
#include <numbers>

#include "absl/status/statusor.h"
#include "core/mesh/mesh.h"
#include "core/sizing/size_field.h"

namespace afmesh {

struct GradedSurfaceParams {
  // An edge is split while its length exceeds max_ratio × the size at its midpoint (> 0).
  // Bisection halves edges, so they end between about max_ratio / 2 and max_ratio times the
  // size. The default √2 centres that range on the size (in log scale): on the graded cube of
  // tests/volume/graded_cube_test.cc the mean edge over the size, per 0.1-wide bin of distance
  // to the source, is 0.83 to 1.07; max_ratio = 1 gives 0.60 to 0.85 (no edge over the size).
  double max_ratio = std::numbers::sqrt2;
  // Refinement stops with RESOURCE_EXHAUSTED rather than produce more triangles than this.
  std::size_t max_triangles = 10'000'000;
};

// `surface` (points N×3, triangles M×3 with tags; each edge in at most two triangles) refined to
// `size`: the input points first, in order, then the new midpoints; every triangle keeps the tag
// and orientation of the input triangle it lies in. Tets of `surface` are not kept.
// INVALID_ARGUMENT for an index out of range, a non-finite coordinate or an edge in more than two
// triangles; RESOURCE_EXHAUSTED past params.max_triangles.
absl::StatusOr<Mesh> grade_surface(const Mesh& surface, const SizeField& size,
                                   const GradedSurfaceParams& params = {});

}  // namespace afmesh
