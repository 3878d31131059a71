// Background grids: exact linear interpolation, nearest-point sizes outside, the default
// five-tet box grid, and results independent of the walk's start.
#include "core/sizing/background_grid.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <random>
#include <vector>

#include "absl/strings/match.h"
#include "core/geometry/predicates.h"
#include "core/geometry/vec.h"
#include "core/quality/validate.h"
#include "core/shapes/shapes.h"
#include "core/sizing/size_spec.h"

namespace afmesh {
namespace {

// A lattice of n×n×n unit cubes over [0, n]^3, each split into the six Kuhn tets along its main
// diagonal (a conforming grid), with size f(p) at every point.
template <class F>
BackgroundGridSpec kuhn_lattice(int n, F f) {
  BackgroundGridSpec grid;
  const auto id = [n](int i, int j, int k) { return (i * (n + 1) + j) * (n + 1) + k; };
  for (int i = 0; i <= n; ++i)
    for (int j = 0; j <= n; ++j)
      for (int k = 0; k <= n; ++k) {
        grid.points.push_back({double(i), double(j), double(k)});
        grid.sizes.push_back(f(grid.points.back()));
      }
  std::array<int, 3> perm{0, 1, 2};
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j)
      for (int k = 0; k < n; ++k) {
        std::sort(perm.begin(), perm.end());
        do {
          std::array<int, 3> c{i, j, k};
          Tet t;
          t[0] = id(c[0], c[1], c[2]);
          for (int s = 0; s < 3; ++s) {
            ++c[perm[s]];
            t[s + 1] = id(c[0], c[1], c[2]);
          }
          const auto& p = grid.points;
          if (orient3d(p[t[0]], p[t[1]], p[t[2]], p[t[3]]) < 0) std::swap(t[2], t[3]);
          grid.tets.push_back(t);
        } while (std::next_permutation(perm.begin(), perm.end()));
      }
  return grid;
}

double linear(const Point& p) { return 1.0 + 0.3 * p[0] - 0.2 * p[1] + 0.5 * p[2]; }

BackgroundGrid make_grid(const BackgroundGridSpec& spec) {
  absl::StatusOr<BackgroundGrid> grid = BackgroundGrid::from_spec(spec);
  EXPECT_TRUE(grid.ok()) << grid.status();
  return *std::move(grid);
}

TEST(BackgroundGrid, InterpolatesALinearFieldExactly) {
  const BackgroundGrid grid = make_grid(kuhn_lattice(3, linear));
  ASSERT_EQ(grid.tets().size(), 27u * 6u);
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> coord(0.0, 3.0);
  BackgroundGrid::Hint hint;
  for (int i = 0; i < 2000; ++i) {
    const Point x{coord(rng), coord(rng), coord(rng)};
    EXPECT_NEAR(grid.size_at(x, &hint), linear(x), 1e-12 * linear(x));
    EXPECT_NEAR(grid.size_at(x), linear(x), 1e-12 * linear(x));
  }
  // Grid points, points on faces and edges, and on the grid's boundary.
  for (const Point& x : {Point{1, 2, 3}, Point{0, 0, 0}, Point{1.5, 1.5, 1}, Point{3, 0.5, 2.25},
                         Point{2, 2, 0.75}, Point{3, 3, 3}}) {
    EXPECT_NEAR(grid.size_at(x, &hint), linear(x), 1e-12 * linear(x));
  }
}

TEST(BackgroundGrid, LocateFindsAClosedContainingTet) {
  const BackgroundGrid grid = make_grid(kuhn_lattice(3, linear));
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> coord(0.0, 3.0);
  for (int i = 0; i < 500; ++i) {
    const Point x{coord(rng), coord(rng), coord(rng)};
    const Index t = grid.locate(x);
    ASSERT_NE(t, kInvalidIndex);
    const Tet& v = grid.tets()[t];
    const auto& p = grid.points();
    EXPECT_GE(orient3d(x, p[v[1]], p[v[2]], p[v[3]]), 0);
    EXPECT_GE(orient3d(p[v[0]], x, p[v[2]], p[v[3]]), 0);
    EXPECT_GE(orient3d(p[v[0]], p[v[1]], x, p[v[3]]), 0);
    EXPECT_GE(orient3d(p[v[0]], p[v[1]], p[v[2]], x), 0);
  }
}

TEST(BackgroundGrid, ResultDoesNotDependOnTheWalkStart) {
  const BackgroundGrid grid = make_grid(kuhn_lattice(3, [](const Point& p) {
    return 1.0 + p[0] * p[0] + std::sin(p[1]) + 0.1 * p[2];  // not linear: tets differ
  }));
  const std::vector<Point> probes{{1, 1, 1}, {1.5, 1.5, 1}, {2, 1, 0.5}, {0.25, 2.5, 2.5},
                                  {3, 3, 3}, {0, 1.5, 1.5}, {1.2, 1.7, 2.9}};
  for (const Point& x : probes) {
    const double reference = grid.size_at(x);
    const Index tet = grid.locate(x);
    for (Index start = 0; start < static_cast<Index>(grid.tets().size()); start += 7) {
      BackgroundGrid::Hint hint{start};
      EXPECT_EQ(grid.locate(x, &hint), tet);
      hint.tet = start;
      EXPECT_EQ(grid.size_at(x, &hint), reference);
    }
  }
}

TEST(BackgroundGrid, OutsidePointsTakeTheNearestPointsSize) {
  const BackgroundGridSpec spec = kuhn_lattice(2, linear);
  const BackgroundGrid grid = make_grid(spec);
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> coord(-3.0, 5.0);
  int outside = 0;
  for (int i = 0; i < 1000; ++i) {
    const Point x{coord(rng), coord(rng), coord(rng)};
    if (grid.locate(x) != kInvalidIndex) continue;
    ++outside;
    double best = std::numeric_limits<double>::infinity();
    double size = 0.0;
    for (std::size_t p = 0; p < spec.points.size(); ++p) {
      const double d = squared_distance(spec.points[p], x);
      if (d < best) {
        best = d;
        size = spec.sizes[p];
      }
    }
    EXPECT_EQ(grid.size_at(x), size);
  }
  EXPECT_GT(outside, 500);
}

// See Regression.Issue12PointsTooFarForSquaredDistancesStillHaveANearest: size_at read
// sizes()[-1] at such a point.
TEST(Regression, Issue12SizeAtAPointTooFarForSquaredDistancesIsAGridSize) {
  const BackgroundGridSpec spec = kuhn_lattice(2, linear);
  const BackgroundGrid grid = make_grid(spec);
  EXPECT_EQ(grid.size_at({-3.1e231, 0.0, 0.0}), spec.sizes[0]);
}

TEST(BackgroundGrid, BoxGridIsFivePositiveTetsFillingTheBox) {
  const Box box{{-1, 0, 2}, {3, 1, 4.5}};
  const BackgroundGrid grid = BackgroundGrid::box_grid(box, 0.8);
  ASSERT_EQ(grid.points().size(), 8u);
  ASSERT_EQ(grid.tets().size(), 5u);
  double volume = 0.0;
  for (const Tet& t : grid.tets()) {
    const auto& p = grid.points();
    const double six_v = orient3d_fast(p[t[0]], p[t[1]], p[t[2]], p[t[3]]);
    EXPECT_GT(six_v, 0.0);
    volume += six_v / 6.0;
  }
  EXPECT_NEAR(volume, 4.0 * 1.0 * 2.5, 1e-12);
  std::mt19937 rng(2);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (int i = 0; i < 200; ++i) {
    const Point x{-1 + 4 * u(rng), u(rng), 2 + 2.5 * u(rng)};
    EXPECT_NE(grid.locate(x), kInvalidIndex);
    EXPECT_EQ(grid.size_at(x), 0.8);
  }
  EXPECT_EQ(grid.size_at({100, -50, 7}), 0.8);
}

TEST(BackgroundGrid, FromArraysRejectsBadGridsNamingTheField) {
  const BackgroundGridSpec good = kuhn_lattice(1, linear);
  {
    auto tets = good.tets;
    tets[2][1] = 99;
    const auto grid = BackgroundGrid::from_arrays(good.points, tets, good.sizes);
    EXPECT_EQ(grid.status().message(), "background.tets[2][1] = 99 is out of range [0, 8)");
  }
  {
    auto tets = good.tets;
    std::swap(tets[4][2], tets[4][3]);
    const auto grid = BackgroundGrid::from_arrays(good.points, tets, good.sizes);
    EXPECT_TRUE(absl::StrContains(grid.status().message(), "background.tets[4] is inverted"));
  }
  {
    auto sizes = good.sizes;
    sizes.pop_back();
    const auto grid = BackgroundGrid::from_arrays(good.points, good.tets, sizes);
    EXPECT_EQ(grid.status().message(),
              "background.sizes must hold one size per point: got 7 sizes for 8 points");
  }
}

}  // namespace
}  // namespace afmesh

namespace afmesh {
namespace {

// box_tets (core/shapes), the structured grid the server and CLI tests stream: every tet
// positive, conforming, and filling the box exactly.
TEST(BoxTets, IsAValidConformingGridFillingTheBox) {
  const Mesh grid = box_tets({-1, 0, 2}, {2, 1, 3.5}, 3);
  ASSERT_EQ(grid.points.size(), 64u);
  ASSERT_EQ(grid.tets.size(), 6u * 27u);
  const ValidationReport report = validate_volume_mesh(grid);
  EXPECT_TRUE(report.valid()) << report.to_string();
  double volume = 0.0;
  for (const Tet& t : grid.tets) {
    const Point& a = grid.points[t[0]];
    const Point ab = sub(grid.points[t[1]], a), ac = sub(grid.points[t[2]], a),
                ad = sub(grid.points[t[3]], a);
    volume += dot(ab, cross(ac, ad)) / 6.0;
  }
  EXPECT_NEAR(volume, 3.0 * 1.0 * 1.5, 1e-12);
  const BackgroundGridSpec spec{.points = grid.points, .tets = grid.tets,
                                .sizes = std::vector<double>(grid.points.size(), 1.0)};
  EXPECT_TRUE(validate_background_grid(spec).ok());
}

}  // namespace
}  // namespace afmesh
