// afmesh-bench-sizing: throughput of the size field with many sources (paper §4.1: "a high
// number of sources (N_s > 100) will have a marked impact on CPU-times"). Evaluations per second
// of SpecSizeField for 1, 10, 100 and 1000 random sources in the unit cube (and 1000 clustered
// within 0.02 of its centre, the hard case for pruning), point by point (size_at) and in one
// batch (sizes_at), with and without pruning, on one thread.
//
//   afmesh-bench-sizing [--sources 1,10,100,1000] [--clustered 1000] [--points N] [--runs 3]
//                       [--json]
//
// Each figure is the best of --runs passes over the same random points (the machine may be
// shared). Pruning never changes a result (spec_size_field.h); the checksum printed covers both
// fields so the work is not optimised away. gmsh, netgen and tetgen have no source fields of this
// kind, so there is no peer to compare with.
#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <random>
#include <string>
#include <vector>

#include "CLI/CLI.hpp"
#include "bench/json_line.h"
#include "core/sizing/spec_size_field.h"

namespace afmesh::bench {
namespace {

struct Options {
  std::vector<int> sources = {1, 10, 100, 1000};
  std::vector<int> clustered = {1000};
  int points = 0;  // 0: 200000 below 1000 sources, 20000 from 1000 on
  int runs = 3;
  bool json = false;
};

struct Case {
  int sources = 0;
  bool clustered = false;
};

// Evaluations per second of one field, point by point and batched.
struct Throughput {
  double single = 0.0;
  double batch = 0.0;
};

struct Measurement {
  Case c;
  int points = 0;
  Throughput full;             // pruning off
  Throughput pruned;           // pruning on
  double build_seconds = 0.0;  // SpecSizeField::create with pruning (the cells)
};

// `count` random sources in the unit cube, or within 0.02 of its centre when `clustered`: point,
// line and triangle sources and the three laws in turn, delta0 0.01-0.05, r0 < 0.02, r1 0.05-0.15.
SizeSpec random_spec(int count, bool clustered, std::mt19937& rng) {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  SizeSpec spec;
  spec.max_size = 0.3;
  for (int i = 0; i < count; ++i) {
    SizeSource s;
    const Point p = clustered
                        ? Point{0.49 + 0.02 * u(rng), 0.49 + 0.02 * u(rng), 0.49 + 0.02 * u(rng)}
                        : Point{u(rng), u(rng), u(rng)};
    s.points.push_back(p);
    for (int k = 0; k < i % 3; ++k) {
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

Throughput measure(const SpecSizeField& field, const std::vector<Point>& xs, int runs,
                   double& checksum) {
  Throughput best;
  std::vector<double> out(xs.size());
  const auto n = static_cast<double>(xs.size());
  for (int run = 0; run < runs; ++run) {
    auto start = std::chrono::steady_clock::now();
    for (const Point& x : xs) checksum += field.size_at(x);
    best.single = std::max(best.single, n / seconds_since(start));
    start = std::chrono::steady_clock::now();
    field.sizes_at(xs, out);
    best.batch = std::max(best.batch, n / seconds_since(start));
    for (const double v : out) checksum += v;
  }
  return best;
}

Measurement run_case(const Case& c, const Options& o, std::mt19937& rng, double& checksum) {
  const SizeSpec spec = random_spec(c.sources, c.clustered, rng);
  Measurement m;
  m.c = c;
  m.points = o.points > 0 ? o.points : (c.sources >= 1000 ? 20000 : 200000);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<Point> xs(m.points);
  for (Point& x : xs) x = {u(rng), u(rng), u(rng)};
  const Box domain{{0, 0, 0}, {1, 1, 1}};
  const SpecSizeField full = *SpecSizeField::create(spec, domain, {.prune_sources = false});
  const auto start = std::chrono::steady_clock::now();
  const SpecSizeField pruned = *SpecSizeField::create(spec, domain);
  m.build_seconds = seconds_since(start);
  m.full = measure(full, xs, o.runs, checksum);
  m.pruned = measure(pruned, xs, o.runs, checksum);
  return m;
}

void print_json(const Measurement& m) {
  JsonLine j;
  j.add("tool", "afmesh").add("bench", "sizing").add("sources", m.c.sources);
  j.add("clustered", m.c.clustered).add("points", m.points);
  j.add("single_no_pruning", m.full.single).add("single_pruning", m.pruned.single);
  j.add("batch_no_pruning", m.full.batch).add("batch_pruning", m.pruned.batch);
  j.add("build_seconds", m.build_seconds);
  std::printf("%s\n", j.str().c_str());
}

void print_header() {
  std::printf("afmesh-bench-sizing: SpecSizeField evaluations per second, one thread\n");
  std::printf("%9s %9s %13s %13s %13s %13s %9s %8s\n", "sources", "points", "single/s", "single/s",
              "batch/s", "batch/s", "pruning", "build s");
  std::printf("%9s %9s %13s %13s %13s %13s %9s %8s\n", "", "", "no pruning", "pruning",
              "no pruning", "pruning", "speed-up", "(cells)");
}

void print_row(const Measurement& m) {
  std::printf("%8d%s %9d %13.3g %13.3g %13.3g %13.3g %8.1fx %8.3f\n", m.c.sources,
              m.c.clustered ? "c" : " ", m.points, m.full.single, m.pruned.single, m.full.batch,
              m.pruned.batch, m.pruned.batch / m.full.batch, m.build_seconds);
}

int run(const Options& o) {
  std::vector<Case> cases;
  for (const int s : o.sources) cases.push_back({s, false});
  for (const int s : o.clustered) cases.push_back({s, true});
  std::mt19937 rng(2024);
  double checksum = 0.0;
  if (!o.json) print_header();
  for (const Case& c : cases) {
    const Measurement m = run_case(c, o, rng, checksum);
    if (o.json) {
      print_json(m);
    } else {
      print_row(m);
    }
    std::fflush(stdout);
  }
  if (!o.json) {
    std::printf(
        "(c: sources clustered within 0.02 of the centre; speed-up: batch pruning / batch "
        "no pruning; peers: gmsh, netgen and tetgen have no source fields, no ratio)\n");
  }
  std::fprintf(stderr, "afmesh-bench-sizing: checksum %.17g\n", checksum);
  return 0;
}

}  // namespace
}  // namespace afmesh::bench

int main(int argc, char** argv) {
  afmesh::bench::Options o;
  CLI::App app{"Throughput of the size field with many sources (evaluations per second)."};
  app.add_option("--sources", o.sources, "source counts, spread over the unit cube")
      ->delimiter(',');
  app.add_option("--clustered", o.clustered, "source counts clustered at the centre")
      ->delimiter(',');
  app.add_option("--points", o.points,
                 "evaluation points per case (default 200000, 20000 from "
                 "1000 sources)")
      ->check(CLI::NonNegativeNumber);
  app.add_option("--runs", o.runs, "passes per figure; the best is kept")
      ->check(CLI::PositiveNumber);
  app.add_flag("--json", o.json, "print one JSON object per case instead of the table");
  CLI11_PARSE(app, argc, argv);
  return afmesh::bench::run(o);
}
