// afmesh-bench-surface: the core surface mesher (MeshSurface, paper §3) on one surface file, one
// thread: output triangles per second, peak memory, the size and quality of what it made, and its
// distance to the input. bench/surface/ runs the peers (CGAL, gmsh, netgen) side by side.
//
//   afmesh-bench-surface --input FILE --size H [--ridge-angle DEG] [--curvature-angle DEG]
//                        [--out FILE] [--json]
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <string>
#include <vector>

#include "CLI/CLI.hpp"
#include "absl/strings/str_cat.h"
#include "absl/strings/str_format.h"
#include "bench/json_line.h"
#include "bench/process_memory.h"
#include "core/geometry/vec.h"
#include "core/io/mesh_io.h"
#include "core/quality/measures.h"
#include "core/quality/mesh_topology.h"
#include "core/quality/validate.h"
#include "core/surface/generate_surface_mesh.h"

namespace afmesh::bench {
namespace {

// params as the options set them; a size of 0 is the input's mean edge.
int run(const std::string& input, SurfaceParams params, const std::string& out, bool json) {
  absl::StatusOr<Mesh> surface = read_mesh(input);
  if (!surface.ok()) {
    std::fprintf(stderr, "afmesh-bench-surface: %s\n", surface.status().ToString().c_str());
    return 3;
  }
  if (!(params.size > 0)) params.size = mean_edge_length(*surface);
  PeakMemoryProbe memory;
  memory.start();
  const auto start = std::chrono::steady_clock::now();
  absl::StatusOr<SurfaceResult> result = generate_surface_mesh(*surface, params);
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  memory.finish();
  if (!result.ok()) {
    std::printf("%s: size %g: %s (%.2f s)\n", input.c_str(), params.size,
                result.status().ToString().c_str(), seconds);
    return 6;
  }
  const Mesh& m = result->mesh;
  double min_angle = 180, edges = 0;
  std::int64_t at_least_30 = 0, under_15 = 0;
  for (const Triangle& t : m.triangles) {
    const double a = triangle_quality(m.points, t).min_angle_deg;
    min_angle = std::min(min_angle, a);
    at_least_30 += a >= 30.0;
    under_15 += a < kThinTriangleDeg;
    for (int k = 0; k < 3; ++k) edges += norm(sub(m.points[t[(k + 1) % 3]], m.points[t[k]]));
  }
  const auto n = static_cast<double>(m.triangles.size());
  // An assembly whose components cross (the report counts the input's crossing pairs) is
  // re-triangulated component by component, and the output crosses where the input does: the
  // output's edge-connected components are its environments then, so that only a crossing
  // within one component fails no_self_intersections.
  const SurfaceReport& r = result->report;
  const auto validate_by_component = [&](const Mesh& mesh) {
    ValidationParams validation_params;
    std::vector<std::int32_t> components;
    if (r.input_crossing_pairs > 0) {
      components = component_environments(mesh.triangles);
      validation_params.face_environments = components;
    }
    return validate_surface(mesh, validation_params);
  };
  const ValidationReport validation = validate_by_component(m);
  // The output is as good as its input allows when it fails no check the input passes (issue 11:
  // closed and manifold wherever the input was): an open input gives an open output, and holes
  // that touch at a vertex stay non-manifold vertices (libcgal-demo's elephant-with-holes). The
  // input is checked after the timing, with the same environments rule for an assembly.
  // "closed" is no fault either way (the volume check it gates is the caller's).
  const ValidationReport input_validation = validate_by_component(*surface);
  std::string failed, failed_by_input;
  for (const Check& check : input_validation.checks)
    if (check.outcome == CheckOutcome::kFailed)
      absl::StrAppend(&failed_by_input, failed_by_input.empty() ? "" : ",", check.name);
  bool valid = true;
  for (const Check& check : validation.checks) {
    if (check.outcome != CheckOutcome::kFailed) continue;
    absl::StrAppend(&failed, failed.empty() ? "" : ",", check.name);
    const bool input_fails_it = std::any_of(
        input_validation.checks.begin(), input_validation.checks.end(), [&](const Check& c) {
          return c.name == check.name && c.outcome == CheckOutcome::kFailed;
        });
    valid = valid && (check.name == "closed" || input_fails_it);
  }
  if (!out.empty()) {
    if (absl::Status st = write_mesh(m, out); !st.ok())
      std::fprintf(stderr, "afmesh-bench-surface: %s\n", st.ToString().c_str());
  }
  // The core's own stage times (generate_surface_mesh's StageClock laps), in order.
  std::string stages_json, stages_text;
  for (const StageTiming& t : result->timings) {
    absl::StrAppend(&stages_json, stages_json.empty() ? "" : ", ", json_string(t.stage), ": ",
                    absl::StrFormat("%.4f", t.seconds));
    absl::StrAppend(&stages_text, stages_text.empty() ? "" : " ",
                    absl::StrFormat("%s %.3f", t.stage, t.seconds));
  }
  if (json) {
    JsonLine j;
    j.add("input", input).add("size", params.size).add("triangles", static_cast<std::int64_t>(n))
        .add("seconds", seconds).add("triangles_per_second", n / seconds)
        .add("peak_bytes_per_triangle", memory.growth_bytes() / n)
        .add("min_angle", min_angle).add("share_at_least_30", at_least_30 / n)
        .add("under_15", under_15)
        .add("under_15_at_thinner_input", r.thin_triangles_at_thinner_input)
        .add("mean_edge_over_h", edges / (3 * n) / params.size)
        .add("hausdorff_over_diagonal", r.hausdorff / r.model_size)
        .add("patches", r.patches).add("lines", r.lines).add("corners", r.corners)
        .add("short_ridges_dropped", r.short_ridges_dropped)
        .add("folded_slivers_collapsed", r.folded_slivers_collapsed)
        .add("sliver_steps_removed", r.sliver_steps_removed)
        .add("highest_sliver_step", r.highest_sliver_step)
        .add("patches_from_input", r.patches_from_input)
        .add("valid", valid).add("failed_checks", failed)
        .add("failed_checks_of_input", failed_by_input)
        .add_raw("stage_seconds", "{" + stages_json + "}");
    std::printf("%s\n", j.str().c_str());
  } else {
    std::printf(
        "%s: size %g: %.0f triangles in %.3f s (%.0f/s), %.0f bytes/triangle peak; min angle "
        "%.2f, >= 30: %.2f%%, < 15: %lld (%lld at input triangles or corners as thin); mean "
        "edge / h %.3f; Hausdorff %.2e of the diagonal; %lld patches (%lld from their input), "
        "%lld lines, %lld corners (%lld short free ridges dropped); dropped %lld degenerate, %lld "
        "duplicate, reoriented %lld, %lld folded slivers collapsed, %lld sliver step faces removed; %s\n  stages (s): %s\n",
        input.c_str(), params.size, n, seconds, n / seconds,
        static_cast<double>(memory.growth_bytes()) / n, min_angle, 100.0 * at_least_30 / n,
        static_cast<long long>(under_15),
        static_cast<long long>(r.thin_triangles_at_thinner_input), edges / (3 * n) / params.size,
        r.hausdorff / r.model_size, static_cast<long long>(r.patches),
        static_cast<long long>(r.patches_from_input), static_cast<long long>(r.lines),
        static_cast<long long>(r.corners),
        static_cast<long long>(r.short_ridges_dropped),
        static_cast<long long>(r.degenerate_triangles_dropped),
        static_cast<long long>(r.duplicate_triangles_dropped),
        static_cast<long long>(r.triangles_reoriented),
        static_cast<long long>(r.folded_slivers_collapsed),
        static_cast<long long>(r.sliver_steps_removed),
        valid ? (failed.empty() ? "valid" : "valid, open") : ("INVALID: " + failed).c_str(),
        stages_text.c_str());
  }
  return valid ? 0 : 4;
}

}  // namespace
}  // namespace afmesh::bench

int main(int argc, char** argv) {
  CLI::App app{"The core surface mesher on one surface (one thread)"};
  std::string input, out;
  afmesh::SurfaceParams params;
  params.size = 0;
  bool json = false;
  app.add_option("--input", input, "surface file (.stl, .obj, .off, .mesh, .msh)")->required();
  app.add_option("--size", params.size, "target edge length h (default: the input's mean edge)");
  app.add_option("--ridge-angle", params.ridge_angle_deg, "ridge angle, degrees");
  app.add_option("--curvature-angle", params.curvature_angle_deg,
                 "largest turn of an element where the input curves, degrees (0: off)");
  app.add_option("--curvature-deviation", params.curvature_deviation,
                 "largest distance of an element from the input where it curves, as a fraction "
                 "of the bounding-box diagonal (0: off)");
  app.add_option("--wall-sizes", params.wall_sizes,
                 "elements at most this many times the thickness of the solid's walls (0: off)");
  app.add_flag("--every-patch-from-input", params.every_patch_from_input,
               "re-triangulate every patch from its input triangles, without the front");
  app.add_option("--out", out, "write the surface (format by extension)");
  app.add_flag("--json", json, "one JSON object");
  CLI11_PARSE(app, argc, argv);
  return afmesh::bench::run(input, params, out, json);
}
