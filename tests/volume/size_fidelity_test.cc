// The size asked for is the size built (issue 10, part 5): with a uniform size h the interior
// edges average h within 10% and 90% of them lie within [0.7 h, 1.4 h], whether the front's
// edges match h, are finer or are coarser; and real closed surfaces of other people mesh at the
// default growth 1.
#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <string>
#include <string_view>

#include "absl/container/flat_hash_set.h"
#include "absl/strings/str_join.h"
#include "core/geometry/vec.h"
#include "core/io/mesh_io.h"
#include "core/quality/measures.h"
#include "core/quality/validate.h"
#include "core/shapes/shapes.h"
#include "core/volume/generate_volume_mesh.h"
#include "core/volume/estimate_elements.h"
#include "core/volume/repair_front.h"
#include "gtest/gtest.h"
#include "tests/volume/mesh_and_check.h"

namespace afmesh {
namespace {

struct EdgeFigures {
  double mean_over_h = 0;  // mean interior edge length / h
  double share_in_band = 0;  // share of interior edges in [0.7 h, 1.4 h]
  std::size_t edges = 0;
};

// Interior edges: those of the tets that are not edges of the boundary triangles (and, with
// `within` > 0, whose midpoints lie within that distance of the origin).
EdgeFigures interior_edges(const Mesh& mesh, double h, double within = 0) {
  auto key = [](Index a, Index b) {
    return std::pair<Index, Index>(std::min(a, b), std::max(a, b));
  };
  absl::flat_hash_set<std::pair<Index, Index>> boundary, seen;
  for (const Triangle& t : mesh.triangles)
    for (int k = 0; k < 3; ++k) boundary.insert(key(t[k], t[(k + 1) % 3]));
  EdgeFigures f;
  double sum = 0;
  std::size_t in_band = 0;
  for (const Tet& t : mesh.tets) {
    for (int i = 0; i < 4; ++i) {
      for (int j = i + 1; j < 4; ++j) {
        const auto e = key(t[i], t[j]);
        if (boundary.contains(e) || !seen.insert(e).second) continue;
        const Point& a = mesh.points[e.first];
        const Point& b = mesh.points[e.second];
        if (within > 0 && norm(scale(add(a, b), 0.5)) > within) continue;
        const double length = norm(sub(a, b));
        sum += length;
        in_band += length >= 0.7 * h && length <= 1.4 * h;
        ++f.edges;
      }
    }
  }
  f.mean_over_h = sum / (static_cast<double>(f.edges) * h);
  f.share_in_band = static_cast<double>(in_band) / static_cast<double>(f.edges);
  return f;
}

Mesh mesh_valid(const Mesh& front, double h) { return mesh_and_check(front, h).mesh; }

TEST(SizeFidelity, SphereWhoseFrontMatchesTheSize) {
  const Mesh mesh = mesh_valid(sphere_surface({0, 0, 0}, 1.0, 0.1), 0.1);
  const EdgeFigures f = interior_edges(mesh, 0.1);
  std::printf("sphere h 0.1: %zu interior edges, mean %.3f h, %.1f%% in [0.7 h, 1.4 h]\n",
              f.edges, f.mean_over_h, 100 * f.share_in_band);
  EXPECT_NEAR(f.mean_over_h, 1.0, 0.1) << f.edges << " edges";
  // The front alone left 89.2% here; the optimiser's smoothing sweep (optimise.h) 94.8%.
  EXPECT_GT(f.share_in_band, 0.90);
}

// Regression for issue 10: a front finer than the size (edges 0.078 at size 0.08 gave interior
// edges of 0.059 at growth 1, eq. 15 carrying the front's smallest sizes everywhere). Away from
// the front, past the layers that grade from its size to h (growth 1.2 per element), the edges
// are h long.
TEST(SizeFidelity, FrontFinerThanTheSizeGrowsToIt) {
  const Mesh mesh = mesh_valid(sphere_surface({0, 0, 0}, 1.0, 0.06), 0.12);
  const EdgeFigures deep = interior_edges(mesh, 0.12, 0.5);
  std::printf("sphere front 0.06, h 0.12, within 0.5: %zu interior edges, mean %.3f h, %.1f%% in "
              "[0.7 h, 1.4 h]\n",
              deep.edges, deep.mean_over_h, 100 * deep.share_in_band);
  EXPECT_NEAR(deep.mean_over_h, 1.0, 0.1) << deep.edges << " edges";
  EXPECT_GT(deep.share_in_band, 0.90);
}

TEST(SizeFidelity, FrontCoarserThanTheSizeComesDownToIt) {
  const Mesh mesh = mesh_valid(box_surface({0, 0, 0}, {1, 1, 1}, 0.2), 0.1);
  const EdgeFigures f = interior_edges(mesh, 0.1);
  std::printf("box front 0.2, h 0.1: %zu interior edges, mean %.3f h, %.1f%% in [0.7 h, 1.4 h]\n",
              f.edges, f.mean_over_h, 100 * f.share_in_band);
  EXPECT_NEAR(f.mean_over_h, 1.0, 0.1) << f.edges << " edges";
}

// The surface in the file at `path`, read and repaired as the service does (empty, with a
// failure naming the file and `where_from`, when it cannot be read).
Mesh repaired_front(const std::string& path, std::string_view where_from) {
  absl::StatusOr<Mesh> front = read_mesh(path);
  EXPECT_TRUE(front.ok()) << path << ": " << front.status() << " (" << where_from << ")";
  if (!front.ok()) return {};
  repair_front(*front);
  return *std::move(front);
}

// A closed surface from ../shared/corpus (real files from Debian packages; CI has ../shared
// beside the checkout), read and repaired as the service does.
Mesh corpus_front(const std::string& name) {
  const std::filesystem::path path =
      std::filesystem::path(AFMESH_SOURCE_DIR) / ".." / "shared" / "corpus" / name;
  return repaired_front(path.string(), "../shared/corpus");
}

// Regression for issue 10: a scan-like blob (openfoam-examples), closed and clean, got stuck at
// the default growth 1 and the default size (the mean edge).
TEST(Regression, Issue10CorpusBlobMeshesAtGrowthOne) {
  const Mesh front = corpus_front("of_blob.stl");
  ASSERT_FALSE(front.triangles.empty());
  mesh_valid(front, mean_edge_length(front));
}

// The front loop alone (no optimiser) at `share` times the front's mean edge: how the
// regressions below run the corpus's sliver fronts.
VolumeParams front_only_at_mean_edge(const Mesh& front, double share = 1.0) {
  VolumeParams params;
  params.size = share * mean_edge_length(front);
  params.optimise = false;
  return params;
}

// Regression for issue 10, part 3: a CAD part (netgen-doc, 380 triangles, angles down to
// 0.44 degrees) stopped "stuck ... after re-opening its surroundings 4 times" at its mean edge:
// the front left pockets of slivers that are not star-shaped (no one point sees all their
// faces), so fill_pocket could not fill them, and the re-opened cavities were rebuilt into the
// same pockets. The back-off now fills the part of such a pocket that its deepest point sees
// (fill_part_of_pocket); the part meshes as given, boundary kept.
TEST(Regression, Issue10CorpusPart1MeshesAsGiven) {
  const Mesh front = corpus_front("netgen_part1.stl");
  ASSERT_FALSE(front.triangles.empty());
  mesh_valid(front, mean_edge_length(front));
}

// Counts the front loop's steps: it reports its progress once every 256 steps.
class StepCounter : public Progress {
 public:
  void report(std::string_view stage, double) override { front_reports += stage == "front"; }
  std::int64_t front_reports = 0;
};

// The number before `what` in `message` (-1 when absent).
std::int64_t count_before(std::string_view message, std::string_view what) {
  const std::size_t at = message.find(what);
  if (at == std::string_view::npos || at < 2) return -1;
  std::size_t from = at - 1;
  while (from > 0 && std::isdigit(static_cast<unsigned char>(message[from - 1]))) --from;
  return std::stoll(std::string(message.substr(from, at - 1 - from)));
}

// A raw CAD tessellation of occt-misc (OCCT's sample data, /usr/share/opencascade/data/stl/;
// scripts/install-deps.sh installs it), read and repaired as the service does.
Mesh occt_front(const std::string& name) {
  return repaired_front("/usr/share/opencascade/data/stl/" + name, "scripts/install-deps.sh");
}

// Regression for issue 10, part 2 (never hang): netgen's part1 at 0.5 x its mean edge could
// not be closed among its slivers; the back-off re-opened 43 regions, the whole mesh twice,
// building 56k tets (19x the 3k expected) in 101k steps and 18-45 s before the ring limit
// stopped it; it later stopped within its VolumeBudget and now meshes. netgen_hinge (netgen-doc,
// 488 of its 1,212 triangles with an angle under 5 degrees, down to 0.33) at 1.2 times its mean
// edge was such a front: its first run re-opened the same region 16 times in a row without
// meshing more of the volume (its budget) and stopped, naming where. Since its sliver faces fit
// their elements to the room before them (element_size_in_room) it closes in one run; given a
// tenth of its VolumeBudget it stops at that, which is checked here in counts of steps and
// tets, not seconds, with no rerun asked for (local_refinements 0).
TEST(Regression, Issue10SliverFrontThatCannotCloseStopsWithinItsBudget) {
  const Mesh front = corpus_front("netgen_hinge.stl");
  ASSERT_FALSE(front.triangles.empty());
  VolumeParams params = front_only_at_mean_edge(front, 1.2);
  params.local_refinements = 0;
  params.budget_share = 0.1;
  absl::StatusOr<VolumeEstimate> estimate = estimate_volume_mesh(front, params);
  ASSERT_TRUE(estimate.ok()) << estimate.status();
  VolumeBudget budget =
      volume_budget(estimate->tets, static_cast<std::int64_t>(front.triangles.size()));
  budget.tets_built = static_cast<std::int64_t>(0.1 * static_cast<double>(budget.tets_built));
  budget.searches = static_cast<std::int64_t>(0.1 * static_cast<double>(budget.searches));
  StepCounter steps;
  absl::StatusOr<VolumeResult> result = generate_volume_mesh(front, params, steps);
  ASSERT_FALSE(result.ok()) << "meshes now: make this a test that it is valid";
  EXPECT_EQ(result.status().code(), absl::StatusCode::kFailedPrecondition);
  const std::string message(result.status().message());
  // It stops at one of its bounds, named: its budget of work, the re-openings in a row without
  // progress (its budget) or the re-openings of one region (the most per region).
  EXPECT_TRUE(message.find("within its budget") != std::string::npos ||
              message.find("(its budget)") != std::string::npos ||
              message.find("(the most per region)") != std::string::npos)
      << message;
  EXPECT_NE(message.find(" near ("), std::string::npos) << message;
  EXPECT_NE(message.find("sliver triangles"), std::string::npos) << message;
  EXPECT_NE(message.find(kRetriangulatedSurfaceAdvice), std::string::npos) << message;
  const std::int64_t built = count_before(message, "tets built");
  EXPECT_GT(built, 0) << message;
  EXPECT_LE(built, budget.tets_built) << message;
  EXPECT_LE(256 * steps.front_reports, budget.searches);
}

// Regression for issue 10, part 3: netgen's part1 at half its mean edge, the front that stopped
// within its budget above before, meshes as given.
TEST(Regression, Issue10Part1AtHalfItsMeanEdgeMeshes) {
  const Mesh front = corpus_front("netgen_part1.stl");
  ASSERT_FALSE(front.triangles.empty());
  VolumeParams params = front_only_at_mean_edge(front, 0.5);
  mesh_and_check(front, params);
}

// A knot (libcgal-demo), closed and clean, at the same defaults.
TEST(RealSurfaces, CorpusKnotMeshesAtGrowthOne) {
  const Mesh front = corpus_front("cgal_knot1.stl");
  ASSERT_FALSE(front.triangles.empty());
  mesh_valid(front, mean_edge_length(front));
}

// Regression for issue 10: a front that cannot be closed says why, in terms of the input. The
// lever (gmsh-doc) has fans of triangles with angles down to 0.008 degrees; the front failed
// there, and the message had to say so instead of advising "a size near the input's edge
// lengths" (the size already was). Issue 10, part 3: it meshed as given at its mean edge after
// meshing again where runs stopped among the slivers, and since sliver needles take points as
// other faces do (not their neighbours' far corners, candidates.cc) on its first run.
TEST(Regression, Issue10LeverMeshesAsGiven) {
  const Mesh front = corpus_front("gmsh_lever.stl");
  ASSERT_FALSE(front.triangles.empty());
  VolumeParams params = front_only_at_mean_edge(front);
  params.local_refinements = 0;
  const VolumeResult result = mesh_and_check(front, params);
  ASSERT_FALSE(result.mesh.tets.empty());
  for (const std::string& warning : result.warnings) {
    EXPECT_NE(warning.find("sliver triangles"), std::string::npos) << warning;
    EXPECT_EQ(warning.find("give a size near"), std::string::npos) << warning;
  }
}

// Issue 10, part 3: the pinion (libcgal-demo, a gear: 420 of its 1,300 triangles with angles
// under 5 degrees, down to 1.3) meshes as given at its mean edge. When every face of it retried
// at once under later rules, not only those touching its slivers (touches_input_sliver), it
// stopped over its budget three times and failed.
TEST(Regression, Issue10PinionMeshesAsGiven) {
  const Mesh front = corpus_front("cgal_pinion.stl");
  ASSERT_FALSE(front.triangles.empty());
  VolumeParams params = front_only_at_mean_edge(front);
  mesh_and_check(front, params);
}

// Issue 10, part 3: occt-misc's TR12J_OCC.stl, a raw CAD tessellation (26,966 triangles, 308
// with an angle under 5 degrees, caps up to 179.9), meshes as given at its mean edge. It stopped
// stuck among caps of 150-166 degrees, 14-48 faces from the nearest triangle under 5 degrees,
// while only the faces touching those retried at once under later rules; now the faces touching
// any poor face do (mark_poor_input_faces). Each run meshed again says why and where.
TEST(Regression, Issue10RawCadTr12jMeshesAsGiven) {
  const Mesh front = occt_front("TR12J_OCC.stl");
  ASSERT_FALSE(front.triangles.empty());
  const VolumeResult result = mesh_and_check(front, front_only_at_mean_edge(front));
  for (const std::string& warning : result.warnings)
    EXPECT_NE(warning.find("meshed again with the size halved within"), std::string::npos)
        << warning;
}

// Issue 10, part 3: netgen_hinge as given at its mean edge. Every run stopped among thin wedges
// the front had left, two faces on one edge facing each other across a few degrees (195 of the
// 610 edges of the front within 15 of its last stop), where no new point fits; the face taking
// its neighbour's far corner first (wedge_apex_candidates) closes them, and the hinge meshes.
TEST(Regression, Issue10HingeMeshesAsGiven) {
  const Mesh front = corpus_front("netgen_hinge.stl");
  ASSERT_FALSE(front.triangles.empty());
  mesh_and_check(front, front_only_at_mean_edge(front));
  // At 1.2 times its mean edge it stopped stuck (Issue10SliverFrontThatCannotCloseStopsWithin-
  // ItsBudget); with its sliver faces' elements fitted to their room it closes in one run.
  VolumeParams coarser = front_only_at_mean_edge(front, 1.2);
  coarser.local_refinements = 0;
  mesh_and_check(front, coarser);
}

// Issue 10, part 3: a sliver front whose run uses up its VolumeBudget is meshed again with the
// size halved about the face it was working on (refine_where_stuck, kMaxRefinementsOverBudget).
// No corpus front runs over its whole budget and then closes (only sh2.stl, which does not
// close and takes 15-40 s), so netgen_part1 at its mean edge is given a small share of it: its
// first run stops over it, the warning says so and where the size was halved, and a later run
// closes, valid. Since faces larger than the size asked are asked the shape of their own best
// element (min_quality_for_face in candidates.cc) it closes within 0.1 of its budget, and over
// 0.05 its first run stops over the tets it may build instead; 0.07 is given.
TEST(Regression, Issue10SliverFrontOverItsBudgetMeshesAgain) {
  const Mesh front = corpus_front("netgen_part1.stl");
  ASSERT_FALSE(front.triangles.empty());
  VolumeParams params = front_only_at_mean_edge(front);
  params.budget_share = 0.07;
  const VolumeResult result = mesh_and_check(front, params);
  ASSERT_FALSE(result.warnings.empty()) << "closes within the share: give it less";
  const std::string& first = result.warnings.front();
  EXPECT_NE(first.find("did not close within its budget"), std::string::npos) << first;
  EXPECT_NE(first.find("meshed again with the size halved within"), std::string::npos) << first;
}

// Issue 10, part 2 (never hang): the runs of one job make at most 3 times the first run's
// budget of crossing tests in all, each rerun given what is left (kJobBudgets in
// generate_volume_mesh.cc). A run goes on past the faces it gets stuck at (ParkedFaces), so each
// rerun could use a whole budget: OCCT's sh2.stl at half its mean edge, which does not close,
// took over 140 s to say so (48 s with the bound). netgen_hinge at a 25th of its diagonal with a
// 20th of its budget runs over it in each of its first runs; its third is given only what the
// job has left, and the message says that the job's work is used up (with 0.1 or 0.2 it closes).
TEST(Regression, Issue10RunsOfAJobShareThreeBudgets) {
  const Mesh front = corpus_front("netgen_hinge.stl");
  ASSERT_FALSE(front.triangles.empty());
  VolumeParams params;
  params.size = 2.36643;
  params.optimise = false;
  params.budget_share = 0.05;
  absl::StatusOr<VolumeResult> result = generate_volume_mesh(front, params, no_progress());
  ASSERT_FALSE(result.ok()) << "closes within the share: give it less";
  EXPECT_EQ(result.status().code(), absl::StatusCode::kFailedPrecondition);
  const std::string message(result.status().message());
  EXPECT_NE(message.find("did not close within its budget"), std::string::npos) << message;
  EXPECT_NE(message.find("over 3 times the first run's budget"), std::string::npos) << message;
}

}  // namespace
}  // namespace afmesh
