// afmesh-bench-volume: meshes one benchmark solid with the core advancing-front mesher on one
// thread and prints speed, peak memory, quality and validity; optionally writes the surface for
// the peer meshers (bench/peers.py) and the volume mesh.
//
//   afmesh-bench-volume --shape sphere --size 0.05 [--growth 1] [--surface PREFIX]
//                       [--out mesh.msh] [--no-optimise] [--no-validate] [--json]
//   afmesh-bench-volume --shape torus --size 0.08 --study [--steps default|LIST]...
//                       [--target DEG]... [--passes 4] [--max-ring 7]
//     LIST: comma-separated steps of edge,face,smooth,split,sweep (or none); every --steps is
//     run with every --target (default: the optimiser's defaults)
//     meshes without optimisation, then runs the optimiser apart (bench/optimise_study.h) and
//     prints the quality before and after, its time, and the classes of the tets left under
//     10 and 20 degrees.
//
// Run one measurement per process: the peak resident memory (VmHWM) is reset just before the
// mesher starts, and "bytes/tet" is (peak during meshing - resident before) / tets.
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <ctime>
#include <string>

#include "CLI/CLI.hpp"
#include "absl/status/status.h"
#include "absl/status/statusor.h"
#include "absl/strings/str_cat.h"
#include "absl/strings/str_format.h"
#include "bench/bench_shapes.h"
#include "bench/json_line.h"
#include "bench/optimise_study.h"
#include "bench/process_memory.h"
#include "bench/tetgen_files.h"
#include "core/common/progress.h"
#include "core/io/mesh_io.h"
#include "core/quality/measures.h"
#include "core/quality/validate.h"
#include "core/volume/generate_volume_mesh.h"

namespace afmesh::bench {
namespace {

struct Options {
  std::string shape;
  double size = 0.0;
  double growth = 1.0;
  bool optimise = true;
  std::string surface_prefix;  // writes PREFIX.stl/.mesh/.smesh/.poly when set
  std::string out_path;        // writes the volume mesh when set
  bool validate = true;
  bool json = false;
};

// One run of the core mesher: result or error, wall and CPU seconds, memory.
struct Run {
  absl::StatusOr<VolumeResult> result = absl::UnknownError("not run");
  double wall_seconds = 0.0;
  double cpu_seconds = 0.0;
  PeakMemoryProbe memory;
};

// What is measured on the finished mesh.
struct Assessment {
  QualitySummary quality;
  bool validated = false;
  bool valid = false;
  std::string validation_text;  // failed checks, one per line; empty when valid
};

double cpu_seconds_now() { return static_cast<double>(std::clock()) / CLOCKS_PER_SEC; }

// Writes the surface as PREFIX.stl (ascii: exact coordinates), PREFIX.mesh (Medit, exact),
// PREFIX.smesh and PREFIX.poly (tetgen).
absl::Status write_surface_files(const Mesh& surface, const std::string& prefix) {
  if (absl::Status s = write_mesh(surface, prefix + ".stl", WriteOptions{.binary_stl = false});
      !s.ok())
    return s;
  if (absl::Status s = write_mesh(surface, prefix + ".mesh"); !s.ok()) return s;
  if (absl::Status s = write_tetgen_smesh(surface, prefix + ".smesh"); !s.ok()) return s;
  return write_tetgen_poly(surface, prefix + ".poly");
}

// Runs generate_volume_mesh once, on this thread, timing it and tracking its peak memory.
void run_core_mesher(const Mesh& surface, const VolumeParams& params, Run& run) {
  run.memory.start();
  const double cpu_start = cpu_seconds_now();
  const auto wall_start = std::chrono::steady_clock::now();
  run.result = generate_volume_mesh(surface, params, no_progress());
  run.wall_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
  run.cpu_seconds = cpu_seconds_now() - cpu_start;
  run.memory.finish();
}

absl::StatusOr<Assessment> assess(const Mesh& mesh, const Mesh& surface, bool validate) {
  Assessment a;
  absl::StatusOr<QualitySummary> quality = summarize_quality(mesh);
  if (!quality.ok()) return quality.status();
  a.quality = *std::move(quality);
  if (!validate) return a;
  const ValidationReport report = validate_volume_mesh(mesh, &surface);
  a.validated = true;
  a.valid = report.valid();
  for (const Check& c : report.checks)
    if (!c.passed()) absl::StrAppend(&a.validation_text, c.name, ": ", c.summary, "\n");
  return a;
}

std::string stage_list(const std::vector<StageTiming>& timings, bool as_json) {
  std::string out;
  for (const StageTiming& t : timings) {
    if (as_json) {
      absl::StrAppend(&out, out.empty() ? "" : ", ", json_string(t.stage), ": ",
                      absl::StrFormat("%.6f", t.seconds));
    } else {
      absl::StrAppend(&out, out.empty() ? "" : ", ", t.stage, absl::StrFormat(" %.3f s", t.seconds));
    }
  }
  return as_json ? "{" + out + "}" : out;
}

double mib(std::int64_t bytes) { return static_cast<double>(bytes) / (1024.0 * 1024.0); }

void print_readable(const Options& o, const Mesh& surface, const Run& run,
                    const Assessment* a) {
  std::printf("afmesh-bench-volume: %s, h = %g, growth %g%s\n",
              bench_shape_description(o.shape).c_str(), o.size, o.growth,
              o.optimise ? "" : ", no optimisation");
  std::printf("  surface       %zu points, %zu triangles\n", surface.points.size(),
              surface.triangles.size());
  if (!run.result.ok()) {
    std::printf("  FAILED        %s\n", run.result.status().ToString().c_str());
    return;
  }
  const Mesh& mesh = run.result->mesh;
  const double tets = static_cast<double>(mesh.tets.size());
  std::printf("  volume mesh   %zu tets, %zu points\n", mesh.tets.size(), mesh.points.size());
  std::printf("  time          %.3f s wall, %.3f s cpu (one thread): %.0f tets/s\n",
              run.wall_seconds, run.cpu_seconds, tets / run.wall_seconds);
  std::printf("  stages        %s\n", stage_list(run.result->timings, false).c_str());
  if (run.memory.ok()) {
    std::printf("  memory        RSS before %.1f MiB, peak while meshing %.1f MiB: +%.1f MiB = "
                "%.0f bytes/tet%s\n",
                mib(run.memory.start_bytes()), mib(run.memory.peak_bytes()),
                mib(run.memory.growth_bytes()),
                static_cast<double>(run.memory.growth_bytes()) / tets,
                run.memory.peak_was_reset() ? "" : " (VmHWM not reset: upper bound)");
  } else {
    std::printf("  memory        unavailable: %s\n", run.memory.status().ToString().c_str());
  }
  if (a == nullptr) return;
  const QualitySummary& q = a->quality;
  std::printf("  quality       min dihedral %.2f deg, <10 deg %.3f%%, <20 deg %.3f%%, radius ratio "
              "min %.4f mean %.4f\n",
              q.tet_min_dihedral_deg.min, 100.0 * q.share_min_dihedral_below_10,
              100.0 * q.share_min_dihedral_below_20, q.tet_radius_ratio.min,
              q.tet_radius_ratio.mean);
  if (!a->validated)
    std::printf("  validity      not checked (--no-validate)\n");
  else if (a->valid)
    std::printf("  validity      valid (validate_volume_mesh against the input surface)\n");
  else
    std::printf("  validity      INVALID:\n%s", a->validation_text.c_str());
}

void print_json(const Options& o, const Mesh& surface, const Run& run, const Assessment* a) {
  JsonLine j;
  j.add("tool", "afmesh").add("shape", o.shape).add("size", o.size).add("growth", o.growth);
  j.add("optimise", o.optimise);
  j.add("surface_points", static_cast<std::int64_t>(surface.points.size()));
  j.add("surface_triangles", static_cast<std::int64_t>(surface.triangles.size()));
  if (!run.result.ok()) {
    j.add("error", run.result.status().ToString());
    std::printf("%s\n", j.str().c_str());
    return;
  }
  const Mesh& mesh = run.result->mesh;
  const auto tets = static_cast<std::int64_t>(mesh.tets.size());
  j.add("tets", tets).add("points", static_cast<std::int64_t>(mesh.points.size()));
  j.add("seconds", run.wall_seconds).add("cpu_seconds", run.cpu_seconds);
  j.add_raw("stages", stage_list(run.result->timings, true));
  if (run.memory.ok()) {
    j.add("rss_before_bytes", run.memory.start_bytes());
    j.add("rss_peak_bytes", run.memory.peak_bytes());
    j.add("bytes_per_tet", static_cast<double>(run.memory.growth_bytes()) / tets);
    j.add("peak_reset", run.memory.peak_was_reset());
  }
  if (a != nullptr) {
    const QualitySummary& q = a->quality;
    j.add("min_dihedral", q.tet_min_dihedral_deg.min);
    j.add("share_below_10", q.share_min_dihedral_below_10);
    j.add("share_below_20", q.share_min_dihedral_below_20);
    j.add("min_radius_ratio", q.tet_radius_ratio.min);
    j.add("mean_radius_ratio", q.tet_radius_ratio.mean);
    if (a->validated) j.add("valid", a->valid).add("validation", a->validation_text);
  }
  std::printf("%s\n", j.str().c_str());
}

int run_benchmark(const Options& o) {
  absl::StatusOr<Mesh> surface = bench_surface(o.shape, o.size);
  if (!surface.ok()) {
    std::fprintf(stderr, "afmesh-bench-volume: %s\n", surface.status().ToString().c_str());
    return 2;
  }
  if (!o.surface_prefix.empty()) {
    if (absl::Status s = write_surface_files(*surface, o.surface_prefix); !s.ok()) {
      std::fprintf(stderr, "afmesh-bench-volume: %s\n", s.ToString().c_str());
      return 2;
    }
  }
  Run run;
  VolumeParams params;
  params.size = o.size;
  params.growth = o.growth;
  params.optimise = o.optimise;
  run_core_mesher(*surface, params, run);
  absl::StatusOr<Assessment> assessment = absl::UnknownError("mesher failed");
  if (run.result.ok()) assessment = assess(run.result->mesh, *surface, o.validate);
  const Assessment* a = assessment.ok() ? &*assessment : nullptr;
  if (o.json)
    print_json(o, *surface, run, a);
  else
    print_readable(o, *surface, run, a);
  if (!run.result.ok()) return 1;
  if (!assessment.ok()) {
    std::fprintf(stderr, "afmesh-bench-volume: %s\n", assessment.status().ToString().c_str());
    return 1;
  }
  if (!o.out_path.empty()) {
    if (absl::Status s = write_mesh(run.result->mesh, o.out_path); !s.ok()) {
      std::fprintf(stderr, "afmesh-bench-volume: %s\n", s.ToString().c_str());
      return 2;
    }
  }
  return a->validated && !a->valid ? 1 : 0;
}

}  // namespace
}  // namespace afmesh::bench

int main(int argc, char** argv) {
  using afmesh::bench::StudyOptions;
  afmesh::bench::Options o;
  CLI::App app{"Benchmark of the core volume mesher on one solid (one thread)."};
  app.add_option("--shape", o.shape, "sphere | torus | box | lblock")->required();
  app.add_option("--size", o.size, "target edge length h")->required();
  app.add_option("--growth", o.growth, "growth factor (>= 1)");
  app.add_option("--surface", o.surface_prefix,
                 "write the surface as PREFIX.stl (ascii), .mesh, .smesh and .poly for the peers");
  app.add_option("--out", o.out_path, "write the volume mesh (format by extension)");
  bool no_optimise = false, no_validate = false, study = false;
  std::vector<std::string> steps_list;
  std::vector<double> targets;
  int passes = afmesh::OptimiseParams{}.passes;
  int max_ring = afmesh::OptimiseParams{}.max_edge_ring;
  StudyOptions so;
  app.add_flag("--study", study, "measure the optimiser apart, before and after (see above)");
  app.add_option("--steps", steps_list,
                 "with --study: optimisation steps, default or of edge,face,smooth,split,sweep "
                 "(repeatable)");
  app.add_option("--target", targets, "with --study: target min dihedral angle, degrees (repeatable)");
  app.add_option("--passes", passes, "with --study: rounds over the bad tets");
  app.add_option("--max-ring", max_ring, "with --study: largest ring of an edge removal or split");
  app.add_flag("--no-optimise", no_optimise, "skip the optimisation step after the front closes");
  app.add_flag("--no-validate", no_validate, "skip validate_volume_mesh");
  app.add_flag("--json", o.json, "print one JSON object instead of the readable report");
  CLI11_PARSE(app, argc, argv);
  o.optimise = !no_optimise;
  o.validate = !no_validate;
  if (!study) return afmesh::bench::run_benchmark(o);
  if (steps_list.empty()) steps_list.push_back("default");
  if (targets.empty()) targets.push_back(afmesh::OptimiseParams{}.target_min_dihedral_deg);
  for (const std::string& steps : steps_list) {
    for (double target : targets) {
      afmesh::bench::StudyVariant v;
      v.params.target_min_dihedral_deg = target;
      v.params.passes = passes;
      v.params.max_edge_ring = max_ring;
      if (const std::string error = afmesh::bench::set_optimise_steps(steps, v.params);
          !error.empty()) {
        std::fprintf(stderr, "afmesh-bench-volume: %s\n", error.c_str());
        return 2;
      }
      v.label = absl::StrCat(steps, " @ ", target, " deg");
      so.variants.push_back(v);
    }
  }
  absl::StatusOr<afmesh::Mesh> surface = afmesh::bench::bench_surface(o.shape, o.size);
  if (!surface.ok()) {
    std::fprintf(stderr, "afmesh-bench-volume: %s\n", surface.status().ToString().c_str());
    return 2;
  }
  so.size = o.size;
  so.growth = o.growth;
  so.json = o.json;
  return afmesh::bench::run_optimise_study(o.shape, *surface, so);
}
