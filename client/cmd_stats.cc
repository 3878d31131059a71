// afmesh stats MESH [--json] [--envs tags|none]: counts, validity and quality of a mesh file.
//
// Crossing environments (paper §2): triangle tags are read as environment ids (0 = none).
//  default      when some triangle tag is positive, a volume mesh also gets the environment_gap
//               check (no tet joins two environments across a thin gap), as a warning: the tags
//               may be patch ids rather than environments.
//  --envs tags  the tags are environments: environment_gap failures make the mesh invalid, and
//               a surface is checked with the relaxed self-intersection rule (faces of two
//               different positive environments may cross). Negative tags are bad input.
//  --envs none  no environment checks.
#include <cstdint>
#include <iostream>
#include <string>
#include <utility>
#include <vector>

#include "absl/strings/str_cat.h"
#include "absl/strings/str_format.h"
#include "client/commands.h"
#include "client/json_writer.h"
#include "core/environments/environments.h"
#include "core/io/mesh_io.h"
#include "core/quality/measures.h"
#include "core/quality/validate.h"

namespace afmesh::cli {
namespace {

struct StatsOptions {
  std::string path;
  bool json = false;
  std::string envs;  // "", "tags" or "none"
};

const char* outcome_name(CheckOutcome o) {
  switch (o) {
    case CheckOutcome::kPassed: return "passed";
    case CheckOutcome::kWarning: return "warning";
    case CheckOutcome::kFailed: return "FAILED";
    case CheckOutcome::kNotRun: return "not run";
  }
  return "?";
}

void print_histogram(std::ostream& out, const char* title, const Histogram& h, const char* unit) {
  const std::int64_t total = h.total();
  if (total == 0) return;
  out << title << ":\n";
  std::int64_t most = 1;
  for (std::int64_t c : h.counts) most = std::max(most, c);
  const int bins = static_cast<int>(h.counts.size());
  for (int i = 0; i < bins; ++i) {
    if (h.counts[i] == 0) continue;
    const int bar = static_cast<int>((40 * h.counts[i] + most - 1) / most);
    const std::string range = absl::StrFormat("[%g, %g)%s", h.bin_lo(i),
                                              h.bin_lo(i) + (h.hi - h.lo) / bins, unit);
    out << absl::StrFormat("  %-14s %10d %6.2f%% %s\n", range, h.counts[i],
                           100.0 * h.counts[i] / total, std::string(bar, '#'));
  }
}

void print_stats(const StatsOptions& o, const Mesh& m, const QualitySummary& q,
                 const ValidationReport& report, const ReadReport& notes) {
  std::cout << o.path << "\n";
  std::cout << absl::StrFormat("  points %d, triangles %d, tetrahedra %d\n", m.points.size(),
                               m.triangles.size(), m.tets.size());
  for (const std::string& n : notes.notes) std::cout << "  note: " << n << "\n";
  std::cout << "validity: " << (report.valid() ? "valid" : "INVALID") << "\n";
  for (const Check& c : report.checks)
    std::cout << absl::StrFormat("  %-26s %-8s %s\n", c.name, outcome_name(c.outcome), c.summary);
  for (const Check& c : report.checks)
    for (const Finding& f : c.findings) std::cout << "    " << c.name << ": " << f.message << "\n";
  if (q.tet_count > 0) {
    std::cout << "tetrahedra quality:\n";
    std::cout << absl::StrFormat("  min dihedral  min %.2f°  mean %.2f°  (%.3f%% < 10°, %.3f%% < 20°)\n",
                                 q.tet_min_dihedral_deg.min, q.tet_min_dihedral_deg.mean,
                                 100 * q.share_min_dihedral_below_10,
                                 100 * q.share_min_dihedral_below_20);
    std::cout << absl::StrFormat("  max dihedral  max %.2f°  mean %.2f°\n",
                                 q.tet_max_dihedral_deg.max, q.tet_max_dihedral_deg.mean);
    std::cout << absl::StrFormat("  radius ratio  min %.4f  mean %.4f\n", q.tet_radius_ratio.min,
                                 q.tet_radius_ratio.mean);
    if (q.boundary_slivers > 0)
      std::cout << absl::StrFormat(
          "  away from the %lld boundary slivers (angle < %g°): %lld tets, min dihedral %.2f°  "
          "(%.3f%% < 20°)\n",
          static_cast<long long>(q.boundary_slivers), kSliverTriangleDeg,
          static_cast<long long>(q.tets_away_from_slivers), q.away_min_dihedral_deg.min,
          100 * q.share_away_below_20);
    print_histogram(std::cout, "  min dihedral angle histogram", q.tet_min_dihedral_hist, "°");
    print_histogram(std::cout, "  radius ratio histogram", q.tet_radius_ratio_hist, "");
  }
  if (q.triangle_count > 0) {
    std::cout << "triangle quality:\n";
    std::cout << absl::StrFormat("  min angle     min %.2f°  mean %.2f°\n",
                                 q.triangle_min_angle_deg.min, q.triangle_min_angle_deg.mean);
    std::cout << absl::StrFormat("  radius ratio  min %.4f  mean %.4f\n",
                                 q.triangle_radius_ratio.min, q.triangle_radius_ratio.mean);
    if (q.tet_count == 0)
      print_histogram(std::cout, "  min angle histogram", q.triangle_min_angle_hist, "°");
  }
}

void add_measure(JsonWriter& j, std::string_view name, const MeasureStats& s) {
  j.begin_object(name);
  j.field("count", s.count);
  j.field("min", s.min);
  j.field("max", s.max);
  j.field("mean", s.mean);
  j.end_object();
}

void add_histogram(JsonWriter& j, std::string_view name, const Histogram& h) {
  j.begin_object(name);
  j.field("lo", h.lo);
  j.field("hi", h.hi);
  j.begin_array("counts");
  for (std::int64_t c : h.counts) j.value(c);
  j.end_array();
  j.end_object();
}

void print_json(const StatsOptions& o, const Mesh& m, const QualitySummary& q,
                const ValidationReport& report, const ReadReport& notes) {
  JsonWriter j(std::cout);
  j.begin_object();
  j.field("file", o.path);
  j.begin_object("counts");
  j.field("points", static_cast<std::int64_t>(m.points.size()));
  j.field("triangles", static_cast<std::int64_t>(m.triangles.size()));
  j.field("tetrahedra", static_cast<std::int64_t>(m.tets.size()));
  j.end_object();
  j.begin_array("notes");
  for (const std::string& n : notes.notes) j.value(n);
  j.end_array();
  j.begin_object("validation");
  j.field("valid", report.valid());
  j.begin_array("checks");
  for (const Check& c : report.checks) {
    j.begin_object();
    j.field("name", c.name);
    j.field("outcome", outcome_name(c.outcome));
    j.field("summary", c.summary);
    j.field("finding_count", c.finding_count);
    j.begin_array("findings");
    for (const Finding& f : c.findings) j.value(f.message);
    j.end_array();
    j.end_object();
  }
  j.end_array();
  j.end_object();
  j.begin_object("quality");
  if (q.tet_count > 0) {
    j.begin_object("tetrahedra");
    add_measure(j, "min_dihedral_deg", q.tet_min_dihedral_deg);
    add_measure(j, "max_dihedral_deg", q.tet_max_dihedral_deg);
    add_measure(j, "radius_ratio", q.tet_radius_ratio);
    j.field("share_min_dihedral_below_10", q.share_min_dihedral_below_10);
    j.field("share_min_dihedral_below_20", q.share_min_dihedral_below_20);
    j.field("boundary_slivers", q.boundary_slivers);
    j.field("tets_away_from_slivers", q.tets_away_from_slivers);
    add_measure(j, "away_from_slivers_min_dihedral_deg", q.away_min_dihedral_deg);
    j.field("away_from_slivers_share_below_20", q.share_away_below_20);
    add_histogram(j, "min_dihedral_histogram", q.tet_min_dihedral_hist);
    add_histogram(j, "radius_ratio_histogram", q.tet_radius_ratio_hist);
    j.end_object();
  }
  if (q.triangle_count > 0) {
    j.begin_object("triangles");
    add_measure(j, "min_angle_deg", q.triangle_min_angle_deg);
    add_measure(j, "radius_ratio", q.triangle_radius_ratio);
    add_histogram(j, "min_angle_histogram", q.triangle_min_angle_hist);
    j.end_object();
  }
  j.end_object();
  j.end_object();
  std::cout << "\n";
}

// The validation of `mesh` with the environment checks `o.envs` asks for. `env` holds the
// arrays the params point to. Returns false (with a message on stderr) when --envs tags cannot
// read the tags.
bool validate(const StatsOptions& o, const Mesh& mesh, ValidationReport& report,
              std::vector<std::int32_t>& env, ReadReport& notes) {
  ValidationParams params;
  const bool strict_tags = o.envs == "tags";
  if (strict_tags || (o.envs.empty() && has_positive_tags(mesh))) {
    absl::StatusOr<FrontEnvironments> read = environments_from_tags(mesh);
    if (read.ok()) {
      if (mesh.tets.empty()) {
        if (strict_tags) {
          env = std::move(read->face);
          params.face_environments = env;
        }
      } else {
        env = std::move(read->point);
        params.point_environments = env;
        params.environment_gap_warns_only = !strict_tags;
      }
    } else if (strict_tags) {
      std::cerr << "afmesh stats: " << o.path << ": --envs tags: " << read.status().message()
                << "\n";
      return false;
    } else {
      notes.notes.push_back(absl::StrCat("triangle tags not read as environments: ",
                                         read.status().message()));
    }
  }
  // A mesh with tets is checked as a volume mesh, one without as a closed surface.
  report = mesh.tets.empty() ? validate_surface(mesh, params) : validate_volume_mesh(mesh, nullptr, params);
  return true;
}

int run_stats(const StatsOptions& o) {
  ReadReport notes;
  absl::StatusOr<Mesh> mesh = read_mesh(o.path, &notes);
  if (!mesh.ok()) {
    std::cerr << "afmesh stats: " << mesh.status().message() << "\n";
    return kExitBadInput;
  }
  ValidationReport report;
  std::vector<std::int32_t> env;
  if (!validate(o, *mesh, report, env, notes)) return kExitBadInput;
  absl::StatusOr<QualitySummary> quality = summarize_quality(*mesh);
  if (!quality.ok()) {  // indices out of range: the validation says which
    quality = QualitySummary{};
  }
  if (o.json)
    print_json(o, *mesh, *quality, report, notes);
  else
    print_stats(o, *mesh, *quality, report, notes);
  return report.valid() ? kExitOk : kExitInvalidMesh;
}

}  // namespace

void add_stats_command(CLI::App& app, Action& action) {
  auto opts = std::make_shared<StatsOptions>();
  CLI::App* cmd = app.add_subcommand(
      "stats", "Counts, validity and quality histograms of a mesh (exit 4 when invalid)");
  cmd->add_option("mesh", opts->path, "Mesh file (.msh .mesh .stl .obj)")->required();
  cmd->add_flag("--json", opts->json, "Print JSON for scripts");
  cmd->add_option("--envs", opts->envs,
                  "triangle tags as crossing environments: tags (relaxed self-intersection "
                  "rule, tets across a gap fail) or none (default: tets across a gap warn when "
                  "tags are present)")
      ->check(CLI::IsMember({"tags", "none"}));
  cmd->callback([opts, &action] { action = [opts] { return run_stats(*opts); }; });
}

}  // namespace afmesh::cli
