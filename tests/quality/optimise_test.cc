// Tests of the tet optimiser: the ring triangulation programme, edge removal, edge contraction
// and edge split on hand-built rings, the flat tet across a boundary quad, and invariants on
// meshed solids (valid, boundary unchanged, fixed points unmoved, worst element never worse,
// deterministic).
#include "core/quality/optimise.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <functional>
#include <limits>
#include <numbers>
#include <string>

#include "core/delaunay/delaunay_3d.h"
#include "core/geometry/predicates.h"
#include "core/quality/measures.h"
#include "core/quality/mesh_topology.h"
#include "core/quality/optimise_steps.h"
#include "core/quality/ring_triangulation.h"
#include "core/quality/validate.h"
#include "core/shapes/shapes.h"
#include "core/volume/generate_volume_mesh.h"
#include "tests/quality/test_meshes.h"

namespace afmesh {
namespace {

constexpr double kNone = -std::numeric_limits<double>::infinity();

// ---------------------------------------------------------------------------------------------
// Helpers.

double worst_sine(const Mesh& m) {
  double worst = std::numeric_limits<double>::infinity();
  for (const Tet& t : m.tets) worst = std::min(worst, tet_min_sine(m.points, t));
  return worst;
}

double worst_dihedral(const Mesh& m) {
  double worst = 180;
  for (const Tet& t : m.tets) worst = std::min(worst, tet_quality(m.points, t).min_dihedral_deg);
  return worst;
}

std::int64_t count_below(const Mesh& m, double degrees) {
  std::int64_t n = 0;
  for (const Tet& t : m.tets) n += tet_quality(m.points, t).min_dihedral_deg < degrees;
  return n;
}

// The faces of exactly one tet, outward, as a surface over the same points.
Mesh boundary_of(const Mesh& m) {
  std::vector<Index> ids(m.tets.size());
  for (std::size_t i = 0; i < ids.size(); ++i) ids[i] = static_cast<Index>(i);
  return testing::surface_mesh(m.points,
                               collect_boundary_faces(m.tets, sorted_face_uses(m.tets, ids))
                                   .triangles);
}

// A valid mesh of `boundary` whose worst tet beats `before` (tet_min_sine).
void expect_valid_and_better(const Mesh& m, const Mesh& boundary, double before) {
  EXPECT_GT(worst_sine(m), before);
  const ValidationReport report = validate_volume_mesh(m, &boundary);
  EXPECT_TRUE(report.valid()) << report.to_string();
}

bool has_edge(const Mesh& m, Index a, Index b) {
  for (const Tet& t : m.tets)
    if (std::count(t.begin(), t.end(), a) + std::count(t.begin(), t.end(), b) == 2) return true;
  return false;
}

// The largest smallest quality over all triangulations of the polygon i, i+1, .., j (brute
// force over every apex of the base (i, j)).
double exhaustive_best(int i, int j, const std::function<double(int, int, int)>& quality) {
  if (j - i < 2) return std::numeric_limits<double>::infinity();
  double best = kNone;
  for (int k = i + 1; k < j; ++k)
    best = std::max(best, std::min({quality(i, k, j), exhaustive_best(i, k, quality),
                                    exhaustive_best(k, j, quality)}));
  return best;
}

// A fixed pseudo-random quality per triangle, some triangles unusable.
double scrambled_quality(int i, int j, int k) {
  const std::uint32_t h = (static_cast<std::uint32_t>(i * 73 + j * 151 + k * 283) * 2654435761u) >> 8;
  if (h % 7 == 0) return kNone;
  return static_cast<double>(h % 1000) / 1000.0;
}

// The kite ring: edge a = (0, 0, -2) -> b = (0, 0, 2) (points 0, 1) through the quadrilateral
// r0..r3 = (2, 0, 0), (0, 1, 0), (-2, 0, 0), (0, -1, 0) (points 2..5), four tets
// (a, b, r_i, r_{i+1}) with smallest sine 1/sqrt(3) = 0.577. Of the two triangulations of the
// ring, the one along the long diagonal r0-r2 (which passes through the edge a-b) keeps that
// worst, 0.577; the one along the short diagonal r1-r3 (points 3, 5) raises it to 0.913.
Mesh kite_ring() {
  return testing::tet_mesh(
      {{0, 0, -2}, {0, 0, 2}, {2, 0, 0}, {0, 1, 0}, {-2, 0, 0}, {0, -1, 0}},
      {{0, 1, 2, 3}, {0, 1, 3, 4}, {0, 1, 4, 5}, {0, 1, 5, 2}});
}

// A square pyramid whose base is folded along its diagonal p-r (points 0, 2) so that the other
// diagonal q-s (points 1, 3) runs just inside the solid: the flat tet (p, q, r, s) lies across
// the base "quad", its two boundary faces are the base triangles (p, q, r), (p, r, s), and its
// two other faces share the interior edge q-s with the tets up to the apex e (point 4).
Mesh folded_pyramid(double fold) {
  return testing::tet_mesh(
      {{0, 0, 0}, {1, 0, fold}, {1, 1, 0}, {0, 1, fold}, {0.5, 0.5, 1}},
      {{0, 1, 2, 3}, {1, 3, 0, 4}, {3, 1, 2, 4}});
}

// The unit cube's corners (points 0..7) and two interior points 0.02 apart (8 and 9),
// tetrahedralised by Delaunay: the tets on the short edge (8, 9) are wedges whose faces on it
// nearly coincide (dihedral angles near 0 at the edges opposite it), and every triangulation of
// an edge's ring that separates 8 from 9 is as flat.
Mesh cube_with_two_points_together() {
  std::vector<Point> points = testing::unit_cube_points();
  points.push_back({0.5, 0.5, 0.49});
  points.push_back({0.5, 0.5, 0.51});
  const absl::StatusOr<DelaunayTets> d = delaunay_tetrahedralise(points);
  EXPECT_TRUE(d.ok()) << d.status();
  return testing::tet_mesh(points, d.ok() ? d->tets : std::vector<Tet>{});
}

Mesh meshed_without_optimisation(const Mesh& front, double h) {
  VolumeParams params;
  params.size = h;
  params.optimise = false;
  absl::StatusOr<VolumeResult> result = generate_volume_mesh(front, params, no_progress());
  EXPECT_TRUE(result.ok()) << result.status();
  return result.ok() ? result->mesh : Mesh{};
}

// ---------------------------------------------------------------------------------------------
// The ring triangulation programme.

TEST(Optimise, MinSineOfTheRegularTetIsSinOfItsDihedralAngle) {
  const Point a{1, 1, 1}, b{1, -1, -1}, c{-1, 1, -1}, d{-1, -1, 1};
  const double s = tet_min_sine(b, a, c, d);  // positive orientation
  EXPECT_NEAR(s, std::sin(std::acos(1.0 / 3.0)), 1e-12);
  EXPECT_NEAR(tet_min_sine(a, b, c, d), -s, 1e-12);  // inverted: negative
  EXPECT_EQ(tet_min_sine({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}), 0.0);  // flat
}

TEST(RingTriangulation, MatchesExhaustiveSearch) {
  for (int n = 3; n <= 9; ++n) {
    int calls = 0;
    const RingTriangulation best = best_ring_triangulation(n, [&](int i, int j, int k) {
      ++calls;
      EXPECT_TRUE(0 <= i && i < j && j < k && k < n) << i << " " << j << " " << k;
      return scrambled_quality(i, j, k);
    });
    const double expected = exhaustive_best(0, n - 1, scrambled_quality);
    EXPECT_EQ(best.quality, expected) << "n = " << n;
    EXPECT_LE(calls, n * (n - 1) * (n - 2) / 6);
    if (expected == kNone) {
      EXPECT_TRUE(best.triangles.empty());
      continue;
    }
    // n - 2 triangles whose worst is the reported quality and that use every ring edge once.
    ASSERT_EQ(best.triangles.size(), static_cast<std::size_t>(n - 2)) << "n = " << n;
    double worst = std::numeric_limits<double>::infinity();
    std::vector<int> ring_edges(n, 0);
    for (const auto& [i, j, k] : best.triangles) {
      worst = std::min(worst, scrambled_quality(i, j, k));
      for (auto [u, v] : {std::pair{i, j}, std::pair{j, k}, std::pair{i, k}})
        if (v == u + 1) ++ring_edges[u];
        else if (u == 0 && v == n - 1) ++ring_edges[n - 1];
    }
    EXPECT_EQ(worst, best.quality);
    for (int e = 0; e < n; ++e) EXPECT_EQ(ring_edges[e], 1) << "n = " << n << ", edge " << e;
  }
}

TEST(RingTriangulation, NoUsableTriangulationGivesNone) {
  const RingTriangulation best =
      best_ring_triangulation(5, [](int i, int, int) { return i == 0 ? kNone : 1.0; });
  // Corner 0 is in a triangle of every triangulation, and every triangle (0, j, k) is unusable.
  EXPECT_EQ(best.quality, kNone);
  EXPECT_TRUE(best.triangles.empty());
  EXPECT_EQ(best_ring_triangulation(2, [](int, int, int) { return 1.0; }).quality, kNone);
}

// ---------------------------------------------------------------------------------------------
// Edge removal, edge split, and the flat tet across a boundary quad.

TEST(EdgeRemoval, KiteRingIsRetriangulatedAlongItsShortDiagonal) {
  Mesh m = kite_ring();
  const Mesh boundary = boundary_of(m);
  const double before = worst_sine(m);
  absl::StatusOr<TetComplex> c = TetComplex::build(m);
  ASSERT_TRUE(c.ok()) << c.status();
  EdgeRing ring;
  TopologyChange change;
  ASSERT_TRUE(propose_edge_removal(*c, 0, 0, 1, 7, ring, change));
  EXPECT_EQ(ring.ring, (std::vector<Index>{2, 3, 4, 5}));
  ASSERT_EQ(change.fresh.size(), 4u);
  for (const Tet& t : change.fresh) {
    EXPECT_EQ(std::count(t.begin(), t.end(), 3) + std::count(t.begin(), t.end(), 5), 2);
    EXPECT_GT(orient3d(m.points[t[0]], m.points[t[1]], m.points[t[2]], m.points[t[3]]), 0);
  }
  std::vector<Index> created;
  ASSERT_TRUE(c->replace(change.old, change.fresh, created));
  c->compact();
  EXPECT_FALSE(has_edge(m, 0, 1));
  EXPECT_NEAR(before, 1 / std::sqrt(3.0), 1e-12);
  EXPECT_NEAR(change.quality, 0.9129, 1e-4);
  EXPECT_NEAR(worst_sine(m), change.quality, 1e-12);
  const ValidationReport report = validate_volume_mesh(m, &boundary);
  EXPECT_TRUE(report.valid()) << report.to_string();
}

TEST(Optimise, FlatTetAcrossABoundaryQuadIsRemovedAndTheBoundaryKept) {
  Mesh m = folded_pyramid(1e-3);
  const Mesh boundary = boundary_of(m);
  ASSERT_EQ(boundary.triangles.size(), 6u);  // 2 base triangles and 4 sides
  ASSERT_LT(worst_dihedral(m), 1.0);
  const absl::StatusOr<OptimiseStats> stats =
      optimise_tets(m, /*fixed_points=*/5, OptimiseParams{}, no_progress());
  ASSERT_TRUE(stats.ok()) << stats.status();
  EXPECT_EQ(stats->edge_removals, 1);
  EXPECT_FALSE(has_edge(m, 1, 3));
  EXPECT_EQ(m.tets.size(), 2u);
  EXPECT_GT(worst_dihedral(m), 20.0);
  const ValidationReport report = validate_volume_mesh(m, &boundary);
  EXPECT_TRUE(report.valid()) << report.to_string();
  EXPECT_EQ(m.points, boundary.points);
}

TEST(EdgeSplit, SplitOfTheFoldedDiagonalKeepsTheBoundary) {
  Mesh m = folded_pyramid(1e-3);
  const Mesh boundary = boundary_of(m);
  const double before = worst_sine(m);
  absl::StatusOr<TetComplex> c = TetComplex::build(m);
  ASSERT_TRUE(c.ok()) << c.status();
  EdgeSplit split;
  ASSERT_TRUE(propose_edge_split(*c, 0, 1, 3, 7, split));
  EXPECT_EQ(m.points.size(), 5u);  // proposing leaves no point behind
  EXPECT_GT(split.quality, before);
  SmoothingScratch scratch;
  std::vector<Index> created;
  ASSERT_TRUE(make_edge_split(*c, split, /*fixed_points=*/5, scratch, created));
  EXPECT_EQ(created.size(), 6u);
  c->compact();
  ASSERT_EQ(m.points.size(), 6u);
  EXPECT_FALSE(has_edge(m, 1, 3));
  for (const Tet& t : m.tets)
    EXPECT_GT(orient3d(m.points[t[0]], m.points[t[1]], m.points[t[2]], m.points[t[3]]), 0);
  expect_valid_and_better(m, boundary, before);
}

TEST(EdgeContraction, WedgesOnAShortEdgeGoWithOneOfItsPoints) {
  Mesh m = cube_with_two_points_together();
  const Mesh boundary = boundary_of(m);
  const double before = worst_sine(m);
  ASSERT_LT(before, std::sin(5.0 * std::numbers::pi / 180.0));
  absl::StatusOr<TetComplex> c = TetComplex::build(m);
  ASSERT_TRUE(c.ok()) << c.status();
  std::vector<Index> around;  // the tets on the edge (8, 9)
  for (Index t = 0; t < static_cast<Index>(m.tets.size()); ++t)
    if (has_corner(m.tets[t], 8) && has_corner(m.tets[t], 9)) around.push_back(t);
  ASSERT_GE(around.size(), 3u);
  const Index t = around[0];
  std::vector<Index> ball;
  TopologyChange change;
  // With fixed_points = 9, point 8 is fixed: it stays.
  EXPECT_FALSE(propose_edge_contraction(*c, t, 9, 8, /*fixed_points=*/9, ball, change));
  ASSERT_TRUE(propose_edge_contraction(*c, t, 8, 9, /*fixed_points=*/8, ball, change));
  EXPECT_GT(change.quality, before);
  EXPECT_EQ(change.old.size(), change.fresh.size() + around.size());
  std::vector<Index> created;
  EXPECT_FALSE(c->replace(change.old, change.fresh, created));  // point 9 left unused
  ASSERT_TRUE(c->replace(change.old, change.fresh, created, false, /*dropped=*/9));
  c->compact();
  ASSERT_EQ(m.points.size(), 9u);
  EXPECT_EQ(m.points[8], (Point{0.5, 0.5, 0.49}));
  expect_valid_and_better(m, boundary, before);
}

TEST(Optimise, ContractsAShortEdgeNoFlipCanMend) {
  Mesh m = cube_with_two_points_together();
  const Mesh boundary = boundary_of(m);
  const double before = worst_sine(m);
  OptimiseParams params;
  params.smoothing = false;  // smoothing alone would pull the two points apart
  params.smoothing_sweeps = 0;
  const absl::StatusOr<OptimiseStats> stats =
      optimise_tets(m, /*fixed_points=*/8, params, no_progress());
  ASSERT_TRUE(stats.ok()) << stats.status();
  EXPECT_GE(stats->edge_contractions, 1);
  EXPECT_EQ(m.points.size(), 10u + stats->edge_splits - stats->edge_contractions);
  EXPECT_GT(worst_dihedral(m), 20.0);
  expect_valid_and_better(m, boundary, before);
}

TEST(Optimise, BadInputIsNamed) {
  Mesh m = testing::two_tet_mesh();
  m.tets[1][2] = 9;
  const absl::StatusOr<OptimiseStats> stats = optimise_tets(m, 0, OptimiseParams{}, no_progress());
  ASSERT_FALSE(stats.ok());
  EXPECT_EQ(stats.status().code(), absl::StatusCode::kInvalidArgument);
  EXPECT_NE(stats.status().message().find("tet 1"), std::string::npos) << stats.status();
}

// ---------------------------------------------------------------------------------------------
// Meshed solids.

struct Solid {
  std::string name;
  Mesh front;
  double h;
};

std::vector<Solid> solids() {
  return {{"sphere", sphere_surface({0, 0, 0}, 1.0, 0.25), 0.25},
          {"torus", torus_surface(1.0, 0.35, 0.15), 0.15},
          {"cube", box_surface({0, 0, 0}, {1, 1, 1}, 0.15), 0.15},
          {"lblock", l_block_with_hole_surface(0.5, 0.15), 0.15}};
}

TEST(Optimise, MeshedSolidsStayValidWithTheirBoundaryAndImprove) {
  for (const Solid& s : solids()) {
    SCOPED_TRACE(s.name);
    const Mesh raw = meshed_without_optimisation(s.front, s.h);
    ASSERT_FALSE(raw.tets.empty());
    Mesh m = raw;
    const auto fixed = static_cast<Index>(s.front.points.size());
    const absl::StatusOr<OptimiseStats> stats =
        optimise_tets(m, fixed, OptimiseParams{}, no_progress());
    ASSERT_TRUE(stats.ok()) << stats.status();
    const ValidationReport report = validate_volume_mesh(m, &s.front);
    EXPECT_TRUE(report.valid()) << report.to_string();
    for (Index p = 0; p < fixed; ++p)
      EXPECT_EQ(m.points[p], raw.points[p]) << "fixed point " << p << " moved";
    // Every change raises the worst tet it touches, so the mesh's worst never drops.
    EXPECT_GE(worst_sine(m), worst_sine(raw));
    EXPECT_LE(count_below(m, 20), count_below(raw, 20));
    EXPECT_GT(worst_dihedral(m), 10.0);
  }
}

TEST(Optimise, SameInputGivesTheSameMesh) {
  const Solid s = solids()[1];
  const Mesh raw = meshed_without_optimisation(s.front, s.h);
  Mesh first = raw, second = raw;
  const auto fixed = static_cast<Index>(s.front.points.size());
  ASSERT_TRUE(optimise_tets(first, fixed, OptimiseParams{}, no_progress()).ok());
  ASSERT_TRUE(optimise_tets(second, fixed, OptimiseParams{}, no_progress()).ok());
  EXPECT_EQ(first.points, second.points);  // bit for bit
  EXPECT_EQ(first.tets, second.tets);
  EXPECT_EQ(first.tet_tags, second.tet_tags);
}

}  // namespace
}  // namespace afmesh
