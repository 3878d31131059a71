// Tetrahedral mesh optimisation: local topological changes, point smoothing and, as a last
// resort, edge splits that raise the worst element quality without touching the boundary.
//
// The advancing front leaves a small share of slivers where fronts meet and flat tets across
// boundary quads. This pass works only on the tets whose quality is under the target, worst
// first, and for each tries in turn
//   1. edge removal (Shewchuk, "Two discrete optimization algorithms for the topological
//      improvement of tetrahedral meshes", 2002): an interior edge of the tet with n <= 7 tets
//      around it is removed, its ring re-triangulated by the triangulation that maximises the
//      smallest quality (a 3-2 flip when n = 3); optionally 2-3 flips of its interior faces;
//      the change whose worst new tet is best is made when it beats the worst tet it replaces;
//   2. smoothing: each movable corner of the tet is moved by hill climbing on the smallest quality
//      around it (Freitag and Ollivier-Gooch 1997);
//   3. when the tet is still under the target, the better (by its new worst tet) of
//      - edge contraction (Klingner and Shewchuk, "Aggressive tetrahedral mesh improvement",
//        2007): one of its interior points merged into a neighbour across one of its edges, the
//        tets around that edge vanishing, when that raises the worst tet around the point
//        removed; the point kept is then smoothed. This removes the wedges on a short edge
//        between two points placed too close (by the front, or by earlier splits) that no flip
//        or move mends;
//      - edge split (Klingner and Shewchuk 2007; in the first split_passes rounds only): a new
//        interior point splits the interior edge whose split gives the best worst tet. This is
//        what removes a flat tet across a boundary quad when no triangulation of the ring of the
//        quad's interior diagonal has only positive tets.
// Tets made or changed that are still under the target are worked on in the next round; a tet
// on which every step failed is tried again only after a change at one of its points.
// Quality is the minimum over the six dihedral angles of their sine (0 for a flat tet, negative
// for an inverted one), so small and near-180° angles are both improved. Every new tet is
// positive by exact orient3d, and every change raises the smallest quality among the tets it
// touches, so the mesh's worst tet never gets worse.
//
// The boundary is left exactly as it is: points with index < fixed_points never move, and
// changes replace only faces and edges that are interior (a face with a tet on both sides, an
// edge whose ring of tets is closed). An edge between two boundary points can be interior: the
// diagonal of a flat boundary quad is removed this way, its two boundary triangles staying faces.
// Face adjacency is built once (tet_complex.h) and updated locally by each change.
// Deterministic: the result depends only on the input arrays and params.
#pragma once

#include <cstdint>

#include "absl/status/statusor.h"
#include "core/common/progress.h"
#include "core/mesh/mesh.h"

namespace afmesh {

struct OptimiseParams {
  // Tets with quality under sin(target_min_dihedral_deg) are worked on (degrees). 20 ends with
  // no tet under 20° on the benchmark solids at 60% of the cost of 25 (sphere, 514k tets:
  // 0.42 s against 0.70 s; min 20.0° against 23.8°, mean radius ratio 0.8161 against 0.8165).
  double target_min_dihedral_deg = 20.0;
  // Rounds over the bad tets: round 0 takes every tet under the target, each later round the
  // tets that changes made and that are still under it, and those that could not be improved.
  // A round costs in proportion to the tets it takes, so the later rounds are cheap: 8 rounds
  // where 4 left a few tets under the target at 2M tets (sphere h 0.02661: one at 19.69°; torus
  // h 0.02221: six, down to 17.90°) leave none, in the same time, and change nothing where 4
  // rounds already left none.
  int passes = 8;
  // Rounds after those, while at most more_passes_max_tets tets are left to work on. A tet that
  // every step failed on is tried again only after a change at one of its points, so the last
  // few under the target on a solid may need many rounds (the sweep's solids in runs under 18°
  // away from their input's slivers, 164 runs: 38 after 8 rounds, 30 after 16, 28 after 32, the
  // tet count unchanged); a filled sliver front keeps thousands that no round mends, and every
  // round costs as much as the last (inv_5ch at diag/25: optimiser 18 s with 8 rounds, over
  // 100 s with 32).
  int more_passes = 24;
  std::int64_t more_passes_max_tets = 1000;
  // Edge splits (edge_split) are tried in the first split_passes rounds only: on fronts of
  // slivers the boundary forces tets no step can mend, and each round split their edges again
  // (a cube with split edges, Regression.Issue10CubeWithSliversAlongItsEdgesMeshes: 7,474 tets
  // after 8 rounds with splits in all of them, under 2,000 with splits in the first 4).
  int split_passes = 4;
  // Sweeps of Laplacian smoothing (kept only where better) over every movable point before the
  // rounds (0 = none). One sweep raises the mean radius ratio by about 0.05 and halves the tets
  // under the target, for about 4 µs per movable point. Not in the paper: it is on by default
  // because the front alone leaves too many interior edges off the size (issue 10 part 5 asks
  // 90% of them within [0.7 h, 1.4 h]): on the bench solids at about 50k and 350k tets one sweep
  // takes that share from 88.6-89.8% to 93.6-95.5% and the mean edge from 1.045-1.050 h to
  // 1.027-1.034 h, for 5-9% more time in the whole job (sphere h = 0.05: 2.15 s -> 2.30 s).
  int smoothing_sweeps = 1;
  // The steps tried on a bad tet; edge removal considers rings of up to max_edge_ring tets.
  bool edge_removal = true;
  int max_edge_ring = 7;
  bool face_removal = false;
  bool smoothing = true;
  // For a tet still under the target: merge one of its movable points into a neighbour across
  // an edge (edge contraction), removing a point.
  bool edge_contraction = true;
  // For a tet still under the target: split one of its interior edges by a new interior point
  // (the better of this and the contraction is made).
  bool edge_split = true;
};

struct OptimiseStats {
  std::int64_t bad_tets = 0;       // under the target before optimising
  std::int64_t edge_removals = 0;  // every ring size
  std::int64_t flips_32 = 0;       // edge removals with a ring of 3 (included above)
  std::int64_t flips_23 = 0;
  std::int64_t points_moved = 0;
  std::int64_t edge_splits = 0;    // each adds one point
  std::int64_t edge_contractions = 0;  // each removes one point
};

// Improves `mesh.tets` (K×4, positive, conforming: every face in one or two tets) over
// `mesh.points` (N×3) in place. Points with index >= fixed_points may move, new points may be
// appended (edge splits) and points removed (edge contractions; the others keep their order, so
// the first fixed_points are unchanged); tets are replaced, added and removed (new tets get tag
// 0; the others keep their order). Returns CANCELLED when progress.cancelled() turns true (the
// mesh is then still valid, only less optimised) and INVALID_ARGUMENT, naming it, for a tet with
// an index out of range or repeated, or a face in more than two tets.
absl::StatusOr<OptimiseStats> optimise_tets(Mesh& mesh, Index fixed_points,
                                            const OptimiseParams& params, Progress& progress);

// Min over the six dihedral angles of tet (a, b, c, d) of their sine, signed by the volume:
// sqrt(8/9)·... = sin(acos(1/3)) ≈ 0.9428 for the regular tet, 0 when flat, < 0 when inverted.
double tet_min_sine(const Point& a, const Point& b, const Point& c, const Point& d);

}  // namespace afmesh
