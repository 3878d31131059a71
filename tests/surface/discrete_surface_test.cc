// Tests of the discrete surface (paper §3, S2/S3/S8): input checks, normals, the tree's nearest
// face against a scan, the neighbour-to-neighbour walk against the tree, and projection far from
// the origin.
#include "core/surface/discrete_surface.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include "core/geometry/closest_points.h"
#include "core/geometry/vec.h"
#include "core/quality/measures.h"
#include "core/shapes/shapes.h"
#include "tests/surface/surface_test_shapes.h"

namespace afmesh {
namespace {

DiscreteSurface build_or_die(const Mesh& mesh, const DiscreteSurfaceParams& params = {}) {
  absl::StatusOr<DiscreteSurface> surface = DiscreteSurface::build(mesh, params);
  EXPECT_TRUE(surface.ok()) << surface.status();
  return *std::move(surface);
}

// The nearest face by scanning every face: the reference for the tree and the walk.
double scan_squared_distance(const DiscreteSurface& s, const Point& x) {
  double best = std::numeric_limits<double>::infinity();
  for (const Triangle& t : s.triangles()) {
    const Point c = closest_point_on_triangle(x, s.local_points()[t[0]], s.local_points()[t[1]],
                                              s.local_points()[t[2]]);
    best = std::min(best, squared_distance(x, c));
  }
  return best;
}

TEST(DiscreteSurface, BuildRefusesBadInput) {
  Mesh mesh;
  mesh.points = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  EXPECT_EQ(DiscreteSurface::build(mesh).status().code(), absl::StatusCode::kInvalidArgument);
  mesh.triangles = {{0, 1, 3}};
  EXPECT_EQ(DiscreteSurface::build(mesh).status().code(), absl::StatusCode::kInvalidArgument);
  mesh.triangles = {{0, 1, 1}};
  EXPECT_EQ(DiscreteSurface::build(mesh).status().code(), absl::StatusCode::kInvalidArgument);
  mesh.triangles = {{0, 1, 2}};
  mesh.triangle_tags = {1, 2};
  EXPECT_EQ(DiscreteSurface::build(mesh).status().code(), absl::StatusCode::kInvalidArgument);
  mesh.triangle_tags = {7};
  mesh.points[2][1] = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(DiscreteSurface::build(mesh).status().code(), absl::StatusCode::kInvalidArgument);
  mesh.points[2][1] = 1.0;
  const DiscreteSurface s = build_or_die(mesh);
  EXPECT_EQ(s.tag(FaceId{0}), 7);
  EXPECT_EQ(s.normal(FaceId{0}), (Point{0, 0, 1}));
}

TEST(DiscreteSurface, NormalsAreUnitAndOutwardOnASphere) {
  const DiscreteSurface s = build_or_die(sphere_surface({1, 2, 3}, 2.0, 0.3));
  EXPECT_EQ(s.degenerate_face_count(), 0);
  const Point centre = s.to_local({1, 2, 3});
  for (Index f = 0; f < s.face_count(); ++f) {
    const Point& n = s.normal(FaceId{f});
    EXPECT_NEAR(norm(n), 1.0, 1e-14);
    EXPECT_GT(dot(n, sub(s.local_points()[s.triangle(FaceId{f})[0]], centre)), 0.0);
  }
}

TEST(DiscreteSurface, DegenerateFaceHasZeroNormal) {
  Mesh mesh;
  mesh.points = {{0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {0, 1, 0}};
  mesh.triangles = {{0, 1, 2}, {0, 1, 3}};
  const DiscreteSurface s = build_or_die(mesh);
  EXPECT_EQ(s.degenerate_face_count(), 1);
  EXPECT_EQ(s.normal(FaceId{0}), (Point{0, 0, 0}));
}

TEST(DiscreteSurface, FacesAtAVertexAreItsFan) {
  const DiscreteSurface s = build_or_die(box_surface({0, 0, 0}, {1, 1, 1}, 1.0));
  std::int64_t uses = 0;
  for (Index v = 0; v < s.point_count(); ++v) {
    const auto faces = s.faces_at(v);
    EXPECT_TRUE(std::is_sorted(faces.begin(), faces.end()));
    for (Index f : faces) {
      const Triangle& t = s.triangle(FaceId{f});
      EXPECT_TRUE(t[0] == v || t[1] == v || t[2] == v);
    }
    uses += static_cast<std::int64_t>(faces.size());
  }
  EXPECT_EQ(uses, 3 * s.face_count());
}

TEST(DiscreteSurface, NearestFaceEqualsAScan) {
  const DiscreteSurface s = build_or_die(torus_surface(1.0, 0.3, 0.08));
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> coordinate(-1.5, 1.5);
  for (int i = 0; i < 300; ++i) {
    const Point x{coordinate(rng), coordinate(rng), 0.3 * coordinate(rng)};
    const Located found = s.nearest_face(x);
    EXPECT_TRUE(found.used_tree);
    EXPECT_EQ(found.squared_distance, scan_squared_distance(s, x)) << i;
  }
}

// Without the tree, nearest_face scans the faces: the tree's face (ties to the smaller id) and
// distance, bit for bit, also on a sphere whose faces tie at the vertices; build_tree restores
// the tree.
TEST(DiscreteSurface, NearestFaceWithoutTheTreeEqualsTheTree) {
  DiscreteSurfaceParams no_tree;
  no_tree.tree = false;
  for (const Mesh& mesh : {torus_surface(1.0, 0.3, 0.08), sphere_surface({0, 0, 0}, 1.0, 0.1)}) {
    const DiscreteSurface with = build_or_die(mesh);
    DiscreteSurface without = build_or_die(mesh, no_tree);
    EXPECT_TRUE(with.has_tree());
    EXPECT_FALSE(without.has_tree());
    std::mt19937 rng(5);
    std::uniform_real_distribution<double> coordinate(-1.5, 1.5);
    std::vector<Point> queries(mesh.points.begin(), mesh.points.begin() + 50);  // ties
    for (int i = 0; i < 300; ++i)
      queries.push_back({coordinate(rng), coordinate(rng), coordinate(rng)});
    for (const Point& global : queries) {
      const Point x = with.to_local(global);
      const Located a = with.nearest_face(x), b = without.nearest_face(x);
      EXPECT_TRUE(b.used_tree);
      EXPECT_EQ(a.face, b.face);
      EXPECT_EQ(a.squared_distance, b.squared_distance);
      EXPECT_EQ(a.face, without.locate(x, kNoFace).face);
    }
    without.build_tree();
    EXPECT_TRUE(without.has_tree());
    EXPECT_EQ(without.nearest_face(queries[0]).face, with.nearest_face(queries[0]).face);
  }
}

// What the walk did over many queries.
struct WalkFigures {
  int queries = 0;
  int same_face = 0;      // walk and tree name the same face
  int same_distance = 0;  // ... or faces equally near (within 1e-12 of the model size)
  int fell_back = 0;      // the walk gave up and asked the tree
  double mean_steps = 0.0;
  int max_steps = 0;
  double mean_walk_evaluations = 0.0;
  double mean_tree_evaluations = 0.0;
  double worst_excess = 0.0;  // largest (walk distance - tree distance)
};

// Random points within `band` of the surface; each is located from the host face of a point
// `hint_distance` away (as the front does: a new point's hint is the host of the face's points).
WalkFigures compare_walk_and_tree(const DiscreteSurface& s, int queries, double band,
                                  double hint_distance, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_int_distribution<Index> face(0, s.face_count() - 1);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  WalkFigures figures;
  double steps = 0, walk_evaluations = 0, tree_evaluations = 0;
  for (int q = 0; q < queries; ++q) {
    const Triangle& t = s.triangle(FaceId{face(rng)});
    const double u = unit(rng), v = unit(rng) * (1.0 - u);
    Point on = s.local_points()[t[0]];
    on = add(on, scale(sub(s.local_points()[t[1]], on), u));
    on = add(on, scale(sub(s.local_points()[t[2]], s.local_points()[t[0]]), v));
    const Point x = add(on, scale(testing::random_direction(rng), band * unit(rng)));
    const Point from = add(on, scale(testing::random_direction(rng), hint_distance));
    const FaceId hint = s.nearest_face(from).face;
    const Located walked = s.locate(x, hint);
    const Located tree = s.nearest_face(x);
    ++figures.queries;
    figures.same_face += walked.face == tree.face;
    figures.same_distance += std::abs(std::sqrt(walked.squared_distance) -
                                      std::sqrt(tree.squared_distance)) <= 1e-12 * s.size();
    figures.fell_back += walked.used_tree;
    figures.worst_excess = std::max(figures.worst_excess, std::sqrt(walked.squared_distance) -
                                                              std::sqrt(tree.squared_distance));
    figures.max_steps = std::max(figures.max_steps, walked.walk_steps);
    steps += walked.walk_steps;
    walk_evaluations += walked.evaluations;
    tree_evaluations += tree.evaluations;
  }
  figures.mean_steps = steps / queries;
  figures.mean_walk_evaluations = walk_evaluations / queries;
  figures.mean_tree_evaluations = tree_evaluations / queries;
  return figures;
}

void print(const char* name, const DiscreteSurface& s, const WalkFigures& f) {
  std::printf(
      "%s: %d faces, %d queries: same face %d, same distance %d, fell back %d, steps mean %.2f "
      "max %d, evaluations per query: walk %.1f, tree %.1f; worst walk excess %.3g (size %.3g)\n",
      name, s.face_count(), f.queries, f.same_face, f.same_distance, f.fell_back, f.mean_steps,
      f.max_steps, f.mean_walk_evaluations, f.mean_tree_evaluations, f.worst_excess, s.size());
}

TEST(DiscreteSurface, WalkAgreesWithTheTreeNearASphere) {
  const DiscreteSurface s = build_or_die(sphere_surface({0, 0, 0}, 1.0, 0.05));
  const WalkFigures f = compare_walk_and_tree(s, 2000, 0.02, 0.15, 1);
  print("sphere", s, f);
  EXPECT_EQ(f.same_distance, f.queries);
  EXPECT_EQ(f.fell_back, 0);
}

TEST(DiscreteSurface, WalkAgreesWithTheTreeNearATorus) {
  const DiscreteSurface s = build_or_die(torus_surface(1.0, 0.3, 0.03));
  const WalkFigures f = compare_walk_and_tree(s, 2000, 0.02, 0.1, 2);
  print("torus", s, f);
  EXPECT_EQ(f.same_distance, f.queries);
  EXPECT_EQ(f.fell_back, 0);
}

// A scan-like sphere: points jittered by a third of the edge length, so neighbouring normals
// differ by tens of degrees and the distance to the surface is bumpy at the scale of a face.
TEST(DiscreteSurface, WalkAgreesWithTheTreeNearANoisyScanLikeSphere) {
  const DiscreteSurface s =
      build_or_die(testing::jittered(sphere_surface({0, 0, 0}, 1.0, 0.04), 0.013, 5));
  const WalkFigures f = compare_walk_and_tree(s, 2000, 0.01, 0.12, 3);
  print("noisy sphere", s, f);
  EXPECT_EQ(f.same_distance, f.queries);
  EXPECT_LE(f.fell_back, f.queries / 100);
}

// Three sheets on one segment (a T): across the non-manifold segment there are no edge
// neighbours, so the walk goes round the segment's vertices. Points near one sheet, hinted from
// another sheet whose distance to them is least on the segment, must cross it. (A hint on a
// sheet where the distance has its own local minimum, e.g. the wall for a point just above the
// floor, stays there: see the header.)
TEST(DiscreteSurface, WalkCrossesANonManifoldSegment) {
  const DiscreteSurface s = build_or_die(testing::three_sheet_t(8));
  std::mt19937 rng(8);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const FaceId on_left = s.nearest_face(s.to_local({-0.5, 0.5, 0.0})).face;
  const FaceId on_right = s.nearest_face(s.to_local({0.5, 0.5, 0.0})).face;
  int crossed = 0;
  for (int i = 0; i < 300; ++i) {
    const double u = 0.2 + 0.7 * unit(rng), y = 0.1 + 0.8 * unit(rng), w = 0.1 * unit(rng) - 0.05;
    // Near the left floor, the right floor, the wall; hinted from the other floor (for the wall:
    // the floor on the other side of it, whose nearest point to x is on the segment).
    const std::vector<std::pair<Point, FaceId>> queries = {
        {{-u, y, w}, on_right}, {{u, y, w}, on_left}, {{w, y, u}, w > 0 ? on_left : on_right}};
    for (const auto& [global, hint] : queries) {
      const Point x = s.to_local(global);
      const Located found = s.locate(x, hint);
      EXPECT_FALSE(found.used_tree);
      EXPECT_NEAR(std::sqrt(found.squared_distance), std::sqrt(s.nearest_face(x).squared_distance),
                  1e-12 * s.size());
      crossed += found.face != hint;
    }
  }
  EXPECT_EQ(crossed, 900);
}

// The walk's bound: a hint on the far side of the sphere is ~60 faces away; with a bound of 8
// the walk gives up and the tree answers.
TEST(DiscreteSurface, LongWalkFallsBackToTheTree) {
  DiscreteSurfaceParams params;
  params.max_walk_steps = 8;
  const DiscreteSurface s = build_or_die(sphere_surface({0, 0, 0}, 1.0, 0.05), params);
  const Point x{0.0, 0.0, 1.01};
  const FaceId far = s.nearest_face({0.0, 0.0, -1.0}).face;
  const Located found = s.locate(x, far);
  EXPECT_TRUE(found.used_tree);
  EXPECT_GT(found.walk_steps, 8);
  EXPECT_EQ(found.squared_distance, s.nearest_face(x).squared_distance);
  params.max_walk_steps = 1000;
  const Located unbounded =
      build_or_die(sphere_surface({0, 0, 0}, 1.0, 0.05), params).locate(x, far);
  EXPECT_FALSE(unbounded.used_tree);
  EXPECT_EQ(unbounded.squared_distance, found.squared_distance);
}

TEST(DiscreteSurface, LocateWithoutHintAsksTheTree) {
  const DiscreteSurface s = build_or_die(sphere_surface({0, 0, 0}, 1.0, 0.2));
  const Located found = s.locate({0.3, 0.2, 0.9}, kNoFace);
  EXPECT_TRUE(found.used_tree);
  EXPECT_EQ(found.walk_steps, 0);
}

// S8 far from the origin: a 10 m terrain patch at UTM-like coordinates (5e6, 5e6, 1e3).
// Projected points must lie on the surface to 1e-9 of the model size (1e-8 m), i.e. within a
// few ulps of 5e6 (9.3e-10): the local frame keeps the differences exact.
TEST(DiscreteSurface, ProjectionFarFromTheOriginLandsOnTheSurface) {
  const double x0 = 5e6, y0 = 5e6, width = 10.0;
  const auto height = [&](double x, double y) {
    return 1e3 + 0.5 * std::sin(0.7 * (x - x0)) * std::cos(0.4 * (y - y0));
  };
  const Mesh mesh = testing::terrain_grid(x0, y0, width, width, 40, height);
  const DiscreteSurface s = build_or_die(mesh);
  // The local copy is the input, exactly (Sterbenz).
  for (Index v = 0; v < s.point_count(); ++v) {
    EXPECT_EQ(s.to_global(s.local_points()[v]), mesh.points[v]);
  }
  std::mt19937 rng(9);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  FaceId hint = kNoFace;
  double worst = 0.0;
  for (int i = 0; i < 1000; ++i) {
    const double x = x0 + 0.5 + 9.0 * unit(rng), y = y0 + 0.5 + 9.0 * unit(rng);
    const Point global{x, y, height(x, y) + 0.2 * (unit(rng) - 0.5)};
    const Located at = s.project(s.to_local(global), hint);
    hint = at.face;
    const Point projected = s.to_global(at.closest);
    // Distance of the projected point to its host face's plane, from global coordinates: the
    // differences to a corner are exact, so this measures the projection, not the test.
    const Triangle& t = s.triangle(at.face);
    const double off = dot(sub(projected, mesh.points[t[0]]), s.normal(at.face));
    worst = std::max(worst, std::abs(off));
    EXPECT_EQ(at.squared_distance, s.nearest_face(s.to_local(global)).squared_distance);
  }
  std::printf("far from origin: worst distance off the surface %.3g m (model size %.3g m)\n", worst,
              s.size());
  EXPECT_LE(worst, 1e-9 * s.size());
}

// A real scan (the Stanford bunny of libcgal-demo, 75k faces): walk and tree agree on 99%. The
// hints come from points three mean edges away in a random direction, which near the ears and
// folds can be nearest to another sheet; a walk from there ends at a local minimum on that sheet
// (measured: 4 of 2000, all with the hint's host ~0.03 from the query's own sheet).
TEST(DiscreteSurface, WalkAgreesWithTheTreeOnTheCorpusBunny) {
  const Mesh mesh = testing::corpus_mesh("cgal_bunny00.stl");
  ASSERT_FALSE(mesh.triangles.empty());
  const DiscreteSurface s = build_or_die(mesh);
  const double h = mean_edge_length(mesh);
  const WalkFigures f = compare_walk_and_tree(s, 2000, 0.2 * h, 3.0 * h, 4);
  print("corpus bunny", s, f);
  EXPECT_GE(f.same_distance, f.queries * 99 / 100);
}

// cannot_be_nearer lets the walks skip faces: it must never say so of a face whose distance is
// not strictly above the bound (here the face's own distance, the closest call), whatever the
// face's shape (a jittered sphere's faces, and the slivers of a CAD box, which get no ball), and
// on well-shaped faces it must say so of most faces well away from x, or it saves nothing.
TEST(DiscreteSurface, CannotBeNearerHoldsForNoFaceAsNearAsTheBound) {
  const std::vector<Mesh> meshes = {
      testing::jittered(testing::uv_sphere({0, 0, 0}, 1.0, 40, 20), 0.01, 3),
      testing::sliver_box(2.0, 1.0, 0.5, 12)};
  for (std::size_t m = 0; m < meshes.size(); ++m) {
    const DiscreteSurface s = build_or_die(meshes[m]);
    const std::vector<Point>& p = s.local_points();
    std::mt19937 rng(5);
    std::uniform_int_distribution<Index> any_face(0, s.face_count() - 1);
    std::normal_distribution<double> off(0.0, 0.05);
    int far = 0, skipped = 0;
    for (int i = 0; i < 20000; ++i) {
      const FaceId on{any_face(rng)};
      const Triangle& t = s.triangle(on);
      const Point centroid = scale(add(p[t[0]], add(p[t[1]], p[t[2]])), 1.0 / 3.0);
      const Point x = add(centroid, {off(rng), off(rng), off(rng)});
      const FaceId f{any_face(rng)};
      const double d = s.squared_distance_to_face(x, f);
      EXPECT_FALSE(s.cannot_be_nearer(x, f, d)) << "face " << index_of(f);
      const double bound = s.squared_distance_to_face(x, on);
      if (d > 4.0 * bound + 0.01) {
        ++far;
        skipped += s.cannot_be_nearer(x, f, bound);
      }
    }
    if (m == 0) {  // the sphere's faces are well shaped
      EXPECT_GT(far, 10000);
      EXPECT_GT(skipped, far / 2) << skipped << " of " << far;
    }
  }
}
}  // namespace
}  // namespace afmesh
