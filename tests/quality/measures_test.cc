// Tests of element quality measures and the mesh quality summary, against hand-computed values.
#include "core/quality/measures.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <vector>

#include "tests/quality/test_meshes.h"

namespace afmesh {
namespace {

constexpr double kTol = 1e-12;

double deg(double radians) { return radians * 180.0 / std::numbers::pi; }

TEST(TetQuality, RegularTetHasEqualDihedralsAndUnitRadiusRatio) {
  const TetQuality q = tet_quality({1, 1, 1}, {-1, 1, -1}, {1, -1, -1}, {-1, -1, 1});
  const double expected = deg(std::acos(1.0 / 3.0));  // 70.528779...
  EXPECT_NEAR(q.min_dihedral_deg, expected, kTol);
  EXPECT_NEAR(q.max_dihedral_deg, expected, kTol);
  EXPECT_NEAR(q.radius_ratio, 1.0, kTol);
  // Edge a = 2√2: volume a^3 / (6√2) = 8/3, positive in this vertex order.
  EXPECT_NEAR(q.volume, 8.0 / 3.0, kTol);
}

// Corner tet (0,0,0), e_x, e_y, e_z: three right dihedrals at the origin's edges, and
// acos(1/√3) at the edges of the slanted face. r_in = 1/(3+√3), r_circ = √3/2, so
// 3 r_in / r_circ = √3 - 1.
TEST(TetQuality, RightCornerTetMatchesHandComputedValues) {
  const TetQuality q = tet_quality({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1});
  EXPECT_NEAR(q.min_dihedral_deg, deg(std::acos(1.0 / std::sqrt(3.0))), kTol);  // 54.7356°
  EXPECT_NEAR(q.max_dihedral_deg, 90.0, kTol);
  EXPECT_NEAR(q.radius_ratio, std::sqrt(3.0) - 1.0, kTol);
  EXPECT_NEAR(q.volume, 1.0 / 6.0, kTol);
}

TEST(TetQuality, InvertedTetHasNegativeVolumeAndSameShapeMeasures) {
  const TetQuality positive = tet_quality({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1});
  const TetQuality inverted = tet_quality({0, 0, 0}, {0, 1, 0}, {1, 0, 0}, {0, 0, 1});
  EXPECT_NEAR(inverted.volume, -1.0 / 6.0, kTol);
  EXPECT_NEAR(inverted.min_dihedral_deg, positive.min_dihedral_deg, kTol);
  EXPECT_NEAR(inverted.max_dihedral_deg, positive.max_dihedral_deg, kTol);
  EXPECT_NEAR(inverted.radius_ratio, positive.radius_ratio, kTol);
}

TEST(TetQuality, NearlyFlatSliverHasRatioNearZeroAndExtremeDihedrals) {
  const TetQuality q = tet_quality({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 1e-6});
  EXPECT_GT(std::abs(q.volume), 0.0);
  EXPECT_LT(q.radius_ratio, 1e-5);
  EXPECT_LT(q.min_dihedral_deg, 1e-3);
  EXPECT_GT(q.max_dihedral_deg, 180.0 - 1e-3);
}

TEST(TetQuality, FlatTetHasZeroVolumeAndZeroRatio) {
  const TetQuality q = tet_quality({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0});
  EXPECT_EQ(q.volume, 0.0);
  EXPECT_EQ(q.radius_ratio, 0.0);
  EXPECT_NEAR(q.min_dihedral_deg, 0.0, kTol);
  EXPECT_NEAR(q.max_dihedral_deg, 180.0, kTol);
}

TEST(TetQuality, CoincidentPointsGiveZeroRatioAndNoNaN) {
  const TetQuality q = tet_quality({0, 0, 0}, {0, 0, 0}, {0, 1, 0}, {0, 0, 1});
  EXPECT_EQ(q.volume, 0.0);
  EXPECT_EQ(q.radius_ratio, 0.0);
  EXPECT_FALSE(std::isnan(q.min_dihedral_deg));
  EXPECT_FALSE(std::isnan(q.max_dihedral_deg));
}

TEST(TetQuality, IndexedOverloadEqualsPointOverload) {
  const std::vector<Point> points = {{0, 0, 0}, {2, 0, 0}, {0.3, 1.5, 0}, {0.2, 0.4, 0.9}};
  const TetQuality a = tet_quality(points, Tet{0, 1, 2, 3});
  const TetQuality b = tet_quality(points[0], points[1], points[2], points[3]);
  EXPECT_EQ(a.min_dihedral_deg, b.min_dihedral_deg);
  EXPECT_EQ(a.radius_ratio, b.radius_ratio);
  EXPECT_EQ(a.volume, b.volume);
  EXPECT_NEAR(tet_signed_volume(points[0], points[1], points[2], points[3]), 2 * 1.5 * 0.9 / 6,
              kTol);
}

// Dihedral angle (degrees) at edge (a, b) of a tet whose other corners are c and d: the angle
// between c and d seen along the edge, computed apart from tet_quality's face normals.
double dihedral_at_edge(const Point& a, const Point& b, const Point& c, const Point& d) {
  auto sub = [](const Point& x, const Point& y) {
    return std::array<double, 3>{x[0] - y[0], x[1] - y[1], x[2] - y[2]};
  };
  auto dot = [](const std::array<double, 3>& x, const std::array<double, 3>& y) {
    return x[0] * y[0] + x[1] * y[1] + x[2] * y[2];
  };
  const std::array<double, 3> e = sub(b, a);
  auto across = [&](const Point& p) {  // p - a without its component along the edge
    std::array<double, 3> v = sub(p, a);
    const double t = dot(v, e) / dot(e, e);
    for (int k = 0; k < 3; ++k) v[k] -= t * e[k];
    return v;
  };
  const std::array<double, 3> u = across(c), w = across(d);
  const std::array<double, 3> cross = {u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2],
                                       u[0] * w[1] - u[1] * w[0]};
  return deg(std::atan2(std::sqrt(dot(cross, cross)), dot(u, w)));
}

// tet_quality ranks the six dihedral angles and evaluates only the extremes: they must be the
// smallest and largest of all six, wherever they sit, also for slivers and caps whose extremes
// are close to 0 and 180 degrees and close to each other.
TEST(TetQuality, ExtremeDihedralsAreTheSmallestAndLargestOfAllSix) {
  const std::vector<std::array<Point, 4>> shapes = {
      {Point{0, 0, 0}, Point{1, 0, 0}, Point{0, 1, 0}, Point{0.2, 0.3, 1}},
      {Point{0, 0, 0}, Point{1, 0, 0}, Point{0, 1, 0}, Point{1, 1, 1e-5}},      // sliver
      {Point{0, 0, 0}, Point{1, 0, 0}, Point{0, 1, 0}, Point{1, 1.001, 2e-5}},  // near-tie sliver
      {Point{0, 0, 0}, Point{1, 0, 0}, Point{0.5, 1, 0}, Point{0.5, 0.3, 1e-4}},  // cap
      {Point{0, 0, 0}, Point{1e-3, 0, 0}, Point{0, 1e-3, 0}, Point{0, 0, 10}},    // needle
      {Point{0, 0, 0}, Point{3, 0.1, 0}, Point{0.2, 2, 0.1}, Point{0.1, 0.3, 0.7}},
  };
  // Every order of the corners, so that each extreme is met at every edge position.
  std::array<int, 4> order = {0, 1, 2, 3};
  for (const std::array<Point, 4>& shape : shapes) {
    do {
      const Point& a = shape[order[0]];
      const Point& b = shape[order[1]];
      const Point& c = shape[order[2]];
      const Point& d = shape[order[3]];
      const std::array<double, 6> all = {
          dihedral_at_edge(a, b, c, d), dihedral_at_edge(a, c, b, d), dihedral_at_edge(a, d, b, c),
          dihedral_at_edge(b, c, a, d), dihedral_at_edge(b, d, a, c), dihedral_at_edge(c, d, a, b)};
      const double lowest = *std::min_element(all.begin(), all.end());
      const double highest = *std::max_element(all.begin(), all.end());
      const TetQuality q = tet_quality(a, b, c, d);
      EXPECT_NEAR(q.min_dihedral_deg, lowest, 1e-7 * lowest + 1e-12)
          << order[0] << order[1] << order[2] << order[3];
      EXPECT_NEAR(q.max_dihedral_deg, highest, 1e-9 * highest)
          << order[0] << order[1] << order[2] << order[3];
    } while (std::next_permutation(order.begin(), order.end()));
  }
}

TEST(TriangleQuality, EquilateralTriangleHasSixtyDegreesAndUnitRatio) {
  const TriangleQuality q = triangle_quality({0, 0, 0}, {1, 0, 0}, {0.5, std::sqrt(3.0) / 2, 0});
  EXPECT_NEAR(q.min_angle_deg, 60.0, kTol);
  EXPECT_NEAR(q.radius_ratio, 1.0, kTol);
  EXPECT_NEAR(q.area, std::sqrt(3.0) / 4, kTol);
}

// Right isosceles triangle with legs 1: angles 45°, 45°, 90°; r_in = 1 - 1/√2,
// r_circ = 1/√2, so 2 r_in / r_circ = 2(√2 - 1).
TEST(TriangleQuality, RightIsoscelesTriangleMatchesHandComputedValues) {
  const TriangleQuality q = triangle_quality({0, 0, 5}, {0, 1, 5}, {1, 0, 5});
  EXPECT_NEAR(q.min_angle_deg, 45.0, kTol);
  EXPECT_NEAR(q.radius_ratio, 2.0 * (std::sqrt(2.0) - 1.0), kTol);
  EXPECT_NEAR(q.area, 0.5, kTol);
}

TEST(TriangleQuality, CollinearAndCoincidentTrianglesHaveZeroRatio) {
  const TriangleQuality flat = triangle_quality({0, 0, 0}, {1, 1, 1}, {3, 3, 3});
  EXPECT_EQ(flat.radius_ratio, 0.0);
  EXPECT_NEAR(flat.min_angle_deg, 0.0, kTol);
  const TriangleQuality pinched = triangle_quality({0, 0, 0}, {0, 0, 0}, {1, 0, 0});
  EXPECT_EQ(pinched.radius_ratio, 0.0);
  EXPECT_EQ(pinched.min_angle_deg, 0.0);
}

TEST(Histogram, CountsEveryValueOnceAndClampsOutOfRange) {
  Histogram h(0.0, 180.0, 18);
  for (double v : {-1.0, 0.0, 9.999, 10.0, 95.0, 179.9, 180.0, 200.0, std::nan("")}) h.add(v);
  EXPECT_EQ(h.total(), 9);
  EXPECT_EQ(h.nan_count, 1);
  EXPECT_EQ(h.counts[0], 3);  // -1 clamped, 0, 9.999
  EXPECT_EQ(h.counts[1], 1);  // 10
  EXPECT_EQ(h.counts[9], 1);  // 95
  EXPECT_EQ(h.counts[17], 3);  // 179.9, 180 and 200 clamped
  EXPECT_DOUBLE_EQ(h.bin_lo(9), 90.0);
}

// The five-tet cube: four right-corner tets of volume 1/6 and the regular central tet of 1/3.
TEST(QualitySummary, FiveTetCubeStatisticsMatchItsElements) {
  Mesh mesh = testing::five_tet_cube();
  mesh.triangles = testing::five_tet_cube_boundary().triangles;
  mesh.triangle_tags.assign(mesh.triangles.size(), 0);
  const absl::StatusOr<QualitySummary> s = summarize_quality(mesh);
  ASSERT_TRUE(s.ok()) << s.status();

  EXPECT_EQ(s->tet_count, 5);
  EXPECT_NEAR(s->tet_min_dihedral_deg.min, deg(std::acos(1.0 / std::sqrt(3.0))), 1e-9);
  EXPECT_NEAR(s->tet_min_dihedral_deg.max, deg(std::acos(1.0 / 3.0)), 1e-9);
  EXPECT_NEAR(s->tet_max_dihedral_deg.max, 90.0, 1e-9);
  EXPECT_NEAR(s->tet_radius_ratio.min, std::sqrt(3.0) - 1.0, 1e-9);
  EXPECT_NEAR(s->tet_radius_ratio.max, 1.0, 1e-9);
  EXPECT_NEAR(s->tet_radius_ratio.mean, (4 * (std::sqrt(3.0) - 1.0) + 1.0) / 5, 1e-9);
  EXPECT_NEAR(s->tet_volume.mean, 1.0 / 5.0, 1e-12);
  EXPECT_EQ(s->tets_with_nonpositive_volume, 0);
  EXPECT_EQ(s->share_min_dihedral_below_10, 0.0);
  EXPECT_EQ(s->share_min_dihedral_below_20, 0.0);

  EXPECT_EQ(s->triangle_count, 12);
  EXPECT_NEAR(s->triangle_min_angle_deg.min, 45.0, 1e-9);
  EXPECT_NEAR(s->triangle_min_angle_deg.max, 45.0, 1e-9);
}

TEST(QualitySummary, HistogramCountsSumToElementCounts) {
  Mesh mesh = testing::five_tet_cube();
  mesh = testing::merge(mesh, testing::translated(testing::six_tet_cube(), {3, 0, 0}));
  mesh.tets.push_back({0, 1, 2, 2});  // degenerate: still counted
  mesh.tet_tags.push_back(0);
  mesh.triangles = testing::octahedron().triangles;
  mesh.triangle_tags.assign(mesh.triangles.size(), 0);
  const absl::StatusOr<QualitySummary> s = summarize_quality(mesh);
  ASSERT_TRUE(s.ok()) << s.status();
  EXPECT_EQ(s->tet_count, 12);
  EXPECT_EQ(s->tet_min_dihedral_hist.total(), 12);
  EXPECT_EQ(s->tet_max_dihedral_hist.total(), 12);
  EXPECT_EQ(s->tet_radius_ratio_hist.total(), 12);
  EXPECT_EQ(s->triangle_min_angle_hist.total(), 8);
  EXPECT_EQ(s->triangle_radius_ratio_hist.total(), 8);
  EXPECT_EQ(s->tets_with_nonpositive_volume, 1);
  EXPECT_NEAR(s->share_min_dihedral_below_10, 1.0 / 12.0, 1e-15);
  EXPECT_EQ(s->tet_radius_ratio_hist.counts.front(), 1);  // the degenerate tet, ratio 0
}

TEST(QualitySummary, ShareBelowThresholdsCountsSlivers) {
  Mesh mesh = testing::tet_mesh(
      {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {1, 1, 0.01}, {1, 1, 0.25}},
      {{0, 1, 2, 3}, {0, 1, 2, 4}, {0, 1, 2, 5}});
  const absl::StatusOr<QualitySummary> s = summarize_quality(mesh);
  ASSERT_TRUE(s.ok()) << s.status();
  // Sliver with apex 0.01 over (1,1): min dihedral < 10°; with apex 0.25: between 10° and 20°.
  const double sliver = tet_quality(mesh.points, mesh.tets[1]).min_dihedral_deg;
  const double flat = tet_quality(mesh.points, mesh.tets[2]).min_dihedral_deg;
  ASSERT_LT(sliver, 10.0);
  ASSERT_GE(flat, 10.0);
  ASSERT_LT(flat, 20.0);
  EXPECT_NEAR(s->share_min_dihedral_below_10, 1.0 / 3.0, 1e-15);
  EXPECT_NEAR(s->share_min_dihedral_below_20, 2.0 / 3.0, 1e-15);
}

TEST(QualitySummary, TetsAwayFromBoundarySliversAreMeasuredApart) {
  Mesh mesh = testing::tet_mesh(
      {// 0-3: a flat tet on the boundary sliver (0, 1, 2), whose angles at 0 and 1 are 0.57°
       {0, 0, 0}, {1, 0, 0}, {0.5, 0.005, 0}, {0.5, 0, 1},
       // 4-6 and 3: a tet that shares a corner with it: near the sliver
       {0.5, 1, 1}, {1.5, 0, 1}, {1, 0.5, 2},
       // 7-10: a regular tet far away; 11-14: a flat one (between 10° and 20°) far away
       {10, 0, 0}, {11, 0, 0}, {10.5, std::sqrt(0.75), 0}, {10.5, std::sqrt(0.75) / 3, std::sqrt(2.0 / 3.0)},
       {20, 0, 0}, {21, 0, 0}, {20, 1, 0}, {21, 1, 0.25}},
      {{0, 1, 2, 3}, {3, 4, 5, 6}, {7, 8, 9, 10}, {11, 12, 13, 14}});
  for (Tet& t : mesh.tets)  // positive, whatever the corners' order above
    if (tet_quality(mesh.points, t).volume < 0) std::swap(t[0], t[1]);
  mesh.triangles = {{0, 2, 1}, {7, 9, 8}};
  mesh.triangle_tags.assign(mesh.triangles.size(), 0);
  const absl::StatusOr<QualitySummary> s = summarize_quality(mesh);
  ASSERT_TRUE(s.ok()) << s.status();
  const double flat = tet_quality(mesh.points, mesh.tets[3]).min_dihedral_deg;
  ASSERT_GE(flat, 10.0);
  ASSERT_LT(flat, 20.0);
  EXPECT_LT(s->tet_min_dihedral_deg.min, 2.0);  // the tet on the sliver
  EXPECT_EQ(s->boundary_slivers, 1);
  EXPECT_NEAR(s->triangle_min_angle_deg.min, deg(std::atan(0.01)), 1e-9);
  EXPECT_EQ(s->tets_away_from_slivers, 2);  // the far ones: not the sliver's nor its neighbour
  EXPECT_NEAR(s->away_min_dihedral_deg.min, flat, 1e-12);
  EXPECT_NEAR(s->away_min_dihedral_deg.max, deg(std::acos(1.0 / 3.0)), 1e-9);
  EXPECT_EQ(s->share_away_below_20, 0.5);

  // Without the sliver every tet is away from one, and the figures are the whole mesh's.
  mesh.triangles = {{7, 9, 8}};
  mesh.triangle_tags = {0};
  const absl::StatusOr<QualitySummary> clean = summarize_quality(mesh);
  ASSERT_TRUE(clean.ok()) << clean.status();
  EXPECT_EQ(clean->boundary_slivers, 0);
  EXPECT_EQ(clean->tets_away_from_slivers, 4);
  EXPECT_EQ(clean->away_min_dihedral_deg.min, clean->tet_min_dihedral_deg.min);
  EXPECT_EQ(clean->share_away_below_20, clean->share_min_dihedral_below_20);
}

TEST(QualitySummary, IsDeterministic) {
  const Mesh mesh = testing::six_tet_cube();
  const QualitySummary a = *summarize_quality(mesh);
  const QualitySummary b = *summarize_quality(mesh);
  EXPECT_EQ(a.tet_radius_ratio.mean, b.tet_radius_ratio.mean);
  EXPECT_EQ(a.tet_min_dihedral_hist.counts, b.tet_min_dihedral_hist.counts);
}

TEST(QualitySummary, EmptyMeshHasZeroCounts) {
  const absl::StatusOr<QualitySummary> s = summarize_quality(Mesh{});
  ASSERT_TRUE(s.ok());
  EXPECT_EQ(s->tet_count, 0);
  EXPECT_EQ(s->tet_volume.count, 0);
  EXPECT_EQ(s->tet_min_dihedral_hist.total(), 0);
}

TEST(QualitySummary, OutOfRangeIndexIsInvalidArgumentNamingTheElement) {
  Mesh mesh = testing::five_tet_cube();
  mesh.tets[3][2] = 42;
  const absl::StatusOr<QualitySummary> s = summarize_quality(mesh);
  ASSERT_FALSE(s.ok());
  EXPECT_EQ(s.status().code(), absl::StatusCode::kInvalidArgument);
  EXPECT_NE(s.status().message().find("tet 3"), std::string_view::npos);
  EXPECT_NE(s.status().message().find("42"), std::string_view::npos);
}

// Two triangles far apart: only the one that comes within the radius counts, with its shortest
// and longest edges and smallest angle; none within gives a count of 0. A long triangle whose
// corners all lie far from the point but which passes by it counts too.
TEST(TrianglesNear, CountsOnlyTrianglesThatComeWithinTheRadius) {
  Mesh m;
  m.points = {{0, 0, 0}, {3, 0, 0}, {0, 4, 0},             // right triangle 3-4-5
              {100, 0, 0}, {101, 0, 0}, {100, 1, 0}};      // far away
  m.triangles = {{0, 1, 2}, {3, 4, 5}};
  const TrianglesNear near = triangles_near(m.points, m.triangles, {3.5, 0, 0}, 1.0);
  EXPECT_EQ(near.count, 1);
  EXPECT_DOUBLE_EQ(near.shortest_edge, 3.0);
  EXPECT_DOUBLE_EQ(near.longest_edge, 5.0);
  EXPECT_NEAR(near.smallest_angle_deg, std::atan2(3.0, 4.0) * 180.0 / std::numbers::pi, 1e-9);
  EXPECT_EQ(triangles_near(m.points, m.triangles, {50, 50, 50}, 1.0).count, 0);
  EXPECT_EQ(triangles_near(m.points, m.triangles, {50, 0, 0}, 100.0).count, 2);
  Mesh passing;
  passing.points = {{-100, 0, 0}, {100, 0, 0}, {0, 1, 0}};
  passing.triangles = {{0, 1, 2}};
  EXPECT_EQ(triangles_near(passing.points, passing.triangles, {0, 0, 0.5}, 1.0).count, 1);
  EXPECT_EQ(triangles_near(passing.points, passing.triangles, {0, 0, 1.5}, 1.0).count, 0);
}

}  // namespace
}  // namespace afmesh
