#include "server/surface_step.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <utility>

#include "absl/strings/str_cat.h"
#include "absl/strings/str_format.h"
#include "core/geometry/vec.h"
#include "core/sizing/spec_size_field.h"
#include "core/spatial/box.h"
#include "core/surface/features.h"
#include "core/surface/sliver_repairs.h"
#include "server/run_guarded.h"
#include "server/volume_output.h"

namespace afmesh::server {
namespace {

using Clock = std::chrono::steady_clock;
using call_detail::seconds_since;

constexpr double kPi = 3.14159265358979323846;

// The corner angle at `a` of triangle (a, b, c), in degrees; 0 when an edge at `a` has no length.
double corner_angle_deg(const Point& a, const Point& b, const Point& c) {
  const Point u = sub(b, a);
  const Point v = sub(c, a);
  if (squared_norm(u) == 0.0 || squared_norm(v) == 0.0) return 0.0;
  return std::atan2(norm(cross(u, v)), dot(u, v)) * 180.0 / kPi;
}

// The report's changes to the input, as notes for the user.
void add_repair_notes(const SurfaceReport& report, std::vector<std::string>& notes) {
  const auto note = [&notes](std::int64_t count, const char* what) {
    if (count > 0) notes.push_back(absl::StrFormat("%d %s", count, what));
  };
  note(report.duplicate_triangles_dropped,
       "duplicate triangles of the input (the same three points as an earlier one) were dropped");
  note(report.degenerate_triangles_dropped,
       "degenerate triangles of the input (a repeated point or no area) were dropped");
  note(report.unused_points_dropped, "points of the input on no triangle were dropped");
  note(report.triangles_reoriented,
       "triangles of the input were turned to agree with their component's orientation");
  if (report.folded_slivers_collapsed > 0)
    notes.push_back(absl::StrFormat(
        "%d sliver triangles of the input folded back over their neighbours (each turned by more "
        "than %g degrees against all three) lost their shortest edge, its ends merged: input "
        "points moved by at most %g",
        report.folded_slivers_collapsed, kFoldedFaceTurnDeg,
        report.longest_folded_edge_collapsed));
  if (report.sliver_steps_removed > 0)
    notes.push_back(absl::StrFormat(
        "%d sliver triangles of the input standing as a step on a seam (lower than %g of the size "
        "asked, the surfaces on its two sides continuing each other) were flipped or collapsed "
        "away: the surface moved by at most %g",
        report.sliver_steps_removed, kStepHeightOfSize, report.highest_sliver_step));
  note(report.short_ridges_dropped,
       "ridges of the input that end freely and are shorter than twice the size were not kept as "
       "lines");
  for (const std::string& stop : report.front_stops)
    notes.push_back(absl::StrCat(
        stop, "; the patch was re-triangulated from its own input triangles instead, split to the "
              "size"));
  if (report.wall_sizes_after_crossing > 0)
    notes.push_back(absl::StrFormat(
        "the surface re-triangulated at the size asked crossed itself across walls thinner than "
        "the size; it was made again with its triangles no longer than %g times a wall's thickness "
        "(wall_sizes), so they are smaller than the size asked on those walls",
        report.wall_sizes_after_crossing));
  if (report.input_crossing_pairs > 0) {
    const Point& c = report.first_input_crossing;
    notes.push_back(absl::StrFormat(
        "%d pairs of the input's triangles cross, the first near (%g, %g, %g): its %d components "
        "were re-triangulated each on its own, and the result crosses where they do",
        report.input_crossing_pairs, c[0], c[1], c[2], report.components));
  }
}

// Memory for a job with `input_triangles` in and `triangles` out (surface_step.h's figures).
double surface_bytes(std::size_t input_triangles, double triangles) {
  return kSurfaceBytesPerInputTriangle * static_cast<double>(input_triangles) +
         kSurfaceBytesPerTriangle * triangles;
}

}  // namespace

SurfaceQualityFigures surface_quality(const Mesh& surface) {
  SurfaceQualityFigures figures;
  if (surface.triangles.empty()) return figures;
  figures.min_angle_deg = 180.0;
  std::int64_t below_30 = 0;
  for (const Triangle& t : surface.triangles) {
    const Point& a = surface.points[t[0]];
    const Point& b = surface.points[t[1]];
    const Point& c = surface.points[t[2]];
    const std::array<double, 3> angles = {corner_angle_deg(a, b, c), corner_angle_deg(b, c, a),
                                          corner_angle_deg(c, a, b)};
    const double smallest = *std::min_element(angles.begin(), angles.end());
    figures.min_angle_deg = std::min(figures.min_angle_deg, smallest);
    figures.max_angle_deg =
        std::max(figures.max_angle_deg, *std::max_element(angles.begin(), angles.end()));
    below_30 += smallest < 30.0 ? 1 : 0;
    figures.count_below_15_deg += smallest < kThinTriangleDeg ? 1 : 0;
  }
  figures.share_below_30_deg =
      static_cast<double>(below_30) / static_cast<double>(surface.triangles.size());
  return figures;
}

absl::StatusOr<SurfaceEstimate> estimate_surface_mesh(const Mesh& input,
                                                      const SurfaceParams& params) {
  std::optional<SpecSizeField> field;
  if (params.spec) {
    Box domain = empty_box();
    for (const Point& p : input.points) enclose(domain, p);
    absl::StatusOr<SpecSizeField> made = SpecSizeField::create(*params.spec, domain);
    if (!made.ok()) return made.status();
    field.emplace(*std::move(made));
  }
  const double uniform_inverse_square = 1.0 / (params.size * params.size);
  const auto inverse_square = [&](const Point& x) {
    if (!field) return uniform_inverse_square;
    const double h = field->size_at(x);
    return 1.0 / (h * h);
  };
  const double equilateral = std::sqrt(3.0) / 4.0;
  double triangles = 0.0;
  for (const Triangle& t : input.triangles) {
    const Point& a = input.points[t[0]];
    const Point& b = input.points[t[1]];
    const Point& c = input.points[t[2]];
    const double area = 0.5 * norm(cross(sub(b, a), sub(c, a)));
    if (area == 0.0) continue;
    const Point centroid = scale(add(add(a, b), c), 1.0 / 3.0);
    const double mean_inverse_square =
        (inverse_square(a) + inverse_square(b) + inverse_square(c) + inverse_square(centroid)) /
        4.0;
    triangles += area * mean_inverse_square / equilateral;
  }
  return SurfaceEstimate{
      .triangles = triangles,
      .bytes = surface_bytes(input.triangles.size(), triangles)};
}

absl::StatusOr<SurfaceOutcome> run_surface_step(const SurfaceJob& job, const Mesh& input,
                                                SurfaceParams params, std::int64_t max_elements,
                                                JobContext& context,
                                                std::vector<std::string>& notes,
                                                std::vector<StageTiming>& timings) {
  if (!job) {
    return absl::UnimplementedError(
        "this server has no surface mesher (MeshSurface, remesh_surface): use a server built with "
        "it");
  }
  const Clock::time_point estimate_start = Clock::now();
  const absl::StatusOr<SurfaceEstimate> estimate =
      run_guarded("estimating the surface", [&] { return estimate_surface_mesh(input, params); });
  timings.push_back({"estimate", seconds_since(estimate_start)});
  if (!estimate.ok()) return estimate.status();
  if (absl::Status status = context.admit_estimate(
          estimate->triangles, "surface triangles", "the input's area and the sizes", "surface",
          estimate->bytes, max_elements);
      !status.ok()) {
    return status;
  }
  if (context.progress().cancelled()) {
    return absl::CancelledError("the call was stopped before meshing the surface");
  }
  params.max_triangles = max_elements;
  // The sizes attached to the surface can ask for many more triangles than the estimate above:
  // the job is admitted again, by the core's count, before its front runs.
  params.admit_expected = [&](double expected) {
    if (!(expected > estimate->triangles)) return absl::OkStatus();
    return context.admit_estimate(
        expected, "surface triangles",
        "the sizes attached to the surface: its curvature and the gaps between its lines",
        "surface", surface_bytes(input.triangles.size(), expected), max_elements);
  };
  absl::StatusOr<SurfaceResult> result = run_guarded(
      "meshing the surface", [&] { return job(input, params, context.progress()); });
  if (!result.ok()) return result.status();
  if (absl::Status whole = check_mesh_output(result->mesh); !whole.ok()) return whole;
  add_repair_notes(result->report, notes);
  SurfaceOutcome outcome{.result = *std::move(result),
                         .quality = {},
                         .estimated_triangles = estimate->triangles};
  outcome.quality = surface_quality(outcome.result.mesh);
  return outcome;
}

void fill_surface_summary(const SurfaceOutcome& outcome, v1::SurfaceSummary& summary) {
  const Mesh& mesh = outcome.result.mesh;
  summary.set_point_count(mesh.points.size());
  summary.set_triangle_count(mesh.triangles.size());

  v1::SurfaceQuality& quality = *summary.mutable_quality();
  quality.set_min_angle_deg(outcome.quality.min_angle_deg);
  quality.set_max_angle_deg(outcome.quality.max_angle_deg);
  quality.set_share_below_30_deg(outcome.quality.share_below_30_deg);
  quality.set_count_below_15_deg(static_cast<std::uint64_t>(outcome.quality.count_below_15_deg));
  quality.set_count_below_15_deg_at_thinner_input(
      static_cast<std::uint64_t>(outcome.result.report.thin_triangles_at_thinner_input));

  const SurfaceReport& report = outcome.result.report;
  const auto count = [](std::int64_t n) {
    return static_cast<std::uint64_t>(std::max<std::int64_t>(n, 0));
  };
  v1::SurfaceRepair& repair = *summary.mutable_repair();
  repair.set_duplicate_triangles_dropped(count(report.duplicate_triangles_dropped));
  repair.set_degenerate_triangles_dropped(count(report.degenerate_triangles_dropped));
  repair.set_unused_points_dropped(count(report.unused_points_dropped));
  repair.set_triangles_reoriented(count(report.triangles_reoriented));
  repair.set_components(count(report.components));
  repair.set_closed_components(count(report.closed_components));
  repair.set_folded_slivers_collapsed(count(report.folded_slivers_collapsed));
  repair.set_longest_folded_edge_collapsed(report.longest_folded_edge_collapsed);
  repair.set_sliver_steps_removed(count(report.sliver_steps_removed));
  repair.set_highest_sliver_step(report.highest_sliver_step);

  v1::SurfaceFeatures& features = *summary.mutable_features();
  features.set_patches(count(report.patches));
  features.set_lines(count(report.lines));
  features.set_corners(count(report.corners));
  features.set_short_ridges_dropped(count(report.short_ridges_dropped));
  features.set_patches_from_input(count(report.patches_from_input));

  v1::SurfaceDistance& distance = *summary.mutable_distance();
  distance.set_hausdorff(report.hausdorff);
  distance.set_max_vertex_distance(report.max_vertex_distance);
  distance.set_model_size(report.model_size);

  summary.set_estimated_triangle_count(outcome.estimated_triangles);
}

}  // namespace afmesh::server
