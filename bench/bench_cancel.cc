// afmesh-bench-cancel: how long the server's MeshVolume job (server/default_volume_job.h: the
// front, compaction, optimisation, then quality and validation) or its MeshSurface job
// (generate_surface_mesh: input, surface, features, curvature, lines, front, flips, smoothing, distance)
// runs on after its call is cancelled, stage by stage (issue 12: a cancelled call frees its
// worker within 100 ms).
//
//   afmesh-bench-cancel --shape lblock --size 0.02 [--trials 8] [--seed 1] [--stage S] [--json]
//   afmesh-bench-cancel --input front.stl --size H ...
//   afmesh-bench-cancel --surface --input surface.stl --size H ...   (the surface job)
//
// A first run without cancelling gives each stage's interval (the job's own timings). Then
// every stage longer than 20 ms gets `trials` runs cancelled at a time drawn uniformly from the
// middle 90% of its interval: the Progress the job sees turns cancelled() true at that time.
// The latency is from that time to the job's return, its memory freed: the time a worker stays
// taken after the server's OnCancel has set the flag (an atomic; the gRPC side adds nothing
// measurable). Per stage: p50, p99 (the maximum for fewer than 100 trials) and max, in ms, and
// the largest "unwind": from the job's first look that saw the cancel to its return. Run it on
// an otherwise idle machine: wall times on a shared core stretch with its load.
#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <functional>
#include <optional>
#include <random>
#include <string>
#include <vector>

#include "CLI/CLI.hpp"
#include "absl/strings/str_format.h"
#include "bench/bench_shapes.h"
#include "bench/json_line.h"
#include "core/common/progress.h"
#include "core/io/mesh_io.h"
#include "core/surface/generate_surface_mesh.h"
#include "server/default_volume_job.h"

namespace afmesh::bench {
namespace {

using Clock = std::chrono::steady_clock;

double seconds_between(Clock::time_point a, Clock::time_point b) {
  return std::chrono::duration<double>(b - a).count();
}

// cancelled() turns true at `cancel_at` (never when unset); records when the job first saw it.
// Called from the job's threads (the quality summary runs on a second one).
class TimedCancel final : public Progress {
 public:
  explicit TimedCancel(std::optional<Clock::time_point> cancel_at) : cancel_at_(cancel_at) {}
  bool cancelled() const override {
    if (!cancel_at_) return false;
    const Clock::time_point now = Clock::now();
    if (now < *cancel_at_) return false;
    Clock::rep expected = 0;
    seen_at_.compare_exchange_strong(expected, now.time_since_epoch().count());
    return true;
  }
  // When cancelled() first returned true (the epoch when it never did).
  Clock::time_point seen_at() const { return Clock::time_point(Clock::duration(seen_at_.load())); }

 private:
  std::optional<Clock::time_point> cancel_at_;
  mutable std::atomic<Clock::rep> seen_at_{0};
};

// One stage of the uncancelled run: [begin, end) seconds from the job's start.
struct StageInterval {
  std::string name;
  double begin = 0.0;
  double end = 0.0;
};

// The stages of a job in order, from its timings.
std::vector<StageInterval> stage_intervals(const std::vector<StageTiming>& timings) {
  std::vector<StageInterval> stages;
  double t = 0.0;
  for (const StageTiming& timing : timings) {
    stages.push_back({timing.stage, t, t + timing.seconds});
    t += timing.seconds;
  }
  return stages;
}

// What a job run gives the bench: its stage timings and its element count (tets or triangles).
struct JobRun {
  std::vector<StageTiming> timings;
  std::size_t elements = 0;
};
// Runs the job once with `progress`; its output is freed before it returns.
using Job = std::function<absl::StatusOr<JobRun>(Progress& progress)>;

Job volume_job(const Mesh& front, double size) {
  return [&front, size](Progress& progress) -> absl::StatusOr<JobRun> {
    VolumeParams params;
    params.size = size;
    absl::StatusOr<server::VolumeJobOutput> output =
        server::run_volume_job(front, params, progress);
    if (!output.ok()) return output.status();
    return JobRun{output->volume.timings, output->volume.mesh.tets.size()};
  };
}

Job surface_job(const Mesh& input, double size) {
  return [&input, size](Progress& progress) -> absl::StatusOr<JobRun> {
    SurfaceParams params;
    params.size = size;
    absl::StatusOr<SurfaceResult> output = generate_surface_mesh(input, params, progress);
    if (!output.ok()) return output.status();
    return JobRun{output->timings, output->mesh.triangles.size()};
  };
}

double percentile(std::vector<double> values, double p) {
  std::sort(values.begin(), values.end());
  const std::size_t i = std::min(values.size() - 1, static_cast<std::size_t>(p * values.size()));
  return values[i];
}

int run(const Job& job, const char* what, std::size_t input_triangles, double size, int trials,
        unsigned seed, const std::string& only, bool json) {
  TimedCancel never(std::nullopt);
  const Clock::time_point start = Clock::now();
  const absl::StatusOr<JobRun> reference = job(never);
  const double total = seconds_between(start, Clock::now());
  if (!reference.ok()) {
    std::fprintf(stderr, "afmesh-bench-cancel: %s\n", reference.status().ToString().c_str());
    return 1;
  }
  const std::size_t elements = reference->elements;
  const std::vector<StageInterval> stages = stage_intervals(reference->timings);
  if (!json) {
    std::printf("%zu input triangles, size %g: %zu %s in %.2f s; stages:", input_triangles, size,
                elements, what, total);
    for (const StageInterval& s : stages)
      std::printf(" %s %.3f s", s.name.c_str(), s.end - s.begin);
    std::printf("\n%-20s %6s %9s %9s %9s %10s\n", "stage", "trials", "p50 ms", "p99 ms", "max ms",
                "unwind ms");
  }
  std::mt19937 random(seed);
  int failures = 0;
  for (const StageInterval& stage : stages) {
    if (stage.end - stage.begin < 0.02 || (!only.empty() && stage.name != only)) continue;
    std::uniform_real_distribution<double> when(stage.begin + 0.05 * (stage.end - stage.begin),
                                                stage.end - 0.05 * (stage.end - stage.begin));
    std::vector<double> latencies_ms, unwind_ms;
    for (int trial = 0; trial < trials; ++trial) {
      const double at = when(random);
      const Clock::time_point job_start = Clock::now();
      const Clock::time_point cancel_at = job_start + std::chrono::duration_cast<Clock::duration>(
                                                          std::chrono::duration<double>(at));
      TimedCancel progress(cancel_at);
      (void)job(progress);  // its output freed inside
      const Clock::time_point returned = Clock::now();
      // A run slower than the reference may end before `at`: that trial measures nothing.
      if (returned < cancel_at) continue;
      latencies_ms.push_back(1e3 * seconds_between(cancel_at, returned));
      unwind_ms.push_back(1e3 * seconds_between(std::max(cancel_at, progress.seen_at()), returned));
    }
    if (latencies_ms.empty()) continue;
    const double p50 = percentile(latencies_ms, 0.5), p99 = percentile(latencies_ms, 0.99),
                 max = *std::max_element(latencies_ms.begin(), latencies_ms.end());
    if (p99 > 100.0) ++failures;
    if (json) {
      JsonLine j;
      j.add("stage", stage.name)
          .add("trials", static_cast<std::int64_t>(latencies_ms.size()))
          .add("p50_ms", p50)
          .add("p99_ms", p99)
          .add("max_ms", max)
          .add("max_unwind_ms", *std::max_element(unwind_ms.begin(), unwind_ms.end()))
          .add(what, static_cast<std::int64_t>(elements));
      std::printf("%s\n", j.str().c_str());
    } else {
      std::printf("%-20s %6zu %9.1f %9.1f %9.1f %10.1f\n", stage.name.c_str(), latencies_ms.size(),
                  p50, p99, max, *std::max_element(unwind_ms.begin(), unwind_ms.end()));
    }
    std::fflush(stdout);
  }
  if (!json) std::printf("stages over the 100 ms goal at p99: %d\n", failures);
  return 0;
}

}  // namespace
}  // namespace afmesh::bench

int main(int argc, char** argv) {
  CLI::App app{"Cancellation latency of the MeshVolume or MeshSurface job, stage by stage"};
  std::string shape = "lblock", input;
  double size = 0.035;
  int trials = 8;
  unsigned seed = 1;
  bool json = false, surface = false;
  std::string only;
  app.add_option("--stage", only, "cancel in this stage only (e.g. front)");
  app.add_option("--shape", shape, "benchmark solid (bench/bench_shapes.h)");
  app.add_option("--input", input, "a closed front from a file instead of --shape");
  app.add_option("--size", size, "element size")->check(CLI::PositiveNumber);
  app.add_option("--trials", trials, "cancelled runs per stage")->check(CLI::PositiveNumber);
  app.add_option("--seed", seed, "seed of the cancellation times");
  app.add_flag("--json", json, "one JSON line per stage");
  app.add_flag("--surface", surface, "the MeshSurface job on the input surface");
  CLI11_PARSE(app, argc, argv);
  absl::StatusOr<afmesh::Mesh> front =
      input.empty() ? afmesh::bench::bench_surface(shape, size) : afmesh::read_mesh(input);
  if (!front.ok()) {
    std::fprintf(stderr, "afmesh-bench-cancel: %s\n", front.status().ToString().c_str());
    return 1;
  }
  const afmesh::bench::Job job = surface ? afmesh::bench::surface_job(*front, size)
                                         : afmesh::bench::volume_job(*front, size);
  return afmesh::bench::run(job, surface ? "triangles" : "tets", front->triangles.size(), size,
                            trials, seed, only, json);
}
