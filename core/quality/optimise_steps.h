// The local steps of the tet optimiser (optimise.h). Each topological step proposes a change
// around one tet without making it; the driver makes the best proposal through
// TetComplex::replace. Smoothing moves one point.
//
// Quality is tet_min_sine (optimise.h) throughout: larger is better, <= 0 for a flat or inverted
// tet. Every proposed tet is positive by exact orient3d.
#pragma once

#include <limits>
#include <vector>

#include "absl/functional/function_ref.h"
#include "core/mesh/mesh.h"
#include "core/quality/optimise.h"
#include "core/quality/tet_complex.h"

namespace afmesh {

inline double tet_min_sine(const std::vector<Point>& points, const Tet& k) {
  return tet_min_sine(points[k[0]], points[k[1]], points[k[2]], points[k[3]]);
}

// Tets `old` to be replaced by `fresh`; quality is the smallest quality among `fresh`.
struct TopologyChange {
  std::vector<Index> old;
  std::vector<Tet> fresh;
  double quality = -std::numeric_limits<double>::infinity();
};

// A criterion for the tets a topological step makes, larger is better, called on positive tets
// only (the steps check positivity by exact orient3d themselves). The optimiser's is tet_min_sine;
// the recovery of prescribed triangles (recover_faces.h) has its own.
using TetCriterion = absl::FunctionRef<double(const Tet&)>;

// Edge removal (Shewchuk 2002, §2): the n tets of `ring` (TetComplex::edge_ring, an interior
// edge, n <= kMaxRingSize) become the 2(n - 2) tets over the triangulation of the ring polygon
// (ring_triangulation.h) whose worst tet by `criterion` is best, among those whose every tet is
// positive and scores above `floor`. False when no such triangulation exists. out.quality is the
// worst new tet's score. (Given a boundary edge's fan, TetComplex::edge_fan, its polygon is
// closed by the side from its last corner to its first: propose_boundary_edge_removal.)
bool propose_edge_removal(const TetComplex& c, const EdgeRing& ring, TetCriterion criterion,
                          double floor, TopologyChange& out);

// Edge removal on the boundary: the n >= 2 tets of `fan` (TetComplex::edge_fan) around the
// boundary edge (a, b), whose boundary faces (a, b, r_0) and (a, b, r_n) are coplanar with r_0
// and r_n on either side of the line ab, become the 2(n - 1) tets over the triangulation of the
// polygon r_0 .. r_n whose worst tet by `criterion` is best: the boundary's quadrilateral
// (a, r_0, b, r_n) turns its diagonal to (r_0, r_n), the region stays the same. For n = 2 the
// 2-2 flip of two tets on a convex hull. Not an optimiser step (the optimiser keeps the boundary);
// the recovery of prescribed triangles (recover_faces.h) uses it, with
// TetComplex::replace(..., boundary_may_change = true). False when n + 1 > kMaxRingSize or no
// triangulation gives positive tets.
bool propose_boundary_edge_removal(const TetComplex& c, const EdgeRing& fan,
                                   TetCriterion criterion, TopologyChange& out);

// 2-3 flip: the face of tet t opposite corner `corner` and the tet beyond it become three tets
// around the edge joining the two apexes. False on a boundary face, when a new tet is not
// positive, or when a new tet does not score above `floor` by `criterion`.
bool propose_face_removal(const TetComplex& c, Index t, int corner, TetCriterion criterion,
                          double floor, TopologyChange& out);

// The optimiser's steps: by tet_min_sine, each only when its new worst beats the old worst. For
// edge removal, `ring` is scratch; false when the edge (a, b) of tet t is on the boundary or has
// more than max_ring tets around it.
bool propose_edge_removal(const TetComplex& c, Index t, Index a, Index b, int max_ring,
                          EdgeRing& ring, TopologyChange& out);
bool propose_face_removal(const TetComplex& c, Index t, int corner, TopologyChange& out);

// Edge contraction (Klingner and Shewchuk, "Aggressive tetrahedral mesh improvement", 2007,
// §3): the movable point b (b >= fixed_points, so never a point of the boundary) of tet t is
// merged into its neighbour a, which stays where it is: the tets around the edge (a, b) vanish
// and b's other tets take a in its place. out.old is the ball of b, out.fresh its tets without a
// with b replaced by a; out.quality their worst. False when b is fixed or not a corner of t, when
// a new tet is not positive by exact orient3d, or when the new worst does not beat the ball's
// worst (tet_min_sine). `ball` is scratch. Made by TetComplex::replace(..., dropped = b).
bool propose_edge_contraction(const TetComplex& c, Index t, Index a, Index b, Index fixed_points,
                              std::vector<Index>& ball, TopologyChange& out);

// Scratch for smooth_point.
struct SmoothingScratch {
  std::vector<Index> ball;           // the tets around the point
  std::vector<double> quality;       // their qualities
  std::vector<double> trial;         // their qualities at a trial position
  std::vector<std::size_t> order;    // positions in `ball`, worst quality first
  std::vector<Point> gradients;      // of the nearly-worst tets' qualities
};

// Moves point v (not fixed: v >= fixed_points) to raise the smallest quality of the tets around
// it: hill climbing along the gradient of the worst tets' quality with a backtracking line
// search (Freitag and Ollivier-Gooch, "Tetrahedral mesh improvement using swapping and
// smoothing", 1997), after trying the centroid of its neighbours. A move is kept only when all
// tets stay positive (exact orient3d) and the smallest quality strictly rises. Returns true when
// the point moved.
// With climb_too false only the centroid is tried (Laplacian smoothing, kept only if better).
bool smooth_point(TetComplex& c, Index v, Index fixed_points, bool climb_too,
                  SmoothingScratch& scratch);

// Edge split by insertion (Klingner and Shewchuk, "Aggressive tetrahedral mesh improvement",
// 2007, §3): a new point z inside the ring of the interior edge (a, b) of tet t replaces the
// n <= max_ring tets around the edge by the 2n tets (z, b, r_i, r_{i+1}) and (a, z, r_i, r_{i+1}),
// so every face on the ring's outside, boundary faces included, stays. z is the best of a few
// points between the edge's midpoint and the ring's centroid.
struct EdgeSplit {
  EdgeRing ring;
  Point z{};
  double quality = -std::numeric_limits<double>::infinity();  // worst of the 2n new tets
};

// Proposes the split of edge (a, b) of tet t; false when the edge is on the boundary, has more
// than max_ring tets around it, or no placement beats the ring's worst tet. Leaves the complex
// as it was.
bool propose_edge_split(TetComplex& c, Index t, Index a, Index b, int max_ring, EdgeSplit& out);

// Makes a proposed split: adds point z, replaces the ring, then smooths z (smooth_point). The
// new tets are appended to `created`. False (nothing changed) if the ring changed meanwhile.
bool make_edge_split(TetComplex& c, const EdgeSplit& split, Index fixed_points,
                     SmoothingScratch& scratch, std::vector<Index>& created);

}  // namespace afmesh
