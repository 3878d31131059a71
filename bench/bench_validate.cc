// afmesh-bench-validate: the cost of the server's "quality+validation" stage on a finished
// volume mesh, each half alone: validate_volume_mesh against the input front and
// summarize_quality.
//
//   afmesh-bench-validate MESH [--repeat 3] [--skip-quality] [--json]
//       MESH is a volume mesh as `afmesh volume` writes it (points: the front's first; triangles:
//       the input front). The boundary handed to the validator is those triangles over the
//       leading points they use, as the server hands it the front, so points match by index.
//       Prints the best wall and thread-CPU seconds of `repeat` runs of each. --skip-quality runs
//       the validator only (for a profile of it alone).
#include <time.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <limits>
#include <string>

#include "CLI/CLI.hpp"
#include "bench/json_line.h"
#include "core/io/mesh_io.h"
#include "core/quality/measures.h"
#include "core/quality/validate.h"

namespace afmesh::bench {
namespace {

double thread_cpu_seconds() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

struct Best {
  double wall = std::numeric_limits<double>::infinity();
  double cpu = std::numeric_limits<double>::infinity();
};

// Runs `work` `repeat` times and keeps the smallest wall and CPU times.
template <typename Work>
Best best_of(int repeat, Work work) {
  Best best;
  for (int i = 0; i < repeat; ++i) {
    const auto wall_start = std::chrono::steady_clock::now();
    const double cpu_start = thread_cpu_seconds();
    work();
    best.cpu = std::min(best.cpu, thread_cpu_seconds() - cpu_start);
    best.wall = std::min(
        best.wall,
        std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count());
  }
  return best;
}

// The input front of a mesh written by `afmesh volume`: its triangles over the leading points.
Mesh front_of(const Mesh& mesh) {
  Mesh front;
  Index used = 0;
  for (const Triangle& t : mesh.triangles) {
    for (Index v : t) used = std::max(used, v + 1);
  }
  front.points.assign(mesh.points.begin(), mesh.points.begin() + used);
  front.triangles = mesh.triangles;
  front.triangle_tags = mesh.triangle_tags;
  return front;
}

int run(const std::string& path, int repeat, bool skip_quality, bool json) {
  absl::StatusOr<Mesh> mesh = read_mesh(path);
  if (!mesh.ok()) {
    std::fprintf(stderr, "afmesh-bench-validate: %s\n", mesh.status().ToString().c_str());
    return 1;
  }
  const Mesh front = front_of(*mesh);
  bool valid = false;
  const Best validation = best_of(repeat, [&] {
    valid = validate_volume_mesh(*mesh, &front).valid();
  });
  double min_dihedral = 0.0;
  const Best quality = best_of(skip_quality ? 0 : repeat, [&] {
    min_dihedral = summarize_quality(*mesh)->tet_min_dihedral_deg.min;
  });
  if (json) {
    JsonLine j;
    j.add("points", static_cast<std::int64_t>(mesh->points.size()))
        .add("tets", static_cast<std::int64_t>(mesh->tets.size()))
        .add("valid", valid)
        .add("validate_seconds", validation.wall)
        .add("validate_cpu_seconds", validation.cpu)
        .add("quality_seconds", quality.wall)
        .add("quality_cpu_seconds", quality.cpu)
        .add("min_dihedral_deg", min_dihedral);
    std::printf("%s\n", j.str().c_str());
    return valid ? 0 : 2;
  }
  std::printf("%s: %zu points, %zu tets, %zu front triangles (best of %d)\n", path.c_str(),
              mesh->points.size(), mesh->tets.size(), front.triangles.size(), repeat);
  std::printf("  validate_volume_mesh  %.3f s wall  %.3f s cpu  (%s)\n", validation.wall,
              validation.cpu, valid ? "valid" : "INVALID");
  std::printf("  summarize_quality     %.3f s wall  %.3f s cpu  (min dihedral %.4f deg)\n",
              quality.wall, quality.cpu, min_dihedral);
  return valid ? 0 : 2;
}

}  // namespace
}  // namespace afmesh::bench

int main(int argc, char** argv) {
  CLI::App app{"Time validate_volume_mesh and summarize_quality on a finished volume mesh"};
  std::string path;
  int repeat = 3;
  bool skip_quality = false;
  bool json = false;
  app.add_option("mesh", path, "volume mesh written by `afmesh volume`")->required();
  app.add_option("--repeat", repeat, "runs of each; the best is printed")->check(CLI::PositiveNumber);
  app.add_flag("--skip-quality", skip_quality, "run the validator only");
  app.add_flag("--json", json, "one JSON line");
  CLI11_PARSE(app, argc, argv);
  return afmesh::bench::run(path, repeat, skip_quality, json);
}
