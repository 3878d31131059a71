#include "bench/optimise_study.h"

#include <algorithm>
#include <ctime>
#include <cstdio>
#include <map>
#include <set>
#include <utility>
#include <vector>

#include "absl/strings/str_cat.h"
#include "absl/strings/str_format.h"
#include "absl/strings/str_split.h"
#include "bench/json_line.h"
#include "core/common/progress.h"
#include "core/quality/measures.h"
#include "core/quality/mesh_topology.h"
#include "core/quality/ring_triangulation.h"
#include "core/quality/tet_complex.h"
#include "core/quality/validate.h"
#include "core/volume/generate_volume_mesh.h"

namespace afmesh::bench {
namespace {

// CPU seconds of this process (one thread): steadier than wall time on a shared machine.
double cpu_seconds() { return static_cast<double>(std::clock()) / CLOCKS_PER_SEC; }

struct Figures {
  double min_dihedral = 0;
  std::int64_t below_10 = 0;
  std::int64_t below_20 = 0;
  std::int64_t tets = 0;
  double mean_radius_ratio = 0;
};

Figures figures(const Mesh& mesh) {
  Figures f;
  const absl::StatusOr<QualitySummary> q = summarize_quality(mesh);
  if (!q.ok()) return f;
  f.tets = q->tet_count;
  f.min_dihedral = q->tet_min_dihedral_deg.min;
  f.mean_radius_ratio = q->tet_radius_ratio.mean;
  for (const Tet& t : mesh.tets) {
    const double d = tet_quality(mesh.points, t).min_dihedral_deg;
    f.below_10 += d < 10;
    f.below_20 += d < 20;
  }
  return f;
}

std::string figures_text(const Figures& f) {
  const double n = static_cast<double>(std::max<std::int64_t>(f.tets, 1));
  return absl::StrFormat("%d tets, min dihedral %.2f deg, <10 deg %d (%.3f%%), <20 deg %d (%.3f%%), "
                         "mean radius ratio %.4f",
                         f.tets, f.min_dihedral, f.below_10, 100.0 * f.below_10 / n, f.below_20,
                         100.0 * f.below_20 / n, f.mean_radius_ratio);
}

// Tets under `degrees`, counted by (points on the boundary, faces on the boundary).
std::map<std::pair<int, int>, std::int64_t> classify(const Mesh& mesh, Index boundary_points,
                                                      const std::set<Triangle>& boundary_faces,
                                                      double degrees) {
  std::map<std::pair<int, int>, std::int64_t> classes;
  for (const Tet& t : mesh.tets) {
    if (tet_quality(mesh.points, t).min_dihedral_deg >= degrees) continue;
    int points = 0, faces = 0;
    for (Index p : t) points += p < boundary_points;
    for (int c = 0; c < 4; ++c) faces += boundary_faces.count(sorted_triangle(tet_face(t, c))) > 0;
    ++classes[{points, faces}];
  }
  return classes;
}

std::string classes_text(const std::map<std::pair<int, int>, std::int64_t>& classes) {
  std::string out;
  for (const auto& [key, count] : classes)
    absl::StrAppend(&out, out.empty() ? "" : ", ", count, " with ", key.first, " bpts/", key.second,
                    " bfaces");
  return out.empty() ? "none" : out;
}

// One line per tet under `degrees` (at most `limit`): its min dihedral angle, its points
// (b = on the boundary) and, per edge, the number of tets around it, or "b" when the edge is on
// the boundary (its ring is open).
std::string sliver_details(Mesh& mesh, Index boundary_points, double degrees, int limit) {
  absl::StatusOr<TetComplex> c = TetComplex::build(mesh);
  if (!c.ok()) return c.status().ToString();
  std::string out;
  EdgeRing ring;
  int shown = 0;
  for (Index t = 0; t < c->slots() && shown < limit; ++t) {
    const Tet k = c->tet(t);
    const double d = tet_quality(mesh.points, k).min_dihedral_deg;
    if (d >= degrees) continue;
    ++shown;
    absl::StrAppend(&out, absl::StrFormat("    tet %d: min dihedral %.3f deg, points", t, d));
    for (Index p : k) absl::StrAppend(&out, " ", p, p < boundary_points ? "b" : "");
    absl::StrAppend(&out, "; edge rings");
    for (int i = 0; i < 4; ++i)
      for (int j = i + 1; j < 4; ++j) {
        const bool closed = c->edge_ring(t, k[i], k[j], kMaxRingSize, ring);
        absl::StrAppend(&out, " ", closed ? absl::StrCat(ring.tets.size())
                                          : ring.tets.size() >= kMaxRingSize ? ">" : "b");
      }
    absl::StrAppend(&out, "\n");
  }
  return out;
}

}  // namespace

std::string set_optimise_steps(const std::string& list, OptimiseParams& params) {
  if (list == "default") return "";
  params.edge_removal = params.face_removal = params.smoothing = params.edge_split = false;
  params.smoothing_sweeps = 0;
  for (absl::string_view step : absl::StrSplit(list, ',')) {
    if (step == "edge") params.edge_removal = true;
    else if (step == "face") params.face_removal = true;
    else if (step == "smooth") params.smoothing = true;
    else if (step == "sweep") params.smoothing_sweeps = 1;
    else if (step == "split") params.edge_split = true;
    else if (step != "none") return absl::StrCat("unknown optimisation step '", step, "'");
  }
  return "";
}

int run_optimise_study(const std::string& shape, const Mesh& surface, const StudyOptions& o) {
  VolumeParams vp;
  vp.size = o.size;
  vp.growth = o.growth;
  vp.optimise = false;
  const double front_start = cpu_seconds();
  absl::StatusOr<VolumeResult> result = generate_volume_mesh(surface, vp, no_progress());
  const double front_seconds = cpu_seconds() - front_start;
  if (!result.ok()) {
    std::printf("FAILED %s\n", result.status().ToString().c_str());
    return 1;
  }
  const Mesh raw = std::move(result->mesh);
  const Figures before = figures(raw);
  std::set<Triangle> boundary_faces;
  for (const Triangle& t : surface.triangles) boundary_faces.insert(sorted_triangle(t));
  const auto boundary_points = static_cast<Index>(surface.points.size());
  if (!o.json) {
    std::printf("optimise study: %s, h = %g, surface %zu points\n", shape.c_str(), o.size,
                surface.points.size());
    std::printf("  front     %.3f s cpu\n", front_seconds);
    std::printf("  before    %s\n", figures_text(before).c_str());
  }
  int exit_code = 0;
  for (const StudyVariant& variant : o.variants) {
    Mesh mesh = raw;
    const double opt_start = cpu_seconds();
    const absl::StatusOr<OptimiseStats> stats =
        optimise_tets(mesh, boundary_points, variant.params, no_progress());
    const double opt_seconds = cpu_seconds() - opt_start;
    if (!stats.ok()) {
      std::printf("FAILED %s: %s\n", variant.label.c_str(), stats.status().ToString().c_str());
      exit_code = 1;
      continue;
    }
    const Figures after = figures(mesh);
    const ValidationReport report = validate_volume_mesh(mesh, &surface);
    if (!report.valid()) exit_code = 1;
    const std::string under10 = classes_text(classify(mesh, boundary_points, boundary_faces, 10));
    const std::string under20 = classes_text(classify(mesh, boundary_points, boundary_faces, 20));
    if (o.json) {
      JsonLine j;
      j.add("shape", shape).add("size", o.size).add("variant", variant.label);
      j.add("front_seconds", front_seconds).add("optimise_seconds", opt_seconds);
      j.add("valid", report.valid());
      j.add("tets_before", before.tets).add("min_dihedral_before", before.min_dihedral);
      j.add("below_10_before", before.below_10).add("below_20_before", before.below_20);
      j.add("mean_radius_ratio_before", before.mean_radius_ratio);
      j.add("tets_after", after.tets).add("min_dihedral_after", after.min_dihedral);
      j.add("below_10_after", after.below_10).add("below_20_after", after.below_20);
      j.add("mean_radius_ratio_after", after.mean_radius_ratio);
      j.add("bad_tets", stats->bad_tets).add("edge_removals", stats->edge_removals);
      j.add("flips_32", stats->flips_32).add("flips_23", stats->flips_23);
      j.add("points_moved", stats->points_moved).add("edge_splits", stats->edge_splits);
      j.add("under_10_after", under10).add("under_20_after", under20);
      std::printf("%s\n", j.str().c_str());
      continue;
    }
    std::printf("  [%s]\n", variant.label.c_str());
    std::printf("  optimise  %.3f s cpu (%.1f%% of the front's): %lld tets under target, %lld edge "
                "removals (%lld 3-2), %lld 2-3 flips, %lld point moves, %lld edge splits\n",
                opt_seconds, 100.0 * opt_seconds / front_seconds,
                static_cast<long long>(stats->bad_tets), static_cast<long long>(stats->edge_removals),
                static_cast<long long>(stats->flips_32), static_cast<long long>(stats->flips_23),
                static_cast<long long>(stats->points_moved),
                static_cast<long long>(stats->edge_splits));
    std::printf("  after     %s\n", figures_text(after).c_str());
    std::printf("  validity  %s\n", report.valid() ? "valid" : report.to_string().c_str());
    std::printf("  <10 after %s\n  <20 after %s\n", under10.c_str(), under20.c_str());
    std::printf("%s", sliver_details(mesh, boundary_points, 10, 10).c_str());
  }
  return exit_code;
}

}  // namespace afmesh::bench
