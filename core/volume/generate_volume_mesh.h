// MeshVolume: tetrahedra filling a closed triangulated front by the advancing front (paper §1,
// steps F1–F11).
#pragma once

#include <cstdint>
#include <limits>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "absl/status/statusor.h"
#include "core/common/progress.h"
#include "core/common/stage_timing.h"
#include "core/mesh/mesh.h"
#include "core/sizing/size_field.h"
#include "core/sizing/size_spec.h"

namespace afmesh {

// Not in the paper: the least growth of the sizes attached to points (eq. 15). With c_i = 1 a
// new point is never larger than the smallest point of its face, so the boundary's smallest
// sizes spread through the whole domain behind the front that carries them: the interior never
// reaches the size asked for (a front of edges 0.078 at size 0.08 gave interior edges of 0.059),
// and where such a front meets a coarser one there is no room left to grade (real scans and
// parts failed at growth 1 and meshed at 1.2). A uniform mesh follows the size field away from
// the boundary; the boundary's finer sizes grow into it by at least this factor per element.
inline constexpr double kMinAttachedGrowth = 1.2;

// Not in the paper: the words a failure's message uses where a re-triangulated surface would
// avoid what stopped the front (sliver triangles, input edges far longer than the size), so
// that a client able to re-triangulate first (`afmesh volume --remesh-surface`) can say how.
inline constexpr char kRetriangulatedSurfaceAdvice[] = "a surface re-triangulated";

// Not in the paper: the words a result's warning (or a failure) uses where the front could not
// close and the volume was filled from its points instead (generate_volume_mesh: the Delaunay
// tetrahedralisation of the front's points and of those its last run placed, its triangles
// recovered by flips or by refilling their cavities, core/delaunay/conforming_fill.h).
inline constexpr char kDelaunayFillWords[] =
    "filled by the Delaunay tetrahedralisation of its points with its triangles recovered (by "
    "flips, or by refilling their cavities with points inside)";

// The most VolumeParams::local_refinements the service accepts (VolumeOptions.max_reruns): each
// run may do a whole VolumeBudget's work.
inline constexpr int kMaxLocalRefinements = 32;

// Not in the paper: what the input looks like where the front failed, the end of a failure's
// message, so that it names a cause the user can act on: how many input triangles come within
// `radius` of x, their edge lengths against the size asked (`size`) and their smallest angle;
// then, when the smallest angle is under 5 degrees (a sliver) or the edges are far longer
// (over 4 x) or far shorter (under 0.2 x) than the size, that cause named with what avoids it
// (kRetriangulatedSurfaceAdvice in each case: of_bullet.stl, stopped among fillet edges of 0.15 x
// the size, meshes re-triangulated, and did not within 300 s with --growth 1.3 or 2). A scan of
// the input (triangles_near), made once, when the job has already failed.
std::string describe_input_near(const Mesh& input, const Point& x, double radius, double size);

// "after meshing again N times" ("once" for 1): how the message of a job that failed after N
// runs meshed again (VolumeParams::local_refinements) says so, so that a client can tell that
// more were possible.
std::string meshed_again_times(std::int64_t times);

struct VolumeParams {
  // Target edge length h of the uniform size field (> 0, in the units of the points).
  double size = 0.0;
  // Growth factor c_i of eq. 15 (>= 1): a new point's size is at most c_i times the smallest
  // size of the face being deleted. Sizes grow by at least 1.2 per element (not in the paper:
  // with c_i = 1 the boundary's smallest sizes would spread through the whole domain), so 1 and
  // any value up to 1.2 give elements of the size field's size away from a finer boundary.
  double growth = 1.0;
  // The full size specification (sources, background grid; paper §4, eq. 1–14). When set, its
  // max_size and growth replace `size` and `growth` above.
  std::optional<SizeSpec> spec;
  // Improve the worst elements after the front closes (flips and smoothing of interior points,
  // core/quality/optimise.h). The boundary is never changed.
  bool optimise = true;
  std::vector<std::int32_t> face_environments;  // LFACR per input triangle (paper §2); empty = none
  // How many times a front that stops (stuck, or a sliver front over its VolumeBudget, this at
  // most twice) is meshed again from the start with the size halved where it stopped: at every
  // face its run got stuck at, each set aside as the run went on (not in the paper;
  // refine_where_stuck and ParkedFaces in generate_volume_mesh.cc); 0: it fails at once. The
  // wire's VolumeOptions.max_reruns, at most kMaxLocalRefinements.
  int local_refinements = 8;
  // The front stops with FAILED_PRECONDITION once it holds more tets than this (> 0; the
  // server's --max-elements), or once it has used up its VolumeBudget.
  std::int64_t max_tets = std::numeric_limits<std::int64_t>::max();
  // Diagnostics only, never set from the wire: false skips the input check's self-intersection
  // rule, so that a front whose faces cross can be given to the loop without environments, to
  // show how the advancing front fails on it (paper §2, Figure 1). The other rules still apply.
  bool check_self_intersections = true;
  // Diagnostics only, never set from the wire: the share of its VolumeBudget a run of the front
  // may use (searches, tets built and crossing tests; > 0), so that a test can run a front over
  // its budget on a small input and watch what follows.
  double budget_share = 1.0;
};

// Not in the paper: the most work one run of the front loop may do before it stops with
// FAILED_PRECONDITION (saying where it was), so that a front that cannot close ends in time
// proportional to its size n = the expected tets (estimate_volume_mesh) + the input triangles.
// Each limit is at least twice (re-openings: about three times) the most a closing front used in
// the tests and on the corpus and raw CAD fronts of issue 10; the most was netgen_part1 at its
// mean edge (n = 1101: 20 n searches, 3 n tets built, 2200 n face tests, 2 re-openings in a row
// without progress). Fronts of well-shaped triangles use about 1-2 n searches and 40-100 n face
// tests.
struct VolumeBudget {
  // Face deletions tried (F7, one candidate search under one class's rules each): 40 n + 20000.
  std::int64_t searches = 0;
  // Tets built, re-opened ones included (F8): 6 n + 20000.
  std::int64_t tets_built = 0;
  // Front faces and points tested by the crossing check (F7.3), where most of the time goes
  // (0.1-0.3 us each): 500 n + 5 10^6. The closing fronts used at most 230 n beyond the
  // 5 10^6 (occt sh1, n = 13658); netgen_part1's 2200 n are 2.4 10^6.
  std::int64_t face_tests = 0;
  // Re-openings (F11 back-off) in a row while the meshed volume sets no new record:
  // 16 + n / 25000.
  std::int64_t reopenings_without_progress = 0;
};
VolumeBudget volume_budget(double expected_tets, std::int64_t input_triangles);

struct VolumeResult {
  // points: the front's points first, in input order, then the new interior points;
  // tets: positive orientation; triangles: the input front unchanged (with its tags).
  Mesh mesh;
  std::vector<StageTiming> timings;
  // One per time the front stopped and was meshed again with the size halved where it stopped
  // (not in the paper: a front whose back-off fails, among sliver input triangles, up to 8
  // times): why it stopped, and where the size was halved.
  std::vector<std::string> warnings;
};

// Checks that `front` is a valid input front: finite coordinates, indices in range, no degenerate
// triangle, closed, manifold and consistently oriented with outward normals, no self-intersection
// (except, with crossing environments, between faces of two different positive environments,
// paper §2). INVALID_ARGUMENT names the first offending element(s); CANCELLED once
// progress.cancelled() turns true.
absl::Status validate_front(const Mesh& front, std::span<const std::int32_t> face_environments = {},
                            bool check_self_intersections = true,
                            Progress& progress = no_progress());

// F2: the size in space: params.spec's sources and background grid (eq. 1–14) over the front's
// box, or the uniform params.size.
absl::StatusOr<std::unique_ptr<SizeField>> make_size_field(const VolumeParams& params,
                                                           const Mesh& front);

// Fills the volume enclosed by `front` (outward-oriented closed triangles) with tetrahedra whose
// boundary faces are exactly the front's triangles. Where the front gets stuck (its back-off
// fails), it is meshed again with the size halved within 3 sizes of there, at most 8 times, each
// said in VolumeResult::warnings (with crossing environments too). When the last run fails too
// (FAILED_PRECONDITION, on a front without crossing environments), the volume is filled from the
// front's points and those that run placed (kDelaunayFillWords), said in a warning.
// Errors: INVALID_ARGUMENT (bad front or params), CANCELLED (progress.cancelled()),
// FAILED_PRECONDITION (the front could not be closed nor the volume filled from its points; the
// message says where and why).
absl::StatusOr<VolumeResult> generate_volume_mesh(const Mesh& front, const VolumeParams& params,
                                                  Progress& progress);

}  // namespace afmesh
