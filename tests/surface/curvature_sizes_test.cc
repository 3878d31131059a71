// Tests of the sizes from the surface's curvature (curvature_sizes.h, paper §4.4 eq. 20–22): the
// turn is read at the element's scale, so that a sphere asks eq. 21's size, a scan's noise finer
// than the size asks nothing, and a rounding narrower than the size keeps its own size.
#include "core/surface/curvature_sizes.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>
#include <optional>
#include <random>
#include <vector>

#include "core/geometry/vec.h"
#include "core/shapes/shapes.h"
#include "core/sizing/size_field.h"
#include "core/surface/generate_surface_mesh.h"
#include "tests/surface/surface_test_shapes.h"

namespace afmesh {
namespace {

// Eq. 20–21 on a circle of radius r: elements turning by 30° are 2 r tan(15°) long.
double eq21_on_radius(double r) { return 2.0 * r * std::tan(15.0 * std::numbers::pi / 180.0); }

// curvature_point_sizes of a model, never cancelled.
std::vector<double> sizes_of(const testing::SurfaceModel& model, double alpha_p_deg,
                             double deviation, const SizeField& base) {
  absl::StatusOr<std::vector<double>> sizes =
      curvature_point_sizes(model.surface, model.features, alpha_p_deg, deviation, base);
  EXPECT_TRUE(sizes.ok()) << sizes.status();
  return sizes.ok() ? *std::move(sizes) : std::vector<double>{};
}

struct Range {
  double smallest = std::numeric_limits<double>::infinity();
  double largest = 0.0;
  int finite = 0;
};

Range finite_range(const std::vector<double>& sizes) {
  Range r;
  for (const double d : sizes) {
    if (!std::isfinite(d)) continue;
    r.smallest = std::min(r.smallest, d);
    r.largest = std::max(r.largest, d);
    ++r.finite;
  }
  return r;
}

// A unit sphere of faces 0.05 across, where the size in force (1) is over eq. 21's 0.536: every
// point takes about 0.536 (the faces turn by ~3°, and the disks see the same curvature at every
// scale). Then the same sphere with its points moved at random by up to 0.0075 (15% of an edge),
// at a size of 0.15: eq. 21 between neighbouring faces reads the noise as sizes down to 0.032;
// at the element's scale the sphere's curvature is all there
// is, and no point asks for less than 0.15 (eq. 21 between the faces alone: 0.032).
TEST(CurvatureSizes, ASphereAsksEq21AndItsNoiseAsksNothing) {
  const Mesh smooth = sphere_surface({0, 0, 0}, 1.0, 0.05);
  const testing::SurfaceModel model = testing::surface_model(smooth);
  const Range sphere = finite_range(sizes_of(model, 30.0, 0.0,
                                                          UniformSize(1.0)));
  std::printf("sphere: %d points, sizes %.4f to %.4f (eq. 21: %.4f)\n", sphere.finite,
              sphere.smallest, sphere.largest, eq21_on_radius(1.0));
  EXPECT_EQ(sphere.finite, model.surface.point_count());
  EXPECT_GT(sphere.smallest, 0.85 * eq21_on_radius(1.0));
  EXPECT_LT(sphere.smallest, 1.15 * eq21_on_radius(1.0));

  const Mesh noisy = testing::jittered(smooth, 0.0075, 7);
  const testing::SurfaceModel noisy_model = testing::surface_model(noisy);
  const Range noise = finite_range(sizes_of(noisy_model,
                                                         30.0, 0.0, UniformSize(0.15)));
  std::printf("noisy sphere: %zu lines, sizes from %.4f\n", noisy_model.features.lines.size(),
              noise.smallest);
  EXPECT_GE(noise.smallest, 0.15);
}

// A cylinder of radius 0.05 (64 faces round, 0.005 across), 1 long, at a size of 0.5: ten times
// its radius. A disk at the size wraps round it, so the turn is read at smaller scales, down to
// one that fits the rounding: the lateral points take eq. 21 on its radius, 0.027; the rounding is
// not averaged away. (Eq. 21 between the faces alone gave 0.049 here: across the diagonal of a
// side quad, 0.005 × 0.025, the centroids are farther apart than the turn's length.)
TEST(CurvatureSizes, ARoundingNarrowerThanTheSizeKeepsItsSize) {
  const testing::SurfaceModel model =
      testing::surface_model(testing::closed_cylinder(0.05, 1.0, 64, 40));
  const std::vector<double> sizes =
      sizes_of(model, 30.0, 0.0, UniformSize(0.5));
  const std::vector<Point>& p = model.surface.local_points();
  Range lateral;
  for (Index v = 0; v < model.surface.point_count(); ++v) {
    const Point x = model.surface.to_global(p[v]);
    if (std::abs(std::hypot(x[0], x[1]) - 0.05) > 1e-6) continue;  // a cap's centre
    lateral.smallest = std::min(lateral.smallest, sizes[v]);
    lateral.largest = std::max(lateral.largest, sizes[v]);
    ++lateral.finite;
  }
  std::printf("cylinder: %d lateral points, sizes %.4f to %.4f (eq. 21: %.4f)\n", lateral.finite,
              lateral.smallest, lateral.largest, eq21_on_radius(0.05));
  EXPECT_GT(lateral.finite, 64 * 40);
  EXPECT_GT(lateral.smallest, 0.8 * eq21_on_radius(0.05));
  EXPECT_LT(lateral.largest, 1.2 * eq21_on_radius(0.05));
}

// A hole of radius 0.5 faceted as CAD tessellations are (netgen_part1's): 36 facets of 10°, each
// a 0.087 × 2 rectangle halved into two slivers. The slivers' centroids are 0.67 apart but only
// 0.058 across the edge they share, and only that bends: eq. 21 over it asks 0.177 (it reads the
// faces' turn over two thirds of a facet, so a little below eq. 21 on the radius, 0.268). Over
// the centroids' whole distance it asked 2.05, and at part1's size (0.209) elements spanned the
// hole with nothing to stop them (0.24% of the diagonal from the input). The turn is read across
// the edge with a chord bound only; this one (epsilon = 1, sizes of ~1.6) is too loose to bind.
TEST(CurvatureSizes, SliversOfAFacetedHoleTurnAcrossTheirEdge) {
  const testing::SurfaceModel model =
      testing::surface_model(testing::closed_cylinder(0.5, 2.0, 36, 1));
  const std::vector<double> sizes =
      sizes_of(model, 30.0, 1.0, UniformSize(0.209));
  const Range r = finite_range(sizes);
  std::printf("faceted hole: %d points, sizes %.4f to %.4f (eq. 21: %.4f)\n", r.finite,
              r.smallest, r.largest, eq21_on_radius(0.5));
  EXPECT_GE(r.finite, 72);
  EXPECT_GT(r.smallest, 0.5 * eq21_on_radius(0.5));
  EXPECT_LT(r.largest, eq21_on_radius(0.5));
}

// The chord bound alone (no angle bound) on the unit sphere of faces 0.05: every point takes the
// length whose chord's midpoint lies epsilon = 0.001 from the circle, sqrt(8 r epsilon) = 0.089,
// and with both bounds the smaller one (eq. 21's 0.536 is larger).
TEST(CurvatureSizes, TheChordBoundAsksTheLengthOfItsSagitta) {
  const testing::SurfaceModel model = testing::surface_model(sphere_surface({0, 0, 0}, 1.0, 0.05));
  const double chord = std::sqrt(8.0 * 1.0 * 0.001);
  for (const double angle : {0.0, 30.0}) {
    const Range r = finite_range(sizes_of(model, angle,
                                                       0.001, UniformSize(1.0)));
    std::printf("sphere, angle %g, epsilon 0.001: sizes %.4f to %.4f (sqrt(8 r e): %.4f)\n",
                angle, r.smallest, r.largest, chord);
    EXPECT_EQ(r.finite, model.surface.point_count());
    EXPECT_GT(r.smallest, 0.85 * chord);
    EXPECT_LT(r.largest, 1.15 * chord);
  }
}

// A line's own turn (not in the paper): a flat disk of radius 2 whose rim is 64 segments, the
// boundary line of an open surface. Its faces are flat, so only the rim can ask for a size. At
// a base size of 1 the rim (12.6 long, over kMinTurnLineSizes sizes) takes eq. 21 on its radius
// at 10° (2 r tan 5° = 0.35), and with epsilon = 0.002 the kink bound at its vertices, which
// turn by 5.625°: 2 epsilon / sin(2.8125°) = 0.0815 (a side of eq. 20's sagitta bound, sqrt(8 r
// epsilon) = 0.179, would cut a vertex by 0.0044); at a base size of 2 the rim is too short for
// its turn to count, and no point asks anything.
TEST(CurvatureSizes, ALineAsksTheSizeOfItsOwnTurn) {
  const Mesh disk = testing::terrain_disk(0.0, 0.0, 2.0, 8, 64, [](double, double) { return 0.0; });
  const testing::SurfaceModel model = testing::surface_model(disk);
  ASSERT_EQ(model.features.lines.size(), 1u);
  const double eq21 = 2.0 * 2.0 * std::tan(5.0 * std::numbers::pi / 180.0);
  const double kink = 2.0 * 0.002 / std::sin(std::numbers::pi / 64.0);
  ASSERT_LT(kink, std::sqrt(8.0 * 2.0 * 0.002));
  struct Case {
    double angle, deviation, expected;
  };
  for (const Case c : {Case{10.0, 0.0, eq21}, Case{0.0, 0.002, kink}, Case{10.0, 0.002, kink}}) {
    const std::vector<double> sizes = sizes_of(model, c.angle,
                                                            c.deviation, UniformSize(1.0));
    Range rim;
    for (Index v = 0; v < model.surface.point_count(); ++v) {
      const Point x = model.surface.to_global(model.surface.local_points()[v]);
      if (std::abs(std::hypot(x[0], x[1]) - 2.0) > 1e-9) {
        EXPECT_FALSE(std::isfinite(sizes[v])) << "an inner point of the flat disk at " << x[0];
        continue;
      }
      rim.smallest = std::min(rim.smallest, sizes[v]);
      rim.largest = std::max(rim.largest, sizes[v]);
      ++rim.finite;
    }
    std::printf("disk rim, angle %g, epsilon %g: %d points, sizes %.4f to %.4f (expected %.4f)\n",
                c.angle, c.deviation, rim.finite, rim.smallest, rim.largest, c.expected);
    EXPECT_EQ(rim.finite, 64);
    EXPECT_GT(rim.smallest, 0.85 * c.expected);
    EXPECT_LT(rim.largest, 1.15 * c.expected);
  }
  const Range coarse = finite_range(
      sizes_of(model, 10.0, 0.002, UniformSize(2.0)));
  EXPECT_EQ(coarse.finite, 0);
}

// A cancelled job stops in the curvature sizes too: they look at the progress every few
// hundred faces (a 1M-face scan at a coarse size spent 29 s there before they did).
TEST(CurvatureSizes, StopWhenTheJobIsCancelled) {
  struct Cancelled final : Progress {
    bool cancelled() const override { return true; }
  } cancelled;
  const testing::SurfaceModel model = testing::surface_model(sphere_surface({0, 0, 0}, 1.0, 0.05));
  const absl::StatusOr<std::vector<double>> sizes = curvature_point_sizes(
      model.surface, model.features, 30.0, 0.0, UniformSize(1.0), cancelled);
  EXPECT_EQ(sizes.status().code(), absl::StatusCode::kCancelled) << sizes.status();
}

// End to end: the disk meshed at 1 with a 10° bound has at least 36 sides on its rim (a chord of
// 10° each), where the size alone gives 13; every output point on the rim stays on it.
TEST(CurvatureSizes, ARimIsSplitByItsTurn) {
  const Mesh disk = testing::terrain_disk(0.0, 0.0, 2.0, 8, 64, [](double, double) { return 0.0; });
  SurfaceParams params;
  params.size = 1.0;
  params.curvature_angle_deg = 10.0;
  const absl::StatusOr<SurfaceResult> result = generate_surface_mesh(disk, params);
  ASSERT_TRUE(result.ok()) << result.status();
  int rim = 0;
  for (const Point& x : result->mesh.points)
    if (std::abs(std::hypot(x[0], x[1]) - 2.0) < 0.01) ++rim;
  std::printf("disk at 1, 10°: %d rim points of %zu\n", rim, result->mesh.points.size());
  EXPECT_GE(rim, 36);
}

// End to end, as a user meshes a scan at the default angles: the noisy sphere above at 0.15 gives
// the triangles of the same sphere meshed with no curvature bound, within 5% (1,332; with eq. 21
// between the faces alone, 6,930).
TEST(CurvatureSizes, ANoisySphereAtTheDefaultAngleGetsTheCountTheSizeAsks) {
  const Mesh noisy = testing::jittered(sphere_surface({0, 0, 0}, 1.0, 0.05), 0.0075, 7);
  SurfaceParams params;
  params.size = 0.15;
  const absl::StatusOr<SurfaceResult> bound = generate_surface_mesh(noisy, params);
  ASSERT_TRUE(bound.ok()) << bound.status();
  params.curvature_angle_deg = 0.0;
  const absl::StatusOr<SurfaceResult> unbound = generate_surface_mesh(noisy, params);
  ASSERT_TRUE(unbound.ok()) << unbound.status();
  std::printf("noisy sphere at 0.15: %zu triangles at 30°, %zu with no bound\n",
              bound->mesh.triangles.size(), unbound->mesh.triangles.size());
  EXPECT_NEAR(static_cast<double>(bound->mesh.triangles.size()),
              static_cast<double>(unbound->mesh.triangles.size()),
              0.05 * static_cast<double>(unbound->mesh.triangles.size()));
}

// The coordinates of `at`'s closest point in its face, solved here as the 2x2 system of the
// point's coordinates along two edges (CurvatureLimitedSize takes sub-areas); none for a face
// with no area.
std::optional<std::array<double, 3>> coordinates_at(const DiscreteSurface& surface,
                                                    const Located& at) {
  const Triangle& t = surface.triangle(at.face);
  const std::vector<Point>& p = surface.local_points();
  const Point e1 = sub(p[t[1]], p[t[0]]), e2 = sub(p[t[2]], p[t[0]]), r = sub(at.closest, p[t[0]]);
  const double a = dot(e1, e1), b = dot(e1, e2), c = dot(e2, e2);
  const double det = a * c - b * b;
  if (!(det > 0.0)) return std::nullopt;
  const double u = (c * dot(r, e1) - b * dot(r, e2)) / det;
  const double v = (a * dot(r, e2) - b * dot(r, e1)) / det;
  return std::array<double, 3>{1.0 - u - v, u, v};
}

// The corner sizes of `at`'s face interpolated linearly at its closest point (coordinates_at);
// the smallest corner where a corner has no size or the face no area.
double interpolated_at(const DiscreteSurface& surface, const std::vector<double>& sizes,
                       const Located& at) {
  const Triangle& t = surface.triangle(at.face);
  const double d0 = sizes[t[0]], d1 = sizes[t[1]], d2 = sizes[t[2]];
  const double smallest = std::min({d0, d1, d2});
  if (!std::isfinite(std::max({d0, d1, d2}))) return smallest;
  const std::optional<std::array<double, 3>> lambda = coordinates_at(surface, at);
  if (!lambda) return smallest;
  return std::max(smallest, (*lambda)[0] * d0 + (*lambda)[1] * d1 + (*lambda)[2] * d2);
}

// interpolated_at over every face at the edge or corner of at.face that at.closest lies on (all
// as near), the smallest; at.face's alone when it lies inside the face.
double smallest_at_closest(const DiscreteSurface& surface, const std::vector<double>& sizes,
                           const Located& at) {
  const Triangle& t = surface.triangle(at.face);
  double own = interpolated_at(surface, sizes, at);
  const std::optional<std::array<double, 3>> lambda = coordinates_at(surface, at);
  if (!lambda) return own;
  std::vector<Index> on;  // the corners the point lies at or between
  for (int k = 0; k < 3; ++k)
    if ((*lambda)[k] > 1e-9) on.push_back(t[k]);
  if (on.size() == 3) return own;
  for (const Index f : surface.faces_at(on[0])) {
    const Triangle& g = surface.triangle(FaceId{f});
    const bool has_all = std::all_of(on.begin(), on.end(), [&](Index q) {
      return g[0] == q || g[1] == q || g[2] == q;
    });
    if (has_all)
      own = std::min(own, interpolated_at(surface, sizes, {FaceId{f}, at.closest, 0.0}));
  }
  return own;
}

// CurvatureLimitedSize skips the nearest-face search where its grid shows that no face that can be
// nearest asks for less than the base size; every answer must still be min(base, the corner sizes
// of the nearest face interpolated at its closest point, the smallest of the faces there where
// that point lies on an edge or corner) (to rounding). Random sizes at the points of a noisy
// sphere (faces of even shape) and of a cylinder of slivers (whose balls the grid keeps apart),
// on one side of each, asked at points on, near, inside and far outside the surface.
TEST(CurvatureSizes, TheLimitedSizeIsTheNearestFacesEverywhere) {
  for (const Mesh& mesh : {testing::jittered(sphere_surface({0, 0, 0}, 1.0, 0.1), 0.01, 3),
                           testing::sliver_cylinder(0.5, 2.0, 48)}) {
    const testing::SurfaceModel model = testing::surface_model(mesh);
    const DiscreteSurface& surface = model.surface;
    std::mt19937 rng(11);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    std::vector<double> point_sizes(static_cast<std::size_t>(surface.point_count()));
    for (Index v = 0; v < surface.point_count(); ++v)  // on one side only: the grid skips
      point_sizes[v] = surface.local_points()[v][0] > 0.0 && unit(rng) < 0.5
                           ? 0.2 + 2.0 * unit(rng)
                           : std::numeric_limits<double>::infinity();
    const UniformSize base(1.0);
    const CurvatureLimitedSize limited(base, surface, point_sizes);
    int skipped_would_bind = 0, asked = 0;
    for (int i = 0; i < 4000; ++i) {
      Point x;
      if (i % 2 == 0) {  // on a face, moved off it by up to a tenth of the model
        const Triangle& t = surface.triangles()[rng() % surface.triangles().size()];
        double u = unit(rng), v = unit(rng);
        if (u + v > 1.0) u = 1.0 - u, v = 1.0 - v;
        const std::vector<Point>& p = surface.local_points();
        x = add(p[t[0]], add(scale(sub(p[t[1]], p[t[0]]), u), scale(sub(p[t[2]], p[t[0]]), v)));
        x = add(x, scale(testing::random_direction(rng), 0.1 * surface.size() * unit(rng) *
                                                              unit(rng) * unit(rng)));
      } else {  // anywhere in the box, and beyond it
        for (double& c : x) c = (unit(rng) - 0.5) * 1.5 * surface.size();
      }
      const Point global = surface.to_global(x);
      const Located nearest = surface.nearest_face(surface.to_local(global));
      const double corners = smallest_at_closest(surface, point_sizes, nearest);
      const double expected = std::min(1.0, corners);
      ASSERT_NEAR(limited.size_at(global), expected, 1e-12 * expected) << "point " << i;
      ++asked;
      skipped_would_bind += corners < 1.0;
    }
    std::printf("%d queries, %d where the corners bind\n", asked, skipped_would_bind);
  }
}

// A size attached to a point grows away from it inside the faces as it grows along their edges
// (linear interpolation of the graded corner sizes), not only along the edges: a long face with one fine corner is not fine all along (of_bullet's cylinder
// of strips 0.013 long beside a fine back end came out 4.6 x finer than asked all over). A cylinder
// of 48 strips 2 long, sized 0.01 at its bottom rim's points: the size grows at c - 1 up the
// strips, and at their middles, 1 up, it is the base's (it was 0.01 there).
TEST(CurvatureSizes, ASizeGrowsAwayFromItsPointInsideALongFace) {
  const Mesh mesh = testing::sliver_cylinder(0.5, 2.0, 48);
  const testing::SurfaceModel model = testing::surface_model(mesh);
  const DiscreteSurface& surface = model.surface;
  std::vector<double> point_sizes(static_cast<std::size_t>(surface.point_count()),
                                  std::numeric_limits<double>::infinity());
  for (Index v = 0; v < surface.point_count(); ++v)
    if (surface.to_global(surface.local_points()[v])[2] < 1e-9) point_sizes[v] = 0.01;
  const double growth = 1.2;
  ASSERT_TRUE(grade_point_sizes(surface, growth, point_sizes).ok());
  const UniformSize base(0.1);
  const CurvatureLimitedSize limited(base, surface, point_sizes);
  const double chord = 2.0 * 0.5 * std::sin(std::numbers::pi / 48.0);
  for (int j = 0; j < 48; ++j) {
    const double angle = 2.0 * std::numbers::pi * (j + 0.5) / 48.0;
    const double r = 0.5 * std::cos(std::numbers::pi / 48.0);  // on the strip's chord
    // 0.2 up the strip: 0.2 from the rim's nearest points, at most 0.2 + a chord from the
    // corner of the face that holds it.
    const Point up{r * std::cos(angle), r * std::sin(angle), 0.2};
    EXPECT_GE(limited.size_at(up), 0.01 + (growth - 1.0) * 0.2 - 1e-12) << "strip " << j;
    EXPECT_LE(limited.size_at(up), 0.01 + (growth - 1.0) * (0.2 + chord)) << "strip " << j;
    const Point middle{up[0], up[1], 1.0};
    EXPECT_EQ(limited.size_at(middle), 0.1) << "strip " << j;
  }
}

// A point on an input edge (as a line's points are) is as near to both faces there, and takes
// the smaller of their sizes; so does a point at a corner. Two faces in the plane z = 0 share
// the edge (0, 0, 0)-(1, 0, 0): (A, B, C) with C = (0.5, 1, 0) held at 0.1 (a gap: the face
// holds its smallest corner) and (B, A, D) with D = (0.5, -1, 0), whose corners all have 1 and
// which interpolates them. On the edge and at A and B the size is 0.1, from either face
// order (the tree's tie between the faces picks one of them, the held face or not); inside
// (B, A, D) it is 1. netgen_part1's line beside a strip was split at the strip's face's size,
// 9 times its other side's (the regression test of issue 11 below).
TEST(CurvatureSizes, APointOnAnEdgeTakesTheSmallerSizeOfTheFacesThere) {
  for (const bool held_first : {false, true}) {
    Mesh mesh;
    mesh.points = {{0.0, 0.0, 0.0}, {1.0, 0.0, 0.0}, {0.5, 1.0, 0.0}, {0.5, -1.0, 0.0}};
    mesh.triangles = held_first ? std::vector<Triangle>{{0, 1, 2}, {1, 0, 3}}
                                : std::vector<Triangle>{{1, 0, 3}, {0, 1, 2}};
    const testing::SurfaceModel model = testing::surface_model(mesh);
    const DiscreteSurface& surface = model.surface;
    ASSERT_EQ(surface.point_count(), 4);
    std::vector<double> point_sizes(4, 1.0);
    std::vector<bool> held(4, false);
    for (Index v = 0; v < 4; ++v)
      if (surface.to_global(surface.local_points()[v])[1] > 0.5) {
        point_sizes[v] = 0.1;
        held[v] = true;
      }
    const UniformSize base(10.0);
    const CurvatureLimitedSize limited(base, surface, point_sizes, held);
    for (const double x : {0.0, 0.2, 0.5, 0.9, 1.0})
      for (const double z : {0.0, 1e-3, -0.2})  // on the edge, or nearest to it off the plane
        EXPECT_EQ(limited.size_at({x, 0.0, z}), 0.1) << x << " " << z << " " << held_first;
    EXPECT_EQ(limited.size_at({0.5, 0.5, 0.0}), 0.1);  // the held face
    EXPECT_NEAR(limited.size_at({0.5, -0.5, 0.0}), 1.0, 1e-12);
  }
}

// netgen_part1 at its mean edge with the deviation bound at 0.001 of the model: its line y =
// 2.528, z = 3.333 runs between a flat patch and a strip 1 wide. The strip's input face holds
// its smallest corner (0.77) and so does the flat patch's, whose held corner lies 2 from the
// line (0.085); the line was split at the strip's size, the flat patch meshed at its own, and the
// line's sides ended as caps: 99.37% at 30° or more, 19 triangles under 15° away from thinner
// input. The line's points now take the smaller size of the faces at their edge.
TEST(Regression, Issue11ALineTakesTheSmallerSizeOfTheFacesOnItsTwoSides) {
  const absl::StatusOr<SurfaceResult> r = testing::mesh_corpus_at_mean_edge(
      "netgen_part1.stl", [](SurfaceParams& params) { params.curvature_deviation = 0.001; });
  ASSERT_TRUE(r.ok()) << r.status();
  const testing::AngleCounts counts = testing::angle_counts(r->mesh);
  EXPECT_GE(static_cast<double>(counts.at_least_30), 0.99 * r->mesh.triangles.size());
  EXPECT_EQ(counts.under_15, r->report.thin_triangles_at_thinner_input);
  EXPECT_LE(r->report.hausdorff, 0.001 * r->report.model_size);
}

// Face caps: the sizes the deviation bound gives an edge hold over both its faces. A fold of two
// faces turning by 40° across their one edge (ridge angle 60: no line there), with the chord
// bound: each face's size is the edge's, which its two ends take too; inside either face, far
// from the edge towards a third corner with no size of its own, the limited size is still the
// edge's, where interpolation grew it to the base's.
TEST(CurvatureSizes, TheSizeOfAnEdgeHoldsOverItsFacesWithFaceCaps) {
  const double turn = 40.0 * std::numbers::pi / 180.0;
  Mesh fold;
  fold.points = {{0.0, 0.0, 0.0},
                 {1.0, 0.0, 0.0},
                 {0.5, 1.0, 0.0},
                 {0.5, -std::cos(turn), std::sin(turn)}};
  fold.triangles = {{0, 1, 2}, {1, 0, 3}};
  FeatureParams feature_params;
  feature_params.ridge_angle_deg = 60.0;
  const testing::SurfaceModel model = testing::surface_model(fold, feature_params);
  const DiscreteSurface& surface = model.surface;
  const UniformSize base(10.0);
  std::vector<double> face_sizes;
  absl::StatusOr<std::vector<double>> sizes =
      curvature_point_sizes(surface, model.features, 0.0, 0.001, base, no_progress(), &face_sizes);
  ASSERT_TRUE(sizes.ok()) << sizes.status();
  ASSERT_EQ(face_sizes.size(), 2u);
  const double edge = face_sizes[0];
  EXPECT_TRUE(std::isfinite(edge));  // (+infinity were the fold a line)
  EXPECT_EQ(face_sizes[1], edge);
  std::vector<double> corners = *sizes;
  for (double& d : corners)
    if (!std::isfinite(d)) d = 10.0;  // the third corners: the base size
  const CurvatureLimitedSize capped(base, surface, corners, {}, face_sizes);
  const CurvatureLimitedSize uncapped(base, surface, corners);
  const Point inside_first{0.5, 0.8, 0.0};
  const Point inside_second{0.5, -0.8 * std::cos(turn), 0.8 * std::sin(turn)};
  for (const Point& x : {inside_first, inside_second}) {
    EXPECT_NEAR(capped.size_at(x), edge, 1e-12 * edge);
    EXPECT_GT(uncapped.size_at(x), 5.0 * edge);
  }
}

// cgal_homer at its mean edge with the deviation bound at 0.001 of the model: an input vertex on
// a bump whose faces turn by 35° lay 1.02e-3 of the diagonal under the triangle over it, the
// kink bound of the bump's edges being interpolated towards the faces' far corners. With the
// face caps it is within the bound, as every other valid corpus file is.
TEST(Regression, Issue11TheDeviationBoundHoldsOnHomersBumps) {
  const absl::StatusOr<SurfaceResult> r = testing::mesh_corpus_at_mean_edge(
      "cgal_homer.stl", [](SurfaceParams& params) { params.curvature_deviation = 0.001; });
  ASSERT_TRUE(r.ok()) << r.status();
  EXPECT_LE(r->report.hausdorff, 0.001 * r->report.model_size);
}

}  // namespace
}  // namespace afmesh
