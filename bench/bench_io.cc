// afmesh-bench-io: time to convert a large closed surface from binary STL to Gmsh MSH 4.1 with
// core/io (read_mesh + write_mesh), and the peak memory of doing so.
//
//   afmesh-bench-io [--size 0.00469] [--dir DIR] [--json]
//       builds a sphere surface (about 1M triangles at the default size), writes DIR/io_sphere.stl
//       as binary STL, then converts it to DIR/io_sphere.msh in a fresh process (this program
//       re-run with --convert) so that the process's peak resident memory covers the conversion
//       only.
//   afmesh-bench-io --convert IN.stl OUT.msh [--json]
//       the conversion alone.
#include <spawn.h>
#include <sys/wait.h>

#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

#include "CLI/CLI.hpp"
#include "absl/status/status.h"
#include "absl/strings/str_cat.h"
#include "bench/json_line.h"
#include "bench/process_memory.h"
#include "core/io/mesh_io.h"
#include "core/shapes/shapes.h"

extern char** environ;

namespace afmesh::bench {
namespace {

// Default size: the icosahedral sphere then has 20 * 224^2 = 1,003,520 triangles.
constexpr double kDefaultSize = 0.00469;

class Stopwatch {
 public:
  double seconds() const {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  }

 private:
  std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();
};

double mib(std::int64_t bytes) { return static_cast<double>(bytes) / (1024.0 * 1024.0); }

std::int64_t file_bytes(const std::string& path) {
  std::error_code error;
  const auto size = std::filesystem::file_size(path, error);
  return error ? -1 : static_cast<std::int64_t>(size);
}

struct Conversion {
  std::int64_t points = 0;
  std::int64_t triangles = 0;
  double read_seconds = 0.0;
  double write_seconds = 0.0;
  PeakMemoryProbe memory;
};

void print_conversion(const std::string& in, const std::string& out, const Conversion& c,
                      bool json) {
  const double total = c.read_seconds + c.write_seconds;
  if (json) {
    JsonLine j;
    j.add("tool", "afmesh").add("points", c.points).add("triangles", c.triangles);
    j.add("read_seconds", c.read_seconds).add("write_seconds", c.write_seconds);
    j.add("seconds", total).add("stl_bytes", file_bytes(in)).add("msh_bytes", file_bytes(out));
    if (c.memory.ok()) {
      j.add("rss_before_bytes", c.memory.start_bytes()).add("rss_peak_bytes", c.memory.peak_bytes());
      j.add("bytes_per_triangle", static_cast<double>(c.memory.growth_bytes()) / c.triangles);
    }
    std::printf("%s\n", j.str().c_str());
    return;
  }
  std::printf("afmesh-bench-io: %s -> %s (core/io read_mesh + write_mesh, fresh process)\n",
              in.c_str(), out.c_str());
  std::printf("  mesh          %lld points, %lld triangles\n", static_cast<long long>(c.points),
              static_cast<long long>(c.triangles));
  std::printf("  files         STL %.1f MiB, MSH 4.1 %.1f MiB\n", mib(file_bytes(in)),
              mib(file_bytes(out)));
  std::printf("  time          read %.3f s + write %.3f s = %.3f s (%.0f triangles/s)\n",
              c.read_seconds, c.write_seconds, total, static_cast<double>(c.triangles) / total);
  if (c.memory.ok()) {
    std::printf("  memory        RSS at start %.1f MiB, peak %.1f MiB: +%.1f MiB = %.0f "
                "bytes/triangle\n",
                mib(c.memory.start_bytes()), mib(c.memory.peak_bytes()),
                mib(c.memory.growth_bytes()),
                static_cast<double>(c.memory.growth_bytes()) / c.triangles);
  }
}

int convert(const std::string& in, const std::string& out, bool json) {
  Conversion c;
  c.memory.start();
  const Stopwatch read_clock;
  absl::StatusOr<Mesh> mesh = read_mesh(in);
  c.read_seconds = read_clock.seconds();
  if (!mesh.ok()) {
    std::fprintf(stderr, "afmesh-bench-io: %s\n", mesh.status().ToString().c_str());
    return 1;
  }
  const Stopwatch write_clock;
  const absl::Status written = write_mesh(*mesh, out);
  c.write_seconds = write_clock.seconds();
  c.memory.finish();
  if (!written.ok()) {
    std::fprintf(stderr, "afmesh-bench-io: %s\n", written.ToString().c_str());
    return 1;
  }
  c.points = static_cast<std::int64_t>(mesh->points.size());
  c.triangles = static_cast<std::int64_t>(mesh->triangles.size());
  print_conversion(in, out, c, json);
  return 0;
}

// Writes the benchmark surface to `stl_path` as binary STL.
int prepare(double size, const std::string& stl_path, bool json) {
  const Stopwatch clock;
  const Mesh sphere = sphere_surface({0.0, 0.0, 0.0}, 1.0, size);
  if (absl::Status s = write_mesh(sphere, stl_path); !s.ok()) {
    std::fprintf(stderr, "afmesh-bench-io: %s\n", s.ToString().c_str());
    return 2;
  }
  if (!json) {
    std::printf("afmesh-bench-io: sphere radius 1, h = %g: %zu triangles written to %s in %.2f s\n",
                size, sphere.triangles.size(), stl_path.c_str(), clock.seconds());
  }
  return 0;
}

// Runs this program again with `args`, waits for it and returns its exit code.
int run_fresh_process(const std::vector<std::string>& args) {
  std::fflush(stdout);  // our lines first, then the child's
  std::vector<char*> argv;
  for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
  argv.push_back(nullptr);
  pid_t pid = 0;
  if (const int error = posix_spawn(&pid, "/proc/self/exe", nullptr, nullptr, argv.data(), environ);
      error != 0) {
    std::fprintf(stderr, "afmesh-bench-io: cannot start /proc/self/exe: %s\n", std::strerror(error));
    return 2;
  }
  int status = 0;
  if (waitpid(pid, &status, 0) != pid || !WIFEXITED(status)) return 2;
  return WEXITSTATUS(status);
}

}  // namespace
}  // namespace afmesh::bench

int main(int argc, char** argv) {
  double size = afmesh::bench::kDefaultSize;
  std::string dir = ".";
  std::vector<std::string> convert_paths;
  bool json = false;
  CLI::App app{"Benchmark of core/io: binary STL -> MSH 4.1 for a ~1M-triangle surface."};
  app.add_option("--size", size, "edge length of the sphere surface (radius 1)");
  app.add_option("--dir", dir, "directory for io_sphere.stl and io_sphere.msh");
  app.add_option("--convert", convert_paths, "IN.stl OUT.msh: only convert, in this process")
      ->expected(2);
  app.add_flag("--json", json, "print one JSON object instead of the readable report");
  CLI11_PARSE(app, argc, argv);
  if (!convert_paths.empty())
    return afmesh::bench::convert(convert_paths[0], convert_paths[1], json);

  const std::string stl = (std::filesystem::path(dir) / "io_sphere.stl").string();
  const std::string msh = (std::filesystem::path(dir) / "io_sphere.msh").string();
  if (const int code = afmesh::bench::prepare(size, stl, json); code != 0) return code;
  std::vector<std::string> args = {argv[0], "--convert", stl, msh};
  if (json) args.push_back("--json");
  return afmesh::bench::run_fresh_process(args);
}
