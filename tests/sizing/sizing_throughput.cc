// Throughput of the size field with many sources (paper §4.1: N_s > 100 dominates the cost):
// evaluations per second for 1, 10, 100 and 1000 random sources in the unit cube, point by point
// (size_at) and in one batch (sizes_at), with and without pruning. Not a test; prints a table.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <random>
#include <utility>
#include <vector>

#include "core/sizing/spec_size_field.h"

namespace afmesh {
namespace {

// `sources` random sources in the unit cube, or within 0.02 of its centre when `clustered` (the
// hard case for pruning: every cell keeps nearly all of them).
SizeSpec random_spec(int sources, bool clustered, std::mt19937& rng) {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  SizeSpec spec;
  spec.max_size = 0.3;
  for (int i = 0; i < sources; ++i) {
    SizeSource s;
    const Point p = clustered ? Point{0.49 + 0.02 * u(rng), 0.49 + 0.02 * u(rng),
                                      0.49 + 0.02 * u(rng)}
                              : Point{u(rng), u(rng), u(rng)};
    s.points.push_back(p);
    const int extra = i % 3;  // point, line and triangle sources in turn
    for (int k = 0; k < extra; ++k) {
      s.points.push_back({p[0] + 0.1 * u(rng), p[1] + 0.1 * u(rng), p[2] + 0.1 * u(rng)});
    }
    s.delta0 = 0.01 + 0.04 * u(rng);
    s.r0 = 0.02 * u(rng);
    s.r1 = 0.05 + 0.1 * u(rng);
    if (i % 3 == 0) s.law = PowerLaw{1.5};
    if (i % 3 == 1) s.law = ExponentialLaw{1.0};
    if (i % 3 == 2) s.law = PolynomialLaw{{1.0, 0.5}};
    spec.sources.push_back(s);
  }
  return spec;
}

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// Evaluations per second of size_at over `xs`, and of sizes_at, each the best of three runs (the
// machine is shared); `checksum` keeps the work from being optimised away.
void measure(const SpecSizeField& field, const std::vector<Point>& xs, double& single,
             double& batch, double& checksum) {
  single = batch = 0.0;
  std::vector<double> out(xs.size());
  for (int run = 0; run < 3; ++run) {
    auto start = std::chrono::steady_clock::now();
    for (const Point& x : xs) checksum += field.size_at(x);
    single = std::max(single, xs.size() / seconds_since(start));
    start = std::chrono::steady_clock::now();
    field.sizes_at(xs, out);
    batch = std::max(batch, xs.size() / seconds_since(start));
    for (double v : out) checksum += v;
  }
}

void run() {
  std::mt19937 rng(2024);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const Box domain{{0, 0, 0}, {1, 1, 1}};
  std::printf("%9s %14s %14s %14s %14s %10s\n", "sources", "single/s", "single/s", "batch/s",
              "batch/s", "build s");
  std::printf("%9s %14s %14s %14s %14s %10s\n", "", "no pruning", "pruning", "no pruning",
              "pruning", "(pruning)");
  double checksum = 0.0;
  for (const auto& [sources, clustered] : {std::pair(1, false), std::pair(10, false),
                                           std::pair(100, false), std::pair(1000, false),
                                           std::pair(1000, true)}) {
    const SizeSpec spec = random_spec(sources, clustered, rng);
    const int n = sources >= 1000 ? 20000 : 200000;
    std::vector<Point> xs(n);
    for (Point& x : xs) x = {u(rng), u(rng), u(rng)};
    const SpecSizeField full = *SpecSizeField::create(spec, domain, {.prune_sources = false});
    const auto start = std::chrono::steady_clock::now();
    const SpecSizeField pruned = *SpecSizeField::create(spec, domain);
    const double build = seconds_since(start);
    double single_full, batch_full, single_pruned, batch_pruned;
    measure(full, xs, single_full, batch_full, checksum);
    measure(pruned, xs, single_pruned, batch_pruned, checksum);
    std::printf("%8d%s %14.3g %14.3g %14.3g %14.3g %10.3f\n", sources, clustered ? "c" : " ",
                single_full, single_pruned, batch_full, batch_pruned, build);
  }
  std::printf("(c: clustered sources)  checksum %.17g\n", checksum);
}

}  // namespace
}  // namespace afmesh

int main() { afmesh::run(); }
