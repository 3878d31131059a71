// Edge collapses inside the patches of a re-triangulated surface (not in the paper, whose front
// places every point where it stays; the collapse of short edges is the third clean-up of CGAL's
// isotropic_remeshing and of gmsh's surface optimisation, beside flips and smoothing). Where the
// front had to close between points much nearer than the size (a crease no line follows, the
// eyes and claws of a scanned figure), it leaves needles and caps that neither a flip nor a
// move of a point can mend: a flip needs a convex quadrilateral, a move needs room. A triangle
// whose smallest angle is under bad_angle_deg has its edges tried, shortest first: a patch
// point (not a corner nor a line point) at one end is merged into the point at the other, when
//   - the two points share exactly the two triangles of the edge and no other neighbour (the
//     link condition: the surface stays a manifold with no repeated edge),
//   - every triangle of the moved point's fan stays within max_normal_turn_deg of its old
//     normal and keeps a positive area (nothing folds over),
//   - and the smallest angle of the fan rises.
// Line points and corners never move and no line side is removed, so every vertex stays on the
// input and every ridge and corner stays as meshed.
#pragma once

#include <cstdint>

#include "absl/status/statusor.h"
#include "core/common/progress.h"
#include "core/surface/surface_front.h"

namespace afmesh {

struct CollapseParams {
  double bad_angle_deg = 15.0;        // triangles under this smallest angle are worked on
  int max_passes = 4;                 // passes over the bad triangles
  double max_normal_turn_deg = 30.0;  // no triangle of the fan turns by more
};

// Collapses edges of s.triangles as above, removing the merged points (s.points and every array
// parallel to it are renumbered by SurfaceMeshState::compact_patch). Returns the number of
// collapses, or CANCELLED soon after progress.cancelled() turns true (the surface then holds the
// collapses made so far, each of which kept it valid). O(passes · M) with M triangles.
absl::StatusOr<std::int64_t> collapse_edges(SurfaceMeshState& s, const CollapseParams& params = {},
                                            Progress& progress = no_progress());

}  // namespace afmesh
