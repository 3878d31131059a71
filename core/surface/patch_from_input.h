// A patch re-triangulated from its own input triangles, for a patch whose surface front stopped
// (not in the paper, whose front closes every patch; CGAL's isotropic_remeshing and MMG start from
// the input's triangles in the same way). Where a crease runs through a patch on no line (a ridge
// that ends inside it, cgal_hand's fingers) the front, whose crossing test (S6) works in the plane
// of a side, can fail to close the patch however it backs off. The input's own triangles cover the
// patch exactly, so:
//
//  1. insert_line_points: the points of the patch's lines (the sides its neighbours share) are
//     inserted into the input edges they lie on, each splitting the triangles of that edge;
//  2. remove_input_line_vertices: the input's vertices on the lines between them are removed,
//     each hole triangulated for the largest smallest angle with no triangle turned by more than
//     kMaxNormalTurnDeg (kMaxLineVertexTurnDeg for those that cannot be so), so that the patch
//     meets its neighbours on exactly their points;
//  3. split_long_edges: edges off the lines longer than kSplitOver times the size wanted at their
//     middle (eq. 15 over the distance from their ends) are split there, longest relative to the
//     size first, the new point on the patch (S8): a triangle split inside one input face stays
//     in it. After each pass of splits the edges are flipped for larger angles (flip_edges);
//  4. collapse_short_edges: where the input is finer than the size, edges off the lines shorter
//     than kCollapseUnder times it lose a point of the patch (an edge collapse that keeps the
//     surface a manifold, turns no triangle by more than kMaxNormalTurnDeg and makes no edge
//     longer than kSplitOver times the size), then flips again.
//
// The flips, collapses and smoothing that follow every patch then shape the triangles (run more
// than once when a patch was made so). Every point stays on the input: the input's vertices,
// the lines' points, the splits' middles moved onto the patch.
#pragma once

#include <cstdint>
#include <vector>

#include "absl/status/status.h"
#include "core/common/progress.h"
#include "core/surface/features.h"
#include "core/surface/surface_front.h"

namespace afmesh {

// Appends to `s` the triangles of `patch` built as above from its input faces, conforming to its
// initial `sides` (those of mesh_patch; empty for a patch without lines), with at most
// `max_triangles` triangles in the end and kSplitPeakOverResult (patch_from_input.cc) times that
// while its long edges are split (a patch with more input triangles is refused before any work: a
// bound on the work and memory, as the front's). FAILED_PRECONDITION when a step
// cannot be done without folding a triangle or when the result is not a closed cover of the
// patch (check_patch_closed), naming where; `s` is then as before the call. CANCELLED once
// progress is. O(T log T) for the T triangles made.
absl::Status patch_from_input(SurfaceMeshState& s, PatchId patch, const std::vector<Side>& sides,
                              std::int64_t max_triangles, Progress& progress = no_progress());

}  // namespace afmesh
