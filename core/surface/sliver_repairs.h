// Repairs of the input's sliver triangles before its features are found (not in the paper;
// generate_surface_mesh.h, steps 1 and 2). Each keeps the surface manifold where it was, moves
// it by a measured distance the report gives, and drops the points left on no face.
#pragma once

#include <cstdint>
#include <limits>
#include <optional>
#include <span>

#include "core/mesh/mesh.h"
#include "core/sizing/size_field.h"
#include "core/surface/discrete_surface.h"

namespace afmesh {

// Each folded face of `clean` (folded_faces in features.h) whose shortest edge is under
// kFoldedSliverEdgeRatio of its longest loses that edge: the two faces on it are dropped and one
// end takes the other's place in its other faces, the end that turns none of them by 90° or
// more (neither end: the face stays, and a surface that follows it may cross itself there,
// explain_stuck then names it). Only where the two ends have no neighbour in common but the
// edge's two opposite corners, so that the surface stays manifold. The points left on no face
// are dropped. Returns how many faces lost an edge and the longest edge they lost; `clean`'s
// points and triangles (with their tags) change together.
inline constexpr double kFoldedSliverEdgeRatio = 0.1;

struct FoldedCollapses {
  std::int64_t count = 0;
  double longest_edge = 0.0;
};

// `before` (both repairs), when given and empty, takes a copy of `clean` as it was before the
// first change, and stays empty when nothing changes (the input as sent, for the distance
// reported; no copy of a large input that needs no repair).
FoldedCollapses collapse_folded_slivers(Mesh& clean, std::span<const FaceId> folded,
                                        std::optional<Mesh>* before = nullptr);

// Sliver steps. A CAD tessellation writes each face of the model on its own. Where a smooth
// surface is split into two faces (a cylinder cut by a plane), each half's rim is a polygon with
// its own points, and the writer closes the seam between the two polygons with a strip of
// slivers standing on it at right angles: a step as high as the polygons are apart, the
// difference of their chords' sagittas (gmsh_lever.stl of the corpus: a strip 0.001-0.33 high
// and 60 long on a cylinder of radius 11, at size 11.76). Both of the strip's long edges are
// ridges, so the strip became a patch of its own between two lines far closer than the gap sizes
// go (kMinGapSizes in gap_sizes.h), and its re-triangulation was all slivers (about 500 of the
// lever's 590 triangles under 30 degrees).
//
// A face is a step when
//  - it turns by more than the ridge angle against the face across its longest edge ab (the
//    same tag, the edge shared by the two only, traversed opposite ways),
//  - it is lower over ab than kStepHeightOfEdge of its length (a sliver), and
//  - the surface beyond it continues the one across ab: a face at its third corner v turns by
//    less than the ridge angle against the face across ab (a seam; the faces beside a chamfer
//    or a rib meet at a ridge instead, and those stay).
// A strip of steps (joined through their corners) goes whole when its highest step is lower
// than kStepHeightOfSize of the smallest size `sizes` asks along it, a step the elements cannot
// see (a face spanning it tilts by under 4.3 degrees), or not at all: a seam's strip is a chain of
// lunes meeting at points, and its wide lunes kept alone were patches with corners of 10 degrees
// (with a distance bound, the steps over it stay and the rest go: `max_height` below).
// Each face of a strip that goes is
//  - a cap (its shortest edge is no sliver's): (a, b, v) and (b, a, w) across ab are flipped to
//    (v, a, w) and (v, w, b), which lie in w's face's plane to within the height, when both
//    turn by less than the ridge angle against it (no fold, no new ridge) and vw is no edge yet
//    (manifold). No point moves;
//  - a needle (its shortest edge under kStepHeightOfEdge of ab too: where the two polygons have
//    points at nearly the same place, the cap's flip would make a needle again): the shortest
//    edge is collapsed, as a folded sliver's (the link condition kept, no face turned over).
// Each face a repair changed is looked at again, and the strips are found again while that
// repairs any; the points left on no face are dropped. Returns how many faces were repaired
// and the highest step (cap height or needle edge): the farthest the surface moved. O(M) per
// round for M faces; the rounds end when one repairs nothing.
// `sizes` is the size asked (the user's field): the sizes attached to the geometry are found
// on the repaired surface. The lever's strip is 0.0503 of its longest edge high at its widest
// face: at 0.05 that face stayed alone, a patch with a triangle of 2.9 degrees; with no edge
// bound the graded noisy sphere's noise (triangles of 8 degrees, ridge angle 60) made steps, and
// at 0.1 a step of cgal_triceratops moved where its front stops. Of the size: at 0.05 the
// lever's strip (0.33 high) went at its mean edge (11.76) but stayed at 5.44 (diag / 40: 97.96%
// of its triangles at 30 degrees and more); at 0.075 it goes at both (99.54% at 5.44), and with
// it the tongue of the lever's side face beside it (0.62 high; no triangle under 15 degrees at
// its mean edge, where 5 were).
inline constexpr double kStepHeightOfEdge = 0.075;
inline constexpr double kStepHeightOfSize = 0.075;

struct StepRepairs {
  std::int64_t count = 0;
  double highest = 0.0;
};

// `max_height`: no step higher than this goes (the user's bound on the distance from the input,
// SurfaceParams::curvature_deviation; a step removed moves the surface by its height). A strip
// that the size alone would remove but that has steps over the bound loses the others, and keeps
// the parts of its lunes that are higher, each a patch with sharp corners at its ends (the
// thinnest output triangles there are then at those corners, as thin as the input's). Whole or
// nothing, the lever at diag / 40 and 0.001 of its diagonal kept its seam strip (0.33 high at
// its widest, 0.002 to 0.02 along most of it) whole, and the strip's triangles, spanning it from
// ridge to ridge at the gap floor, were thinner than its input faces (96 under 15 degrees that
// are not at thinner input; 212 under 15 in all, 81,580 triangles). Step by step: 15 under 15
// degrees, all at thinner input, 94,560 triangles (the plane beside the strip finer where the
// kept lunes' short lines end), the distance to the input unchanged (0.0668% of the diagonal).
// Without a bound, whole or nothing stays the rule (see the strips above).
StepRepairs repair_sliver_steps(Mesh& clean, const SizeField& sizes, double ridge_angle_deg,
                                double max_height = std::numeric_limits<double>::infinity(),
                                std::optional<Mesh>* before = nullptr);

}  // namespace afmesh
