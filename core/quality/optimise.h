// Tetrahedral mesh optimisation: local flips and vertex smoothing that raise the worst element
// quality without touching the boundary.
//
// The advancing front leaves a small share of slivers where fronts meet. This pass works on the
// tets whose smallest dihedral angle is under `OptimiseParams::target_min_dihedral_deg`, worst
// first, and tries in turn
//   - 3-2 flips: an interior edge with exactly three tets around it is removed (three tets become
//     two sharing the triangle of the ring);
//   - 2-3 flips: an interior face is removed (two tets become three around the segment joining
//     their apexes);
//   - smoothing: a movable point moves toward the centroid of its neighbours;
// and keeps an operation only when every new tet is positive (exact orient3d) and the smallest
// quality among the tets it touches strictly increases. Quality here is the minimum over the six
// dihedral angles of their sine (0 for a flat tet, negative for an inverted one), so small and
// near-180° angles are both improved.
//
// The boundary is left exactly as it is: points with index < fixed_points never move, and flips
// only replace faces and edges that are interior (shared by two tets / surrounded by tets).
// Deterministic: tets are visited in order of (quality, index).
#pragma once

#include <cstdint>

#include "absl/status/statusor.h"
#include "core/common/progress.h"
#include "core/mesh/mesh.h"

namespace afmesh {

struct OptimiseParams {
  // Tets whose min dihedral angle is below this (degrees) are worked on.
  double target_min_dihedral_deg = 30.0;
  // Passes over the bad tets; each pass re-collects them.
  int passes = 4;
  // Sweeps of smoothing over every movable point before the passes (0 = none).
  int smoothing_sweeps = 1;
};

struct OptimiseStats {
  std::int64_t flips_32 = 0;
  std::int64_t flips_23 = 0;
  std::int64_t points_moved = 0;
};

// Improves `mesh.tets` (K×4, positive) over `mesh.points` in place. Points with index
// >= fixed_points may move; tets are replaced, added and removed by flips (their tags are reset
// to 0 for new tets). Returns CANCELLED when progress.cancelled() turns true (the mesh is then
// still valid, only less optimised).
absl::StatusOr<OptimiseStats> optimise_tets(Mesh& mesh, Index fixed_points,
                                            const OptimiseParams& params, Progress& progress);

// Min over the six dihedral angles of tet (a, b, c, d) of their sine, signed by the volume:
// sqrt(8/9)·... = sin(acos(1/3)) ≈ 0.9428 for the regular tet, 0 when flat, < 0 when inverted.
double tet_min_sine(const Point& a, const Point& b, const Point& c, const Point& d);

}  // namespace afmesh
