// Delaunay3 and delaunay_tetrahedralise (core/delaunay/delaunay_3d.h): checked against the
// invariants of a Delaunay tetrahedralisation: every element positive, the elements tiling the
// convex hull (volumes add up, each inner face shared by two elements turned opposite ways),
// no point strictly inside an element's circumsphere; on random, grid (degenerate: many points
// on one sphere, four on one plane), repeated and far-from-origin points.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <span>
#include <random>
#include <vector>

#include "core/delaunay/delaunay_3d.h"
#include "core/geometry/predicates.h"
#include "core/quality/measures.h"
#include "core/quality/mesh_topology.h"

namespace afmesh {
namespace {

std::vector<Point> cube_corners(const Point& lo, double side) {
  std::vector<Point> p;
  for (int k = 0; k < 8; ++k)
    p.push_back({lo[0] + side * (k & 1), lo[1] + side * (k >> 1 & 1), lo[2] + side * (k >> 2 & 1)});
  return p;
}

std::vector<Point> random_points(int n, const Point& lo, double side, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<Point> p;
  for (int i = 0; i < n; ++i)
    p.push_back({lo[0] + side * u(rng), lo[1] + side * u(rng), lo[2] + side * u(rng)});
  return p;
}

// Every element positive; their volumes add up to `hull_volume` (to 1e-9 of it); every face is
// shared by at most two elements, turned opposite ways. Returns the number of faces of one
// element only (the hull's).
std::int64_t expect_tiling(const std::vector<Point>& p, const std::vector<Tet>& tets,
                           double hull_volume) {
  double volume = 0;
  for (const Tet& t : tets) {
    EXPECT_GT(orient3d(p[t[0]], p[t[1]], p[t[2]], p[t[3]]), 0);
    // Measured from the first point: far from the origin, coordinates' rounding would swamp it.
    const auto local = [&](Index v) { return Point{p[v][0] - p[0][0], p[v][1] - p[0][1],
                                                   p[v][2] - p[0][2]}; };
    volume += tet_signed_volume(local(t[0]), local(t[1]), local(t[2]), local(t[3]));
  }
  EXPECT_NEAR(volume, hull_volume, 1e-9 * hull_volume);
  std::vector<Index> all(tets.size());
  std::iota(all.begin(), all.end(), 0);
  std::int64_t hull_faces = 0;
  for_each_tet_face(tets, all, [&](std::span<const FaceUse> uses) {
    EXPECT_LE(uses.size(), 2u);
    if (uses.size() == 2) EXPECT_NE(uses[0].even, uses[1].even) << "two elements on one side";
    hull_faces += uses.size() == 1;
  });
  return hull_faces;
}

// No point lies strictly inside an element's circumsphere (points on it are allowed: the
// perturbation chose among the tied tetrahedralisations).
void expect_empty_spheres(const std::vector<Point>& p, const std::vector<Tet>& tets) {
  int violations = 0;
  for (const Tet& t : tets)
    for (std::size_t q = 0; q < p.size(); ++q) {
      if (has_corner(t, static_cast<Index>(q))) continue;
      violations += insphere(p[t[0]], p[t[1]], p[t[2]], p[t[3]], p[q]) > 0;
    }
  EXPECT_EQ(violations, 0);
}

TEST(Delaunay3, RandomPointsInACubeTileItWithEmptySpheres) {
  std::vector<Point> p = cube_corners({0, 0, 0}, 1.0);
  const std::vector<Point> inside = random_points(400, {0, 0, 0}, 1.0, 7);
  p.insert(p.end(), inside.begin(), inside.end());
  const absl::StatusOr<DelaunayTets> d = delaunay_tetrahedralise(p);
  ASSERT_TRUE(d.ok()) << d.status();
  EXPECT_GT(d->tets.size(), 5 * p.size());
  const std::int64_t hull = expect_tiling(p, d->tets, 1.0);
  EXPECT_EQ(hull, 12) << "the cube's six faces, two triangles each";
  expect_empty_spheres(p, d->tets);
  for (std::size_t i = 0; i < p.size(); ++i) EXPECT_EQ(d->vertex_of_point[i], Index(i));
}

// A grid: every cell's eight corners lie on one sphere and every face's four on one plane. The
// symbolic perturbation must still give positive elements that tile the cube.
TEST(Delaunay3, AGridsCosphericalPointsTileTheCubeWithNoFlatElement) {
  std::vector<Point> p;
  const int n = 6;
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) p.push_back({i / 5.0, j / 5.0, k / 5.0});
  const absl::StatusOr<DelaunayTets> d = delaunay_tetrahedralise(p);
  ASSERT_TRUE(d.ok()) << d.status();
  const std::int64_t hull = expect_tiling(p, d->tets, 1.0);
  EXPECT_EQ(hull, 6 * 25 * 2);
  expect_empty_spheres(p, d->tets);
  // Every grid point is a vertex of some element.
  std::vector<bool> used(p.size(), false);
  for (const Tet& t : d->tets)
    for (const Index v : t) used[v] = true;
  EXPECT_EQ(std::count(used.begin(), used.end(), true), static_cast<long>(p.size()));
}

TEST(Delaunay3, RepeatedPointsAreOneVertex) {
  std::vector<Point> p = cube_corners({0, 0, 0}, 1.0);
  const std::vector<Point> inside = random_points(50, {0, 0, 0}, 1.0, 3);
  p.insert(p.end(), inside.begin(), inside.end());
  const std::size_t unique = p.size();
  p.push_back(p[3]);
  p.push_back(p[20]);
  p.push_back(p[20]);
  const absl::StatusOr<DelaunayTets> d = delaunay_tetrahedralise(p);
  ASSERT_TRUE(d.ok()) << d.status();
  EXPECT_EQ(d->vertex_of_point[unique], d->vertex_of_point[3]);
  EXPECT_EQ(d->vertex_of_point[unique + 1], d->vertex_of_point[20]);
  EXPECT_EQ(d->vertex_of_point[unique + 2], d->vertex_of_point[20]);
  EXPECT_EQ(p[d->vertex_of_point[unique + 2]], p[20]);
  expect_tiling(p, d->tets, 1.0);
  for (const Tet& t : d->tets)
    for (const Index v : t) EXPECT_EQ(d->vertex_of_point[v], v) << "elements use first copies";
}

// Terrain in UTM lies ~5e6 from the origin: a cube of side 1e-3 there is meshed as at the origin
// (the predicates are exact whatever the coordinates).
TEST(Delaunay3, PointsFarFromTheOriginTileTheirHull) {
  const Point lo{5.0e6, 4.2e6, 1.3e3};
  std::vector<Point> p = cube_corners(lo, 1e-3);
  const std::vector<Point> inside = random_points(200, lo, 1e-3, 11);
  p.insert(p.end(), inside.begin(), inside.end());
  const absl::StatusOr<DelaunayTets> d = delaunay_tetrahedralise(p);
  ASSERT_TRUE(d.ok()) << d.status();
  // The corners' coordinates are rounded to the doubles there (9.3e-10 apart): the box's
  // volume is not quite 1e-9.
  const double volume = (p[7][0] - p[0][0]) * (p[7][1] - p[0][1]) * (p[7][2] - p[0][2]);
  EXPECT_NEAR(volume, 1e-9, 1e-14);
  EXPECT_EQ(expect_tiling(p, d->tets, volume), 12);
  expect_empty_spheres(p, d->tets);
}

TEST(Delaunay3, CoplanarPointsMakeNoElementAndBadPointsAreRefused) {
  std::vector<Point> flat;
  for (int i = 0; i < 30; ++i) flat.push_back({std::cos(i * 0.7) * i, std::sin(i * 0.7) * i, 2.0});
  const absl::StatusOr<DelaunayTets> d = delaunay_tetrahedralise(flat);
  ASSERT_TRUE(d.ok()) << d.status();
  EXPECT_TRUE(d->tets.empty());
  EXPECT_EQ(delaunay_tetrahedralise({{0, 0, 0}, {1, NAN, 0}}).status().code(),
            absl::StatusCode::kInvalidArgument);
  Delaunay3 small(Box{{0, 0, 0}, {1, 1, 1}});
  EXPECT_EQ(small.insert({1e9, 0, 0}).status().code(), absl::StatusCode::kInvalidArgument);
  EXPECT_TRUE(delaunay_tetrahedralise({}).ok());
}

// Many points: the tiling holds (the empty spheres are checked on the smaller sets above).
TEST(Delaunay3, TwentyThousandRandomPointsTileTheirCube) {
  std::vector<Point> p = cube_corners({-1, -1, -1}, 2.0);
  const std::vector<Point> inside = random_points(20000, {-1, -1, -1}, 2.0, 5);
  p.insert(p.end(), inside.begin(), inside.end());
  const absl::StatusOr<DelaunayTets> d = delaunay_tetrahedralise(p);
  ASSERT_TRUE(d.ok()) << d.status();
  EXPECT_EQ(expect_tiling(p, d->tets, 8.0), 12);
}

}  // namespace
}  // namespace afmesh
