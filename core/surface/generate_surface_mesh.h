// MeshSurface: re-triangulates a surface given only as triangles (paper §3, steps S1–S11, with
// the discrete lines and patches of its end and the sizes of §4).
//
// Steps:
//  1. Input as it comes (clean_surface_input): duplicate and zero-area triangles and unused
//     points are dropped, closed components are oriented consistently and outward; each change
//     is counted in the report. Sliver steps a CAD writer closes a seam with
//     (repair_sliver_steps in sliver_repairs.h) are flipped and collapsed away.
//  2. The discrete surface (discrete_surface.h): host faces, normals, projection (S2, S3, S8).
//     Sliver faces folded back over all three neighbours (folded_faces in features.h) lose their
//     shortest edge first, and the surface is built again (counted in the report).
//  3. Features (features.h): ridges, boundary, non-manifold and tag edges as discrete lines,
//     corners, patches; the size bounded by the input's curvature (curvature_sizes.h, eq. 20–22).
//  4. Sides along every line (split_lines.h, F3), shared by the patches on both sides.
//  5. Each patch meshed in turn from its sides by the surface front, S1–S11.
//  6. The result assembled (corners and line points shared) and checked.
//  7. Edge flips inside the patches (flip_edges.h), then the points inside them smoothed on the
//     input and the line points slid along their lines (smooth_points.h): neither is in the
//     paper, both keep every point on the input and every line as meshed.
//  8. Its distance to the input measured (two-sided Hausdorff, sampled at vertices, edge
//     midpoints and centroids).
#pragma once

#include <cstdint>
#include <functional>
#include <limits>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "absl/status/status.h"
#include "absl/status/statusor.h"
#include "core/common/progress.h"
#include "core/common/stage_timing.h"
#include "core/mesh/mesh.h"
#include "core/sizing/size_spec.h"
#include "core/surface/discrete_surface.h"

namespace afmesh {

struct SurfaceParams {
  // Target edge length h of the uniform size field (> 0, in the units of the points).
  double size = 0.0;
  // Growth factor c_i of eq. 15 (>= 1) for the sizes attached to the lines' corners and to
  // new points.
  double growth = 1.0;
  // The full size specification (sources, background grid; paper §4). When set, its max_size
  // and growth replace `size` and `growth`.
  std::optional<SizeSpec> spec;
  // Adjacent input faces whose normals differ by more than this make a ridge (degrees, (0, 180)).
  double ridge_angle_deg = 30.0;
  // A discrete line turning by more than this at a vertex is split there (degrees, (0, 180]).
  double corner_angle_deg = 60.0;
  // Elements turn by at most this angle where the input is curved (paper §4.4, eq. 20–22;
  // degrees in (0, 180), or 0: no curvature bound): the size is reduced where the input curves
  // faster, so that small holes and fillets are not meshed over. 30° gives about 12 elements
  // round a circle.
  double curvature_angle_deg = 30.0;
  // The largest distance of the output from the input where it curves, as a fraction of the
  // model size (the input's bounding-box diagonal; in [0, 1), or 0: no such bound). Not in the
  // paper, whose §4.4 leaves "other measures of surface accuracy" open (curvature_sizes.h):
  // where the input curves with radius r (eq. 20) an element is at most sqrt(8 r epsilon) long
  // (the chord whose midpoint lies epsilon from its arc), and across a crease where two faces
  // turn by alpha, 2 epsilon / sin(alpha / 2) (the kink bound), epsilon being the deviation over
  // kDeviationMargin (2.25, for triangles longer and wider than one chord). The angle alone lets
  // an element of length l lie 0.067 l from the input at 30°, 0.17% of the model size at
  // l = diag / 40. With 0.001 every corpus surface that closes at its mean edge (22 of 30, and
  // the open of_wigley) lies 0.036–0.102% of its diagonal from the input (cgal_homer 2% over
  // the deviation asked), with 1 (the bunny, where the 30° bound is finer) to 90 times the
  // triangles of the angle bound alone (gmsh_surface1, 80 coarse facets: 84 → 7,782), and the
  // bench's CAD parts at diag / 40 and bunny at diag / 60 within 0.060–0.077%. It is off by
  // default: the triangles it costs on coarse CAD tessellations (every facet crease is a
  // kink) are the user's choice, and with it the front stops on some inputs it closes without
  // it (cgal_dino at 0.001 and its mean edge), by margins that move with any change of the
  // sizes.
  double curvature_deviation = 0.0;
  // Elements no longer than this many times the thickness of the solid the surface bounds, the
  // distance across to its opposite wall (wall_sizes.h; not in the paper), down to 0.15 of the
  // size; 0: no such bound (the default here). A surface that is to be a volume mesher's front
  // needs it where its walls are thinner than the size: the volume job that re-triangulates its
  // front first asks kVolumeFrontWallSizes unless told otherwise. A surface asked for itself
  // keeps the size asked on its thin walls (a sheet 1 thick at a size of 10 would otherwise
  // take 40 times the triangles).
  double wall_sizes = 0.0;
  // Stop with RESOURCE_EXHAUSTED past this many output triangles (the server's --max-elements).
  std::int64_t max_triangles = std::numeric_limits<std::int64_t>::max();
  // When set, called once before the front runs with the number of triangles that the size
  // field and the sizes attached to the surface (its curvature and the gaps between its lines)
  // ask for; a status other than OK ends the job with it. The server re-admits the job by this
  // count against its memory budget, since its own estimate sees the size field only (of_bullet:
  // 40k estimated, 148k made). Not in the paper.
  std::function<absl::Status(double expected_triangles)> admit_expected;
  // Every patch re-triangulated from its own input triangles (patch_from_input.h), as a patch
  // whose front stopped is, without trying the front: the fallback alone, to test and compare
  // it. Not in the paper; off by default (the front's triangles are better).
  bool every_patch_from_input = false;
};

// What was done to the input before meshing, and what came out (every count is exact).
struct SurfaceReport {
  std::int64_t input_points = 0;
  std::int64_t input_triangles = 0;
  std::int64_t duplicate_triangles_dropped = 0;  // same three points as an earlier triangle
  std::int64_t degenerate_triangles_dropped = 0;  // a repeated point or zero area
  std::int64_t unused_points_dropped = 0;          // on no triangle
  std::int64_t triangles_reoriented = 0;           // turned to agree with their component
  // Folded slivers (folded_faces in features.h) that lost their shortest edge, its two ends
  // merged, and the longest edge so lost (the farthest a point of the input moved).
  std::int64_t folded_slivers_collapsed = 0;
  double longest_folded_edge_collapsed = 0.0;
  // Faces of sliver steps (repair_sliver_steps in sliver_repairs.h) flipped or collapsed away,
  // and the highest step (the farthest the surface moved).
  std::int64_t sliver_steps_removed = 0;
  double highest_sliver_step = 0.0;
  std::int64_t components = 0;                     // edge-connected components
  std::int64_t closed_components = 0;
  std::int64_t patches = 0;
  std::int64_t lines = 0;
  std::int64_t corners = 0;
  // Ridges that end freely and are shorter than twice the size: not kept as lines
  // (FeatureParams::short_ridge_sizes).
  std::int64_t short_ridges_dropped = 0;
  // Two-sided Hausdorff distance between output and input (sampled: vertices, edge midpoints
  // and centroids of each), to the input as sent (before the sliver repairs above moved it), and
  // the largest distance of an output vertex from the input as repaired (the surface the points
  // were projected onto).
  double hausdorff = 0.0;
  double max_vertex_distance = 0.0;
  double model_size = 0.0;  // the input's bounding-box diagonal
  // With more than one component (an assembly): the pairs of input triangles that cross, and
  // the centroid of the first pair's first triangle (global frame). Each component is
  // re-triangulated on its own, so the result crosses where the input does. Not counted for a
  // single component (the check costs O(M log M)).
  std::int64_t input_crossing_pairs = 0;
  Point first_input_crossing{0.0, 0.0, 0.0};
  // Patches whose surface front stopped and that were re-triangulated from their own input
  // triangles instead (patch_from_input.h), and why each front stopped (the message it would
  // otherwise have failed with).
  std::int64_t patches_from_input = 0;
  std::vector<std::string> front_stops;
  // Not 0 when the result crossed itself at the wall sizes asked (none by default) and was made
  // again with its triangles no longer than this many times the walls' thickness
  // (SurfaceParams::wall_sizes; generate_surface_mesh).
  double wall_sizes_after_crossing = 0.0;
  // Of the output's triangles under kThinTriangleDeg (15°), those on an input triangle or at a
  // corner between lines whose own angle is no larger (thin_triangles_at_thinner_input).
  std::int64_t thin_triangles_at_thinner_input = 0;
};

// The wall sizes of a surface re-triangulated as a volume's front (MeshVolume with
// remesh_surface; SurfaceParams::wall_sizes): one element across the thinnest walls. Not the
// default of SurfaceParams since the fallback (patch_from_input.h) re-triangulates the patches
// whose fronts the finer sizes stopped (cgal_dino, cgal_bones): on the corpus at its mean edge
// and at 0.5, 0.7, 1.4 and 2 times it, the same outcomes with it as without (5 December 2026).
inline constexpr double kVolumeFrontWallSizes = 1.0;

struct SurfaceResult {
  // points and triangles of the new surface; triangle_tags: the input tag of each triangle's
  // patch. Oriented as the (cleaned) input.
  Mesh mesh;
  SurfaceReport report;
  std::vector<StageTiming> timings;
};

// Re-triangulates `input` (points N×3, triangles M×3, triangle_tags M or empty) at the size of
// `params`. Errors: INVALID_ARGUMENT (bad input or params, naming the element), CANCELLED
// (progress.cancelled()), RESOURCE_EXHAUSTED (over params.max_triangles), FAILED_PRECONDITION
// (a patch could not be closed; the message says where).
absl::StatusOr<SurfaceResult> generate_surface_mesh(const Mesh& input, const SurfaceParams& params,
                                                    Progress& progress = no_progress());

// Not in the paper: `stuck` (a FAILED_PRECONDITION where a patch's front stopped) with, when
// `clean` (the input as step 1 left it) intersects itself, how many pairs of its triangles cross
// and where the first is: an input that crosses itself has no surface the front can follow
// there, and the message should name that, not only the side. When it does not and `surface`
// (clean's discrete surface) is given, its folded faces (folded_faces in features.h), if any, are
// named instead. Any other status is returned as it is; CANCELLED when progress is. O(M log M),
// run only after a failure.
absl::Status explain_stuck(absl::Status stuck, const Mesh& clean,
                           Progress& progress = no_progress(),
                           const DiscreteSurface* surface = nullptr);

// The pairs of triangles of `mesh` that cross (validate_surface's no_self_intersections) and
// the centroid of the first pair's first triangle, in `mesh`'s frame; 0 pairs when none cross.
// With `components` (one id > 0 per triangle, as face_environments), only pairs within one
// component count. O(M log M).
struct SurfaceCrossings {
  std::int64_t pairs = 0;
  Point first{0.0, 0.0, 0.0};
};
absl::StatusOr<SurfaceCrossings> surface_crossings(
    const Mesh& mesh, std::span<const std::int32_t> components = {},
    Progress& progress = no_progress());

// Not in the paper: FAILED_PRECONDITION when two triangles of one component of `result` (the
// job's output, `components` one id > 0 per triangle as face_environments) cross, naming how many
// pairs and where the first is. The front's crossing test (S6) works in the plane of a side,
// patch by patch; flips, collapses and smoothing move triangles after it, and the patches of a
// thin wall are meshed apart: a surface that crosses itself is no volume's front, and it is never
// returned as a success. Components may cross each other where the input's do (an assembly,
// re-triangulated component by component). O(M log M).
absl::Status check_result_does_not_cross_itself(const Mesh& result,
                                                std::span<const std::int32_t> components,
                                                Progress& progress = no_progress());

// The smallest angle under which a triangle of the output is thin (issue 11: "none under 15°
// away from input corners whose own angle is smaller").
inline constexpr double kThinTriangleDeg = 15.0;

// Not in the paper: how many triangles of `output` (in `input`'s local frame; hosts[i] a face of
// `input` near point i, or kNoFace; triangle_patch[t] the patch triangle t was meshed in, or
// empty) have a smallest angle under `thin_deg` and are as thin as the input there:
//  - on an input triangle whose own smallest angle is no larger (the input face nearest their
//    centroid, found by a walk from the host of their first point): a sliver face whose every
//    edge is a line (its own patch, kept as it is), or a strip between two lines narrower than
//    the gap floor (kMinGapSizes) spanned from line to line;
//  - or alone in their patch at the corner of their smallest angle: both its edges there are
//    line sides, so the angle is the one the lines make at that corner (a corner sharper than
//    the triangle's other angles allow; issue 11's bar: "none under 15° away from input corners
//    whose own angle is smaller").
// The rest are the mesher's to answer for. O(T) plus one walk per thin triangle.
std::int64_t thin_triangles_at_thinner_input(const Mesh& output, std::span<const FaceId> hosts,
                                             std::span<const Index> triangle_patch,
                                             const DiscreteSurface& input,
                                             double thin_deg = kThinTriangleDeg);

}  // namespace afmesh
