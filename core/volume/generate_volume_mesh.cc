// MeshVolume: the advancing-front loop of the paper, §1, steps F1–F11.
#include "core/volume/generate_volume_mesh.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <memory>
#include <string>


#include "absl/cleanup/cleanup.h"
#include "absl/strings/str_cat.h"
#include "absl/strings/str_format.h"
#include "core/delaunay/conforming_fill.h"
#include "core/environments/environments.h"
#include "core/front/repair_counts.h"
#include "core/geometry/vec.h"
#include "core/quality/measures.h"
#include "core/quality/optimise.h"
#include "core/quality/validate_common.h"
#include "core/sizing/attached_sizes.h"
#include "core/sizing/spec_size_field.h"
#include "core/volume/end_game_watch.h"
#include "core/volume/estimate_elements.h"
#include "core/volume/front_steps.h"

namespace afmesh {
namespace {

using volume::MesherState;

constexpr int kAttemptsBeforeBackOff = 6;  // queue classes a face passes before a cavity opens
constexpr int kMaxCavityRings = 4;
constexpr double kMinNewPointSpacing = 0.04;  // of the wanted size; the last class allows 0.044
constexpr std::size_t kMaxPocketFaces = 256;  // larger unmeshed regions are not pockets
// fill_by_delaunay's work: kFillTestsPerTriangle element-triangle tests per front triangle
// (conforming_fill.h), and this many more (recover_faces_by_flips).
constexpr std::int64_t kFillTests = 200000;

// Part fills (fill_part_of_pocket) per region: uncounted, a region whose faces each part fill
// leaves stuck again was filled part by part without end (OCCT sh1.stl at 0.5 x its mean edge:
// 364 s, 135k tets, then stuck; with at most 2, stuck after 61 s, and sh1 at its mean edge
// meshes in 1.8 s instead of 6.5 s).
constexpr int kMaxPartFills = 2;
// Grown part fills (fill_grown_part_of_pocket) per region, the last resort once its re-openings
// are used up; each closes the face the region was stuck at. Of the OCCT and corpus runs that
// stopped stuck before it, 2 closed two (cgal_dino, cgal_triceratops), 8 and 32 the same three
// (those and shape.stl at half its mean edge). Letting the region re-open again after each fill
// closed two others (TR12J_OCC at its mean edge, cgal_triceratops).
constexpr int kMaxGrownPartFills = 8;
// A front whose back-off fails (stuck_report) is meshed again from the start with the size
// halved (kLocalRefinementShare) within kLocalRefinementRadius sizes of the first corner of the
// face it stopped at, growing back to the size in force over one more size (a point source,
// eq. 10-11), at most VolumeParams::local_refinements times (refine_where_stuck). The sweep's
// raw CAD and corpus runs (bench/sweep): occt 5 -> 9 of 12 valid (shape.stl at every size,
// TR12J_OCC), the corpus 19 -> 22 of 60. Where the size is halved matters: about the face's
// centroid, 7 of 12.
// Fronts with crossing environments are meshed again too (they were not before): the sails at
// twice their default cells (thin_shapes.h, grid_scale 2) stopped on the jib's cambered side,
// among flat pockets left under elements whose four corners are input points, and mesh once the
// size is halved there three times; bench/sweep's thin group went from 94 to 96 of 100 valid
// (the crossing X of camber 0.02, 6 cells, 0.001 thick). A sliver front (MesherState::
// sliver_front()) over its VolumeBudget is meshed again likewise, about the first corner of the
// face it was working on when the budget ran out: it spends it re-opening the same pockets of
// slivers, at most kMaxRefinementsOverBudget times, each run costing a whole budget. The sweep's
// corpus runs went from 22 to 25 of 60 valid (gmsh_lever at its mean edge, inv_coil at both
// sizes; 2 such runs are needed there), and at --growth 1.3 netgen_part1, gmsh_lever and
// cgal_pinion mesh; the failing runs take 2-10 times longer (sh2.stl 3 -> 35 s, the case that
// kept budget overruns out before: it stops somewhere else each time). VolumeParams::
// local_refinements sets how many times a front is meshed again in all.
constexpr int kMaxRefinementsOverBudget = 2;
// The runs of a job make at most this many times the first run's budget of crossing tests, each
// rerun given what is left (generate_volume_mesh).
constexpr double kJobBudgets = 3.0;
constexpr double kLocalRefinementShare = 0.5;
constexpr double kLocalRefinementRadius = 3.0;
constexpr int kCancelCheckInterval = 256;  // faces between cancellation checks
// Input triangles with an angle below this are called slivers in failure messages.
constexpr double kSliverAngleDeg = 5.0;
// mark_poor_input_faces: input faces whose best element is under this retry at once.
constexpr double kRetryMarkQuality = 0.5;

Box padded_bounds(const std::vector<Point>& points) {
  Box b = empty_box();
  for (const Point& p : points) enclose(b, p);
  double extent = 0;
  for (int a = 0; a < 3; ++a) extent = std::max(extent, b.hi[a] - b.lo[a]);
  for (int a = 0; a < 3; ++a) {
    b.lo[a] -= 0.01 * extent;
    b.hi[a] += 0.01 * extent;
  }
  return b;
}

// Not in the paper: on a front with sliver faces (is_sliver_face), marks the corners of every
// input face whose best element (best_element_quality) is under kRetryMarkQuality as
// MesherState::input_sliver_point, the faces touching them retrying at once under later rules
// (delete_face_with_later_rules). Not only the slivers themselves: among a CAD tessellation's
// caps and needles the faces that stop the front are mostly poor ones beside the slivers, not
// the slivers (TR12J_OCC's stops lay among caps of 150-166 degrees, 14-48 faces from the
// nearest triangle under 5 degrees). Marking the faces under 0.5 took the sweep's corpus runs
// from 28 to 29 of 60 valid and the raw CAD runs from 8 to 9 of 12 (TR12J_OCC as given;
// bench/sweep/README.md).
void mark_poor_input_faces(MesherState& s, const Mesh& input, const std::vector<double>& best) {
  s.input_sliver_point.assign(input.points.size(), false);
  for (std::size_t t = 0; t < input.triangles.size(); ++t)
    if (best[t] < kRetryMarkQuality)
      for (const Index p : input.triangles[t]) s.input_sliver_point[p] = true;
}

// F1/F4: the input triangles, flipped to look into the domain, form the initial front, each with
// its crossing environment (paper §2).
absl::Status load_initial_front(MesherState& s, const Mesh& input,
                                const std::vector<std::int32_t>& face_env) {
  // F5, eq. 15 for the input: each boundary point gets the mean length of its boundary edges.
  absl::StatusOr<std::vector<double>> sizes = attached_point_sizes(
      input, {.rule = EdgeLengthRule::kMean, .tag_sizes = {}, .point_sizes = {}});
  if (!sizes.ok()) return sizes.status();
  s.point_size = *std::move(sizes);
  if (!face_env.empty())
    s.point_env = point_environments(input.points.size(), input.triangles, face_env);
  for (std::size_t t = 0; t < input.triangles.size() && !s.point_env.empty(); ++t) {
    const Triangle& u = input.triangles[t];
    if (face_env[t] != kNoEnvironment ||
        !std::all_of(u.begin(), u.end(),
                     [&](Index p) { return s.point_env[p] == kSharedEnvironment; }))
      continue;
    s.rim_strip_point.resize(input.points.size(), false);
    for (const Index p : u) s.rim_strip_point[p] = true;
  }
  std::vector<double> best(input.triangles.size());
  bool has_sliver = false;
  for (std::size_t t = 0; t < input.triangles.size(); ++t) {
    const Triangle& u = input.triangles[t];
    const Triangle inward{u[0], u[2], u[1]};
    const Index env = face_env.empty() ? 0 : face_env[t];
    best[t] = volume::best_element_quality(s, inward);
    has_sliver = has_sliver ||
                 (s.point_env.empty() && volume::is_sliver_face(s, env, inward, best[t]));
    s.front.add(inward, volume::queue_size_for_face(s, inward, env), env);
  }
  if (has_sliver) mark_poor_input_faces(s, input, best);
  return absl::OkStatus();
}

absl::Status check_face_environments(const Mesh& front, const std::vector<std::int32_t>& env) {
  if (env.empty()) return absl::OkStatus();
  if (env.size() != front.triangles.size())
    return absl::InvalidArgumentError(absl::StrFormat(
        "face_environments has %d entries for %d triangles", env.size(), front.triangles.size()));
  for (std::size_t t = 0; t < env.size(); ++t)
    if (env[t] < 0)
      return absl::InvalidArgumentError(absl::StrFormat(
          "triangle %d has crossing environment %d; environments are >= 0 (0 = none)", t,
          env[t]));
  return absl::OkStatus();
}

// F7: tries the candidates of the face in order, under the acceptance rules for a face that has
// failed `attempts` times (strictness_for); adds the first element that does not cross the front
// (F8–F10). Returns false when none fits. `cap_new_points`: Strictness::cap_new_points.
bool delete_face(MesherState& s, Index face, int attempts, bool cap_new_points = false) {
  ++s.searches;
  volume::adapt_bins_when_crowded(s);
  const Triangle v = s.front.item(face).v;
  volume::Strictness rules = volume::strictness_for(attempts);
  rules.cap_new_points = cap_new_points;
  const double target = volume::target_size_for_face(s, v);           // F5/F9, eq. 15
  double d = volume::element_size_for_target(s, v, target);
  if (d > target && volume::is_sliver_face(s, s.front.item(face).env, v,
                                           volume::best_element_quality(s, v)))
    d = volume::element_size_in_room(s, face, target, d);  // not in the paper (front_steps.h)
  // A face much smaller than the size wanted there (a sliver of front left between elements)
  // closes with points that exist: a new point may not come closer to the front's points than
  // this share of the wanted size. Else each tiny face spawns a tinier element next to it, for
  // ever (seen on the L-block at h 0.05: points 1e-5 apart, tets without end).
  const double min_spacing = kMinNewPointSpacing * target;
  const Point ideal = volume::ideal_point(s, v, d);                    // F7.1
  volume::gather_candidates(s, face, ideal, d, rules);                 // F7.2
  // With crossing environments (paper §2) the two sides of a thin region lie closer than any
  // gap: they keep the rules they had (Strictness::graze is not asked there).
  const double graze = s.point_env.empty() ? rules.graze * d : 0.0;
  for (const volume::Candidate& c : s.candidates) {
    Index p = c.point;
    if (p == kInvalidIndex) {  // a new point: eq. 15 sets its size
      if (!volume::new_point_is_clear(s, c.position, c.spacing_size, c.clearance_size, rules,
                                      s.front.item(face).env, min_spacing))
        continue;
      p = static_cast<Index>(s.points.size());
      s.points.push_back(c.position);
      s.point_size.push_back(
          new_point_size(s.size_field.size_at(c.position), s.growth, s.point_size, v));
    }
    if (!volume::element_crosses_front(s, face, p, nullptr, graze)) {  // F7.3
      volume::add_element(s, face, p);                                 // F8–F10
      return true;
    }
    if (c.point == kInvalidIndex) {
      s.points.pop_back();
      s.point_size.pop_back();
    }
  }
  return false;
}

// Not in the paper: a face touching a poor face of an input with slivers (touches_input_sliver,
// mark_poor_input_faces) that failed under the rules of its queue class retries at once under those
// of the later classes, before it is deferred. F6 orders the queue by class first, so a deferred
// face waits behind the whole front, and among the forced slivers of a CAD tessellation the faces
// around it are meshed over meanwhile and leave it no point at all
// (Regression.Issue10CubeWithOneOrFiveSplitsMeshes). Retried at once, it takes the best point its
// surroundings offer while they are still open. Away from the slivers it is not needed, and it did
// harm: applied to every face of a front that has slivers somewhere, it took poor elements early
// where a deferred face would have found a good one later, and the front filled pockets it then got
// stuck in; the sweep's corpus runs (bench/sweep) went from 25 to 28 of 60 valid (cgal_pinion at
// both sizes, cgal_handle at its mean edge), inv_coil took 2.6 s instead of 7.3 (14,608 tets, not
// 33,554), and of the raw CAD runs TR12J_OCC at its mean edge stopped stuck (9 -> 8 of 12).
// Returns true when it closed.
bool delete_face_with_later_rules(MesherState& s, Index face) {
  for (int attempts = s.front.item(face).attempts + 1; attempts < kAttemptsBeforeBackOff;
       ++attempts)
    if (delete_face(s, face, attempts)) return true;
  return false;
}

// Not in the paper: a coarse face, one whose element is clamped above the size wanted there
// (element_size_for_target: a face of an input much coarser than the size), also retries at once
// under the later rules (delete_face_with_later_rules). Such faces are queued first to grade the
// front down from the boundary's size (queue_key_for_element); where a wall is thinner than
// their elements, the first rules find no point (the best point too near the opposite wall),
// and deferred, a coarse face waited while the finer front grown beside it filled the gap under
// it, where only ever smaller elements fit then (Regression.Issue10ThinWallCoarserThanTheSize-
// Meshes: a plate 2 thick, triangulated at 5.5 on one side, at size 1.145; gmsh_t13_data's
// surface, walls 2 thick with triangles up to 6.7, at sizes 0.8 to 1.3).
bool is_coarse_face(const MesherState& s, Index face) {
  const Triangle& v = s.front.item(face).v;
  const double target = volume::target_size_for_face(s, v);
  return volume::element_size_for_target(s, v, target) > target;
}

}  // namespace

std::string describe_input_near(const Mesh& input, const Point& x, double radius, double size) {
  const TrianglesNear near = triangles_near(input.points, input.triangles, x, radius);
  const std::int64_t count = near.count;
  const double smallest_angle = near.smallest_angle_deg, shortest = near.shortest_edge,
               longest = near.longest_edge;
  if (count == 0) return absl::StrFormat("; no input triangle within %g of there", radius);
  std::string text = absl::StrFormat(
      "; the %d input triangles within %g of there have edges %g to %g long (size asked %g) and "
      "angles down to %.3g degrees",
      count, radius, shortest, longest, size, smallest_angle);
  if (smallest_angle < kSliverAngleDeg) {
    absl::StrAppend(&text,
                    ": sliver triangles, whose elements are slivers too; the front could not "
                    "close among them: ",
                    kRetriangulatedSurfaceAdvice, " with better-shaped triangles avoids this");
  } else if (shortest > 4.0 * size) {
    absl::StrAppend(&text,
                    ": input edges far longer than the size, which the front must grade down "
                    "from in the gaps along them; a size nearer the input's edges, or ",
                    kRetriangulatedSurfaceAdvice, " at the size, avoids this");
  } else if (shortest < 0.2 * size) {
    absl::StrAppend(&text,
                    ": input edges far shorter than the size; a smaller size or a larger --growth "
                    "gives the front room to grade, ",
                    kRetriangulatedSurfaceAdvice, " at the size avoids the short edges");
  }
  return text;
}

namespace {

// describe_input_near for front face v, where the front failed at x: within three of its
// element sizes (or target sizes, when larger) of x.
std::string describe_input_near_face(const MesherState& s, const Mesh& input, const Triangle& v,
                                     const Point& x) {
  const double target = volume::target_size_for_face(s, v);
  const double d = volume::element_size_for_target(s, v, target);
  return describe_input_near(input, x, 3.0 * std::max(d, target), target);
}

// Not in the paper: whether the back-off makes progress. Re-opening elements (F11) gives up
// meshed volume to mesh it again; a front that re-opens again and again without its meshed
// volume ever passing its best so far is going round in circles, even when each re-opening is
// in a new region (netgen_part1 at 0.5 x its mean edge: 43 re-openings, the whole mesh
// re-opened twice, 19x its expected tets built before the ring limit stopped it).
class ReopeningWatch {
 public:
  explicit ReopeningWatch(double domain_volume) : tolerance_(kRecordShare * domain_volume) {}
  // Call once per step.
  void step(const MesherState& s) {
    if (s.meshed_volume <= record_ + tolerance_) return;
    record_ = s.meshed_volume;
    since_record_ = 0;
  }
  // Counts a re-opening; returns how many there have been since the last record.
  std::int64_t reopened() { return ++since_record_; }

 private:
  // A record beats the last by more than this share of the enclosed volume: the running sum of
  // the tets' volumes drifts by rounding as elements come and go.
  static constexpr double kRecordShare = 1e-12;
  double tolerance_;
  double record_ = 0;
  std::int64_t since_record_ = 0;
};

// FAILED_PRECONDITION for the back-off: the front got stuck at face v (centroid x) `how`, with
// what the input looks like there (describe_input_near_face).
absl::Status stuck_report(const MesherState& s, const Mesh& input, const Triangle& v,
                          const Point& x, const std::string& how) {
  return absl::FailedPreconditionError(absl::StrCat(
      absl::StrFormat("the front got stuck at face (%d, %d, %d) near (%g, %g, %g) %s; %d tets "
                      "built (%d of them since re-opened), %d front faces left",
                      v[0], v[1], v[2], x[0], x[1], x[2], how, s.tets.size(),
                      static_cast<std::int64_t>(s.tets.size()) - s.live_tets, s.front.size()),
      describe_input_near_face(s, input, v, x)));
}

// The back-off's counts per region (RepairCounts): re-openings, part fills and grown part fills.
struct BackOffCounts {
  RepairCounts reopenings, part_fills, grown_part_fills;
};

// The back-off for a face that failed in every queue class (F11): fill the small pocket it
// bounds from one kernel point, or, when it has none, the part of it about `face` that one point
// sees (at most kMaxPartFills times per region); failing that, re-open the elements around it,
// one ring more each time the same region needs it again. When the region has been re-opened
// kMaxCavityRings times, the part grown from `face` (fill_grown_part_of_pocket, at most
// kMaxGrownPartFills times per region) is the last resort: only a job that would stop here tries
// it, so every job that closes without it is unchanged. Fails when that fails too (`may_park`
// set: the front loop sets the face aside and goes on, ParkedFaces), or when the front has
// re-opened `max_reopenings` times in a row without progress (ReopeningWatch).
absl::Status back_off(MesherState& s, const Mesh& input, Index face, BackOffCounts& counts,
                      ReopeningWatch& watch, std::int64_t max_reopenings, bool& may_park) {
  may_park = false;
  const Triangle v = s.front.item(face).v;
  const std::uint32_t stamp = s.front.item(face).stamp;
  const Point centroid =
      scale(add(s.points[v[0]], add(s.points[v[1]], s.points[v[2]])), 1.0 / 3.0);
  const double d = volume::element_size_for_face(s, v);
  const auto requeue = [&] {
    const FrontItem<3>& f = s.front.item(face);
    if (f.alive && f.stamp == stamp) {
      s.front.requeue(face, volume::queue_size_for_face(s, v, f.env));
    }
    return absl::OkStatus();
  };
  const auto fill_part = [&](RepairCounts& fill_counts, int max_fills, auto&& fill) {
    int& fills = fill_counts.at(centroid, d);
    if (fills >= max_fills) return false;
    ++fills;
    return fill(s, face, kMaxPocketFaces) > 0;
  };
  if (volume::fill_pocket(s, face, kMaxPocketFaces) > 0 ||
      fill_part(counts.part_fills, kMaxPartFills, volume::fill_part_of_pocket))
    return requeue();
  int& count = counts.reopenings.at(centroid, d);
  // Not in the paper: a cap stuck again where the front has re-opened before takes a new point
  // in the thin pocket it may lie in (cap_clearance_size in candidates.cc). Tried on a
  // cap's last try instead, before any back-off, it took flat elements where re-opening once
  // found better ones (a 48-round cylinder with fanned caps: min dihedral 17.9 -> 8.5 degrees).
  if (count > 0 && volume::is_cap_face(s, v) &&
      delete_face(s, face, kAttemptsBeforeBackOff - 1, /*cap_new_points=*/true))
    return absl::OkStatus();
  const int rings = 1 + count;
  const Point& x = centroid;
  if (rings > kMaxCavityRings) {
    if (fill_part(counts.grown_part_fills, kMaxGrownPartFills, volume::fill_grown_part_of_pocket))
      return requeue();
    may_park = true;
    return stuck_report(
        s, input, v, x,
        absl::StrFormat("after its region had been re-opened %d times (the most per region)",
                        kMaxCavityRings));
  }
  if (watch.reopened() > max_reopenings)
    return stuck_report(
        s, input, v, x,
        absl::StrFormat("after re-opening elements %d times in a row (its budget) without "
                        "meshing more of the volume than at its best",
                        max_reopenings));
  ++count;
  volume::open_cavity(s, face, rings);
  return requeue();
}

absl::Status overlap_report(const MesherState& s, Index face, double domain_volume) {
  const Triangle v = s.front.item(face).v;
  const Point& x = s.points[v[0]];
  return absl::FailedPreconditionError(absl::StrFormat(
      "the elements overlap: their volume %g exceeds the enclosed volume %g after %d tets; the "
      "fronts passed through each other near (%g, %g, %g), face environment %d. With crossing "
      "environments, give the faces on each side of a thin region one environment (paper §2)",
      s.meshed_volume, domain_volume, s.live_tets, x[0], x[1], x[2], s.front.item(face).env));
}

// FAILED_PRECONDITION: `what` went wrong, then the face being worked on, where it is, and what
// the input looks like there (describe_input_near_face).
absl::Status failure_at_face(const MesherState& s, const Mesh& input, Index face,
                             const std::string& what) {
  const Triangle v = s.front.item(face).v;
  const Point& x = s.points[v[0]];
  return absl::FailedPreconditionError(
      absl::StrCat(what,
                   absl::StrFormat(", last face (%d, %d, %d) near (%g, %g, %g)", v[0], v[1], v[2],
                                   x[0], x[1], x[2]),
                   describe_input_near_face(s, input, v, x)));
}

absl::Status end_game_report(const MesherState& s, const Mesh& input, Index face,
                             double domain_volume, std::int64_t smallest_front) {
  return failure_at_face(
      s, input, face,
      absl::StrFormat(
          "the front stopped closing: the elements hold all but %.2g of the enclosed volume, but "
          "the last front faces (%d now, %d at best) only make ever smaller elements; %d tets "
          "built",
          1.0 - s.meshed_volume / domain_volume, s.front.size(), smallest_front, s.live_tets));
}

// VolumeParams::max_tets: the server's limit on the mesh it will send.
absl::Status overbuilt_report(const MesherState& s, const Mesh& input, Index face,
                              double expected_tets, std::int64_t max_tets) {
  return failure_at_face(
      s, input, face,
      absl::StrFormat("the front built %d tets, over its limit of %d (the size field asks for "
                      "about %.0f), with %d front faces left",
                      s.live_tets, max_tets, expected_tets, s.front.size()));
}

// The job's VolumeBudget used up: a front that builds and re-opens many times the elements
// the size field asks for (estimate_volume_mesh), or keeps searching without closing, is making
// them far smaller than asked or going round in circles, wherever it is stuck; it stops with a
// report instead of running on.
std::string budget_overrun(const MesherState& s, const VolumeBudget& budget,
                           double expected_tets) {
  const auto tets_built = static_cast<std::int64_t>(s.tets.size());
  if (tets_built > budget.tets_built)
    return absl::StrFormat(
        "the front built %d tets (%d of them since re-opened), over its budget of %d (the size "
        "field asks for about %.0f), with %d front faces left",
        tets_built, tets_built - s.live_tets, budget.tets_built, expected_tets, s.front.size());
  if (s.searches > budget.searches || s.face_tests > budget.face_tests)
    return absl::StrFormat(
        "the front did not close within its budget of %d face deletions and %d crossing tests "
        "(it tried %d and made %d): %d tets built (%d of them since re-opened; the size field "
        "asks for about %.0f), %d front faces left",
        budget.searches, budget.face_tests, s.searches, s.face_tests, tets_built,
        tets_built - s.live_tets, expected_tets, s.front.size());
  return {};
}


// The points the front placed that its live elements use (a stopped run's, for
// fill_by_delaunay).
std::vector<Point> points_placed(const MesherState& s) {
  std::vector<bool> used(s.points.size(), false);
  for (const Tet& t : s.tets)
    if (t[0] != kInvalidIndex)
      for (Index q : t) used[q] = true;
  std::vector<Point> out;
  for (std::size_t p = static_cast<std::size_t>(s.input_points); p < s.points.size(); ++p)
    if (used[p]) out.push_back(s.points[p]);
  return out;
}

// The mesh of `tets` (those with tet[0] == kInvalidIndex deleted) on `points`, of which the
// first `input_points` are the input's and keep their indices; the other points no tet uses are
// dropped. The triangles are the input's, with its tags. CANCELLED when the call is cancelled:
// a 2M-tet compaction takes ~100 ms, too long to finish for a caller that no longer waits
// (issue 12, part 3).
absl::StatusOr<Mesh> compacted_mesh(const std::vector<Point>& points, Index input_points,
                                    const std::vector<Tet>& tets, std::int64_t live_tets,
                                    const Mesh& input, Progress& progress) {
  CancelCheck cancel(progress);
  Mesh out;
  std::vector<Index> new_index(points.size(), kInvalidIndex);
  for (Index p = 0; p < input_points; ++p) new_index[p] = p;
  Index next = input_points;
  out.tets.reserve(static_cast<std::size_t>(live_tets));
  for (const Tet& t : tets) {
    if (cancel.due()) return absl::CancelledError("volume meshing cancelled");
    if (t[0] == kInvalidIndex) continue;
    Tet u;
    for (int k = 0; k < 4; ++k) {
      if (new_index[t[k]] == kInvalidIndex) new_index[t[k]] = next++;
      u[k] = new_index[t[k]];
    }
    out.tets.push_back(u);
  }
  out.points.resize(static_cast<std::size_t>(next));
  for (std::size_t p = 0; p < points.size(); ++p)
    if (new_index[p] != kInvalidIndex) out.points[new_index[p]] = points[p];
  out.tet_tags.assign(out.tets.size(), 0);
  out.triangles = input.triangles;
  out.triangle_tags = input.triangle_tags;
  out.triangle_tags.resize(out.triangles.size(), 0);
  return out;
}

// The front's result: its live tets, the points they use.
absl::StatusOr<Mesh> compact_result(const MesherState& s, const Mesh& input, Progress& progress) {
  return compacted_mesh(s.points, s.input_points, s.tets, s.live_tets, input, progress);
}

// Where a run of the front loop stopped for refine_where_stuck to mesh again, and why.
struct Stop {
  std::vector<Point> at;     // the places, the first where it stopped first
  bool over_budget = false;  // a sliver front over its VolumeBudget (otherwise stuck)
  std::int64_t face_tests = 0;         // the crossing tests the run made (MesherState)
  std::int64_t budget_face_tests = 0;  // and those its VolumeBudget allowed
};

// Not in the paper: the faces a run of the front loop set aside where the back-off failed
// (back_off's may_park), so that one run finds the places that need a smaller size
// (refine_where_stuck), not only the first. A parked face stays on the front, out of the
// queue: the crossing checks still see it, and an element of a neighbour may close it yet (or a
// re-opening remove it), after which it no longer counts. Before, a run stopped at the first
// such face and the next run, meshed again from the start with the size halved there, found
// the next place, one place per run: netgen_hinge at a 25th of its diagonal stopped at nine
// places and failed with the default eight reruns. Going on costs work (the faces round a
// parked one fail in turn), so a run goes on past its first parked face for at most 4 times the
// crossing tests it made before it (kGoOnShare; at 1 the hinge took 7 reruns, at 4 it takes 2);
// past that, or at kMaxParked faces, it stops.
class ParkedFaces {
 public:
  // Whether a face that failed may be set aside.
  bool may_park(const MesherState& s) const {
    return parked_.size() < kMaxParked && !gone_on_long_enough(s);
  }
  // Sets aside `face` (its stamp when it failed), which failed at `at` with `why`.
  void park(const MesherState& s, Index face, const Point& at, absl::Status why) {
    if (parked_.empty()) tests_before_ = s.face_tests;
    parked_.push_back({face, s.front.item(face).stamp, at, std::move(why)});
  }
  // Whether the run has gone on past its first parked face for long enough.
  bool gone_on_long_enough(const MesherState& s) const {
    return !parked_.empty() && static_cast<double>(s.face_tests - tests_before_) >
                                   kGoOnShare * static_cast<double>(tests_before_);
  }
  // The places of the faces still parked, then `also` (where the run stopped, if it did):
  // the first of each cluster, a place within kClusterSizes sizes (`field`) of one kept being
  // left out, at most kMaxPlaces.
  std::vector<Point> places(const MesherState& s, const SizeField& field,
                            std::optional<Point> also = std::nullopt) const {
    std::vector<Point> all;
    for (const std::size_t i : left(s)) all.push_back(parked_[i].at);
    if (also) all.push_back(*also);
    std::vector<Point> kept;
    for (const Point& x : all) {
      if (kept.size() >= kMaxPlaces) break;
      const double reach = kClusterSizes * field.size_at(x);
      if (std::none_of(kept.begin(), kept.end(),
                       [&](const Point& y) { return distance(x, y) < reach; }))
        kept.push_back(x);
    }
    return kept;
  }
  // With faces still parked: `stopped_near` set to their places, and the first one's failure,
  // which says at how many places the run got stuck. Nullopt when none is left.
  std::optional<absl::Status> stop(const MesherState& s, const SizeField& field,
                                   std::optional<Stop>& stopped_near) const {
    const std::vector<std::size_t> still = left(s);
    if (still.empty()) return std::nullopt;
    stopped_near = Stop{places(s, field), false};
    const absl::Status& first = parked_[still[0]].why;
    if (stopped_near->at.size() < 2) return first;
    return absl::Status(
        first.code(),
        absl::StrCat(first.message(),
                     absl::StrFormat("; the run went on past it and got stuck at %d places in all",
                                     stopped_near->at.size())));
  }
  // How many parked faces are still on the front.
  std::int64_t count_left(const MesherState& s) const {
    return static_cast<std::int64_t>(left(s).size());
  }

 private:
  // The parked faces still on the front, in the order they were parked.
  std::vector<std::size_t> left(const MesherState& s) const {
    std::vector<std::size_t> out;
    for (std::size_t i = 0; i < parked_.size(); ++i) {
      const FrontItem<3>& f = s.front.item(parked_[i].face);
      if (f.alive && f.stamp == parked_[i].stamp) out.push_back(i);
    }
    return out;
  }
  // Bounds on the faces parked in one run, on the work after the first (a share of the
  // crossing tests before it), and on the places a run gives (each a point source, which every
  // size query evaluates).
  static constexpr std::size_t kMaxParked = 4096;
  static constexpr double kGoOnShare = 4.0;
  static constexpr std::size_t kMaxPlaces = 16;
  // A place within one refinement radius of a kept one is inside its refined ball already.
  static constexpr double kClusterSizes = kLocalRefinementRadius;
  struct Parked {
    Index face;
    std::uint32_t stamp;
    Point at;
    absl::Status why;
  };
  std::vector<Parked> parked_;
  std::int64_t tests_before_ = 0;  // MesherState::face_tests at the first park
};

// `share` of the work `budget` allows (VolumeParams::budget_share).
VolumeBudget share_of(VolumeBudget budget, double share) {
  const auto part = [&](std::int64_t n) {
    return static_cast<std::int64_t>(share * static_cast<double>(n));
  };
  budget.searches = part(budget.searches);
  budget.tets_built = part(budget.tets_built);
  budget.face_tests = part(budget.face_tests);
  return budget;
}

// F1–F11: the front loop itself. Returns the compacted mesh; the mesher's state (front, bins,
// incidence lists) is freed on return, before the optimiser builds its own structures. At most
// `max_face_tests` crossing tests (what the job's reruns have left), or its VolumeBudget's.
absl::StatusOr<Mesh> advance_front(const Mesh& front, const VolumeParams& params,
                                   const SizeField& size_field, double growth, StageClock& clock,
                                   Progress& progress, std::optional<Stop>& stopped_near,
                                   std::int64_t max_face_tests, std::vector<Point>& placed) {
  const double boundary_edge = mean_edge_length(front);
  const double domain_volume = enclosed_volume(front.points, front.triangles, nullptr);
  const double max_size = params.spec ? params.spec->max_size : params.size;
  const double h = std::min(max_size, boundary_edge);
  // The bins' cells are about one element: sized by the boundary alone, a size well below the
  // input's edges put hundreds of front points in a cell (a cube of edges 0.15 at size 0.02 did
  // not finish in 400 s).
  MesherState s(front, std::max(growth, kMinAttachedGrowth), size_field,
                padded_bounds(front.points), h);
  const double expected_tets =
      std::max(1.0, estimate_volume_mesh(front, size_field, max_size, growth).tets);
  VolumeBudget budget = share_of(
      volume_budget(expected_tets, static_cast<std::int64_t>(front.triangles.size())),
      params.budget_share);
  budget.face_tests = std::min(budget.face_tests, max_face_tests);
  const std::int64_t max_tets = params.max_tets;
  s.tets.reserve(static_cast<std::size_t>(
      std::min({expected_tets * 1.3, 1.0 * max_tets, 1.0 * budget.tets_built})));
  s.points.reserve(front.points.size() + static_cast<std::size_t>(expected_tets / 4));
  if (absl::Status st = load_initial_front(s, front, params.face_environments); !st.ok())
    return st;
  bool closed = false;
  const absl::Cleanup count_work = [&] {
    if (!closed) placed = points_placed(s);
    if (!stopped_near) return;
    stopped_near->face_tests = s.face_tests;
    stopped_near->budget_face_tests = budget.face_tests;
  };

  BackOffCounts back_off_counts;
  ParkedFaces parked;
  volume::EndGameWatch end_game;
  ReopeningWatch reopenings(domain_volume);
  std::int64_t steps = 0;
  while (std::optional<Index> face = s.front.pop()) {                  // F6, F11
    ++steps;
    reopenings.step(s);
    if (std::string overrun = budget_overrun(s, budget, expected_tets); !overrun.empty()) {
      const Point at = s.points[s.front.item(*face).v[0]];
      if (s.sliver_front())
        stopped_near = Stop{parked.places(s, size_field, at), true};
      else if (parked.count_left(s) > 0)
        stopped_near = Stop{parked.places(s, size_field), false};
      return failure_at_face(s, front, *face, overrun);
    }
    if (end_game.stalled(s.meshed_volume, domain_volume, s.front.size(), steps)) {
      // Meshed again finer where it stalled, as where it got stuck (a latitude-longitude
      // sphere's pole: Regression.Issue10EndGameStopIsMeshedAgainWhereItStopped).
      stopped_near = Stop{{s.points[s.front.item(*face).v[0]]}, false};
      return end_game_report(s, front, *face, domain_volume, end_game.smallest_front());
    }
    if (steps % kCancelCheckInterval == 0) {
      if (progress.cancelled()) return absl::CancelledError("volume meshing cancelled");
      if (s.live_tets > max_tets) return overbuilt_report(s, front, *face, expected_tets, max_tets);
      // Elements that do not overlap cannot hold more than the enclosed volume. With crossing
      // environments whose faces hide each other where they should not (paper §2), fronts
      // could pass through each other and mesh space twice: stop then, with a report.
      if (s.meshed_volume > domain_volume * (1.0 + 1e-6))
        return overlap_report(s, *face, domain_volume);
      progress.report("front", std::min(0.99, static_cast<double>(s.live_tets) / expected_tets));
      if (parked.gone_on_long_enough(s))
        if (std::optional<absl::Status> st = parked.stop(s, size_field, stopped_near)) return *st;
    }
    if (delete_face(s, *face, s.front.item(*face).attempts)) continue;
    if ((volume::touches_input_sliver(s, s.front.item(*face).v) || is_coarse_face(s, *face)) &&
        delete_face_with_later_rules(s, *face))
      continue;
    const FrontItem<3>& f = s.front.item(*face);
    if (f.attempts + 1 < kAttemptsBeforeBackOff) {
      s.front.defer(*face, volume::queue_size_for_face(s, f.v, f.env));
      continue;
    }
    const Point at = s.points[f.v[0]];  // where refine_where_stuck halves the size
    bool may_park = false;
    if (absl::Status st = back_off(s, front, *face, back_off_counts, reopenings,
                                   budget.reopenings_without_progress, may_park);
        !st.ok()) {
      if (may_park && parked.may_park(s)) {
        parked.park(s, *face, at, std::move(st));
        continue;
      }
      // With faces parked, their places only: the run went on around them, and where it
      // stopped after them is not where the front as meshed from the start stops (the issue's
      // large sails at 1 mm: refined there too, the reruns got stuck again beside the first
      // place, 3 reruns and +35% tets, where refined at the first place alone they close).
      if (st.code() == absl::StatusCode::kFailedPrecondition)
        stopped_near = Stop{parked.count_left(s) > 0 ? parked.places(s, size_field)
                                                     : std::vector<Point>{at},
                            false};
      return st;
    }
  }
  // Every live face is queued but those parked: an empty queue means a front of parked faces.
  if (s.front.size() != parked.count_left(s))
    return absl::InternalError(absl::StrFormat(
        "the front queue ran empty with %d faces left on the front", s.front.size()));
  if (std::optional<absl::Status> st = parked.stop(s, size_field, stopped_near)) return *st;
  closed = true;
  clock.lap("front");

  absl::StatusOr<Mesh> mesh = compact_result(s, front, progress);
  if (!mesh.ok()) return mesh.status();
  clock.lap("compact");
  return mesh;
}

// Not in the paper (VolumeParams::local_refinements): the run's size specification (made from
// its uniform size and growth when it has none) gains a point source at x, halving the size
// `field` gives there within kLocalRefinementRadius of it; returns that radius. Sliver input
// triangles (CAD tessellations) leave the front pockets no element of their sizes fits; smaller
// elements there do.
double refine_where_stuck(VolumeParams& run, const SizeField& field, const Point& x) {
  if (!run.spec)
    run.spec = SizeSpec{
        .max_size = run.size, .growth = run.growth, .sources = {}, .background = std::nullopt};
  const double local = field.size_at(x);
  run.spec->sources.push_back({.points = {x},
                               .delta0 = kLocalRefinementShare * local,
                               .r0 = kLocalRefinementRadius * local,
                               .r1 = local,
                               .law = PowerLaw{.gamma = 1.0}});
  return kLocalRefinementRadius * local;
}

// Not in the paper (issue 10, part 3): the fill of a front the volume front could not close however
// often it meshed it again: the Delaunay tetrahedralisation of its points and of the interior
// points its last run placed, with the front's triangles recovered by flips and by refilling
// cavities with Steiner points inside (conforming_fill, core/delaunay/conforming_fill.h), as
// TetGen's -pY meshes sliver fronts as given. The optimiser then improves it as any other mesh.
// FAILED_PRECONDITION when a triangle cannot be recovered, or the fill has more than `max_tets`
// elements.
absl::StatusOr<Mesh> fill_by_delaunay(const Mesh& front, const std::vector<Point>& placed,
                                      std::int64_t max_tets, Progress& progress,
                                      std::int64_t& steiner_points) {
  std::vector<Point> points = front.points;
  points.insert(points.end(), placed.begin(), placed.end());
  const std::int64_t work =
      kFillTestsPerTriangle * static_cast<std::int64_t>(front.triangles.size()) + kFillTests;
  absl::StatusOr<ConformingFill> fill = conforming_fill(points, front.triangles, work, progress);
  if (!fill.ok()) return fill.status();
  if (static_cast<std::int64_t>(fill->tets.size()) > max_tets)
    return absl::FailedPreconditionError(absl::StrFormat(
        "the fill has %d tets, over the most allowed (%d)", fill->tets.size(), max_tets));
  points.insert(points.end(), fill->steiner.begin(), fill->steiner.end());
  steiner_points = static_cast<std::int64_t>(fill->steiner.size());
  return compacted_mesh(points, static_cast<Index>(front.points.size()), fill->tets,
                        static_cast<std::int64_t>(fill->tets.size()), front, progress);
}

}  // namespace

VolumeBudget volume_budget(double expected_tets, std::int64_t input_triangles) {
  const double n = expected_tets + static_cast<double>(input_triangles);
  return {.searches = static_cast<std::int64_t>(40 * n + 20000),
          .tets_built = static_cast<std::int64_t>(6 * n + 20000),
          .face_tests = static_cast<std::int64_t>(500 * n + 5e6),
          .reopenings_without_progress = static_cast<std::int64_t>(16 + n / 25000)};
}

// F2: the size in space: the specification's sources and background grid (eq. 1–14), or one
// uniform size.
absl::StatusOr<std::unique_ptr<SizeField>> make_size_field(const VolumeParams& params,
                                                           const Mesh& front) {
  return make_size_field(params.spec, params.size, front.points);
}

std::string meshed_again_times(std::int64_t times) {
  if (times == 1) return "after meshing again once";
  return absl::StrFormat("after meshing again %d times", times);
}

absl::StatusOr<VolumeResult> generate_volume_mesh(const Mesh& front, const VolumeParams& params,
                                                  Progress& progress) {
  VolumeResult result;
  StageClock clock(result.timings);
  if (!params.spec) {
    if (!(params.size > 0) || !std::isfinite(params.size))
      return absl::InvalidArgumentError(absl::StrFormat("size must be > 0, got %g", params.size));
    if (!(params.growth >= 1.0) || !std::isfinite(params.growth))
      return absl::InvalidArgumentError(
          absl::StrFormat("growth must be >= 1, got %g", params.growth));
  }
  if (!(params.budget_share > 0) || !std::isfinite(params.budget_share))
    return absl::InvalidArgumentError(
        absl::StrFormat("budget_share must be > 0, got %g", params.budget_share));
  if (params.local_refinements < 0)
    return absl::InvalidArgumentError(absl::StrFormat(
        "local_refinements must be >= 0, got %d", params.local_refinements));
  if (absl::Status st = check_face_environments(front, params.face_environments); !st.ok())
    return st;
  if (absl::Status st = validate_front(front, params.face_environments,
                                       params.check_self_intersections, progress);
      !st.ok())
    return st;
  VolumeParams run = params;
  // A front none of whose faces has an environment (--envs auto that found no thin region) is
  // meshed as one given without environments, by the same rules (not in the paper): the
  // filters of §2 would change nothing, but the rules that differ on fronts with environments
  // (sliver faces, back-off) would.
  if (count_environments(run.face_environments) == 0) run.face_environments.clear();
  absl::StatusOr<std::unique_ptr<SizeField>> size_field = make_size_field(run, front);
  if (!size_field.ok()) return size_field.status();
  const double growth = params.spec ? params.spec->growth : params.growth;
  clock.lap("validate");

  // F1–F11, and again with the size halved where the back-off failed (refine_where_stuck, not
  // in the paper), each time said in a warning; the last failure names every such place.
  absl::StatusOr<Mesh> mesh = absl::UnknownError("not run");
  std::string where;  // the places the size was halved, for the last failure
  int over_budget = 0;  // runs that stopped over their budget
  // The crossing tests of the runs so far, and the first run's budget of them: the runs of a
  // job make at most kJobBudgets times that, each rerun given what is left (not in the paper).
  // Runs that go on past the faces they parked (ParkedFaces) may each use a whole budget; a
  // front that cannot close (OCCT's sh2.stl at half its mean edge) then took over 140 s to say
  // so, 48 s with the bound.
  std::int64_t tests_used = 0, first_budget = 0;
  bool out_of_work = false;
  std::vector<Point> placed;  // the points a run that stopped had placed
  for (int refinement = 0;; ++refinement) {
    std::optional<Stop> stopped_near;
    const std::int64_t left =
        first_budget == 0
            ? std::numeric_limits<std::int64_t>::max()
            : static_cast<std::int64_t>(kJobBudgets * static_cast<double>(first_budget)) -
                  tests_used;
    mesh = advance_front(front, run, **size_field, growth, clock, progress, stopped_near, left,
                         placed);
    if (mesh.ok() || !stopped_near || refinement >= params.local_refinements) break;
    tests_used += stopped_near->face_tests;
    if (first_budget == 0) first_budget = stopped_near->budget_face_tests;
    if (static_cast<double>(tests_used) >= kJobBudgets * static_cast<double>(first_budget)) {
      out_of_work = true;
      break;
    }
    if (stopped_near->over_budget && ++over_budget > kMaxRefinementsOverBudget) break;
    std::string within;  // each place with its radius, for the warning
    for (const Point& x : stopped_near->at) {
      const std::string place = absl::StrFormat("(%g, %g, %g)", x[0], x[1], x[2]);
      const double radius = refine_where_stuck(run, **size_field, x);
      absl::StrAppend(&within, within.empty() ? "" : ", ", absl::StrFormat("%g of ", radius),
                      place);
      absl::StrAppend(&where, where.empty() ? "" : ", ", place);
    }
    result.warnings.push_back(absl::StrCat(
        mesh.status().message(), "; meshed again with the size halved within ", within));
    size_field = make_size_field(run, front);
    if (!size_field.ok()) return size_field.status();
  }
  if (!mesh.ok()) {
    absl::Status failed = mesh.status();
    if (!result.warnings.empty())
      failed = absl::Status(
          failed.code(),
          absl::StrCat(failed.message(), "; ",
                       meshed_again_times(static_cast<std::int64_t>(result.warnings.size())),
                       " with the size halved where it stopped before: ", where,
                       out_of_work ? absl::StrFormat("; its runs made %d crossing tests, over %g "
                                                     "times the first run's budget",
                                                     tests_used, kJobBudgets)
                                   : ""));
    if (failed.code() != absl::StatusCode::kFailedPrecondition ||
        !run.face_environments.empty())
      return failed;
    clock.lap("front");
    std::int64_t steiner_points = 0;
    mesh = fill_by_delaunay(front, placed, params.max_tets, progress, steiner_points);
    if (mesh.status().code() == absl::StatusCode::kCancelled) return mesh.status();
    if (!mesh.ok())
      return absl::Status(
          failed.code(),
          absl::StrCat(failed.message(),
                       "; nor could the volume be filled from its points (their Delaunay "
                       "tetrahedralisation, its triangles recovered by flips or by refilling "
                       "their cavities): ",
                       mesh.status().message()));
    result.warnings.push_back(absl::StrFormat(
        "%s; %s instead (%d points the front had placed, %d points added inside, no new "
        "boundary point)",
        failed.message(), kDelaunayFillWords, placed.size(), steiner_points));
    clock.lap("delaunay fill");
  }
  result.mesh = *std::move(mesh);
  progress.report("front", 1.0);
  if (params.optimise) {
    absl::StatusOr<OptimiseStats> stats =
        optimise_tets(result.mesh, static_cast<Index>(front.points.size()), OptimiseParams{},
                      progress);
    if (!stats.ok()) return stats.status();
    clock.lap("optimise");
  }
  return result;
}

}  // namespace afmesh
