// Edge flips inside the patches of a re-triangulated surface (not in the paper, whose front
// places every point where it stays; the classic clean-up after a surface front, as netgen's
// and gmsh's surface meshers do): the diagonal of two triangles of one patch is swapped where
// that raises their smaller minimum angle, the quadrilateral is convex in its mean plane,
// both new triangles stay within 30° of it and (FlipParams::keep_uncrossed) neither meets
// another triangle of the surface beyond the corners they share (exact predicates). Points
// never move, and no edge on a discrete line is flipped, so every vertex stays on the input and
// every ridge and corner stays as meshed.
#pragma once

#include <cstdint>
#include <utility>
#include <vector>

#include "absl/container/flat_hash_set.h"
#include "absl/status/statusor.h"
#include "core/common/progress.h"
#include "core/mesh/mesh.h"

namespace afmesh {

struct FlipParams {
  int max_passes = 8;           // passes over all edges (each pass flips independent edges)
  double min_gain_deg = 0.5;    // a flip must raise the smaller minimum angle by this much
  double max_normal_turn_deg = 30.0;
  // Refuse a flip whose new triangles meet another triangle beyond the corners they share (exact
  // tests through bins of the triangles' boxes, which cost about as much as the flips).
  bool keep_uncrossed = true;
};

// Flips edges of `triangles` (M×3 over `points`, oriented consistently) between triangles of the
// same `patch` (M values) that are not in `fixed` (edges as (min, max) point pairs). Returns the
// number of flips, or CANCELLED soon after progress.cancelled() turns true (`triangles` then
// hold the flips made so far: still a valid triangulation). O(passes · M log M), with bins of
// the triangles' boxes for keep_uncrossed. With `may_gain` (M flags), the first pass looks only
// at the edges of the triangles flagged, as later passes look only at those a flip changed, and
// on return the flags are those whose edges may still gain (none when the last pass flipped
// nothing, else the triangles it changed): a caller that changes some triangles between two
// calls flags them too, and the second call makes the flips of a call over all edges (but a
// flip that the first refused because it crossed a triangle that has moved since).
absl::StatusOr<std::int64_t> flip_edges(const std::vector<Point>& points,
                                        std::vector<Triangle>& triangles,
                                        const std::vector<Index>& patch,
                                        const absl::flat_hash_set<std::pair<Index, Index>>& fixed,
                                        const FlipParams& params = {},
                                        Progress& progress = no_progress(),
                                        std::vector<bool>* may_gain = nullptr);

}  // namespace afmesh
