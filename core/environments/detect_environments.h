// Crossing environments found automatically (`--envs auto`): paper §2, "This crossing
// environment variable can either be obtained by checking the initial front for crossing
// faces, or by marking the different surface patches ...". This is the first way.
//
// The rule, in five steps (each a function in detect_environments.cc):
//
//  1. Thin pairs (find_thin_pairs). Two front faces f, g form a thin pair when
//       (a) they cross: they intersect in more than their shared vertices imply (exact,
//           triangles_intersect_improperly, core/geometry/intersect.h) -- crossing faces of
//           the two sides, or coplanar overlaps such as the two cuts of a shell on a symmetry
//           plane; or
//       (b) they nearly touch from the two sides of a thin solid: they share no vertex, their
//           distance d (closest points, core/geometry/closest_points.h) is below
//           `closeness` × min(h_f, h_g), with h the face's mean edge length (the local size of
//           the front), their normals fold against each other (the angle between them exceeds
//           `fold_angle_deg`, as where a thin sheet's two sides meet, step 2; a side and the
//           narrow strip closing its rim at 90° are a corner, not thin), and the solid lies
//           between them: with v the vector from f's closest point to g's, n_f · v > 0 and
//           n_g · v < 0 (front normals point out of the domain, i.e. into the solid). Two faces
//           facing each other across a narrow gap of the domain (n_f · v < 0) are not thin:
//           that gap must be filled with tets joining both, so it gets no environment. Last,
//           the two faces lie over each other: projected along the coordinate axis nearest
//           n_f − n_g, they overlap in more than a line or a point (exact, orient2d_projected;
//           not in the paper). Faces of a step, near and facing each other but side by side,
//           have no thin region between them.
//     Candidate pairs come from an AABB tree (core/spatial) over the faces' boxes, each
//     enlarged by closeness × h; no all-pairs scan.
//  2. Sides (group_sides). The faces of thin pairs are grouped: two such faces at a common point
//     belong to the same side when the fan of faces around that point leads from one to the
//     other across edges that do not fold, i.e. where the angle between the normals of the two
//     faces on the edge is at most `fold_angle_deg`. The ridge where the two sides of a thin
//     sheet meet folds (their normals are nearly opposite there), so grouping stops at it, and
//     sheets that touch only in a point (the apex where the rims of a crossing X cross) stay
//     apart; across smooth edges and ordinary corners (a shell meeting a symmetry plane at 90°,
//     the fold of a quadrant's sheet at the crossing of an X) a side continues. This is the
//     paper's "all the surfaces lying on one side of a potentially troublesome region have been
//     given the same environment variable" (Figure 4).
//  3. Growth (grow_sides). Faces next to a side join it, ring by ring (`grow_rings` rings of
//     faces sharing an edge without a fold), unless they touch two sides (by an edge, or by a point
//     on a face of another side: a narrow strip closing a plate's rim between its sides). This
//     marks the faces at the rim of a thin region, whose only close faces on the other side share
//     their rim vertices (and so are not thin pairs by (b)), and which the front would otherwise
//     build on without filtering, a few tenths of a millimetre from the other side.
//  4. Numbering (number_sides). Each side is one environment, numbered 1, 2, ... in the order
//     of its smallest face index (deterministic). All other faces get 0.
//  5. Separation (check_sides_separated). The two faces of every thin pair must end up in
//     different environments; otherwise the sides could not be told apart automatically and
//     INVALID_ARGUMENT names the pair (mark the environments by tags instead) -- or, when faces
//     cross at a steep angle (normals more than 30° from parallel), names them: surfaces that
//     pass through each other, like two solids given overlapping, are no thin region, and no
//     environments can mesh them (give the boundary of their union).
// LPOCR then follows from LFACR (point_environments, environments.h): ridge points of two
// environments get -1.
#pragma once

#include <cstdint>

#include "absl/status/statusor.h"
#include "core/common/progress.h"
#include "core/environments/environments.h"
#include "core/mesh/mesh.h"

namespace afmesh {

struct AutoEnvironmentParams {
  // Faces nearly touch when their distance is below closeness × the smaller of their mean edge
  // lengths. 0.25: the other side is then far closer than the element the front would build on
  // the face (about one edge length high), while faces of one smooth surface, one ring or more
  // apart, are never that close. Must be finite and >= 0 (0: crossing faces only).
  double closeness = 0.25;
  // Two faces of thin pairs sharing a vertex are on the same side unless the angle between
  // their normals exceeds this (degrees, in (0, 180)). 135° stops at the fold of a thin sheet
  // (~180°) and passes a 90° corner.
  double fold_angle_deg = 135.0;
  // Rings of faces by which each side grows (step 3), >= 0.
  int grow_rings = 2;
};

// What the detection found, for reports and tests.
struct AutoEnvironmentStats {
  std::int64_t crossing_pairs = 0;  // thin pairs of kind (a)
  std::int64_t close_pairs = 0;     // thin pairs of kind (b)
  std::int64_t marked_faces = 0;    // faces in some environment (thin pairs and growth)
  int environment_count = 0;
};

struct DetectedEnvironments {
  FrontEnvironments environments;
  AutoEnvironmentStats stats;
};

// The crossing environments of `front` (N points, M triangles, outward normals) by the rule
// above. A front with no thin pair gets all zeros (environment_count 0).
// Errors: INVALID_ARGUMENT when an index is out of range, a coordinate is not finite, a
// triangle is degenerate (repeated or collinear points: it has no normal), the parameters are
// out of range, or the sides of a thin region cannot be separated (step 4); CANCELLED when
// progress.cancelled().
absl::StatusOr<DetectedEnvironments> detect_environments(const Mesh& front,
                                                         const AutoEnvironmentParams& params,
                                                         Progress& progress);

}  // namespace afmesh
