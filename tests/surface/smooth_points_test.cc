// Tests of the smoothing of the points inside the patches (smooth_points.h): on a sphere meshed
// by a jittered coarse triangulation whose points lie on the input, the smallest angle rises,
// every point stays on the input, no triangle turns over, anchored points stay, and the
// triangles are the same.
#include "core/surface/smooth_points.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "core/geometry/vec.h"
#include "core/quality/measures.h"
#include "core/shapes/shapes.h"
#include "core/sizing/size_field.h"
#include "tests/surface/surface_test_shapes.h"

namespace afmesh {
namespace {

class CancelledProgress final : public Progress {
 public:
  bool cancelled() const override { return true; }
};

Point normal_of(const std::vector<Point>& p, const Triangle& t) {
  const Point n = cross(sub(p[t[1]], p[t[0]]), sub(p[t[2]], p[t[0]]));
  return scale(n, 1.0 / norm(n));
}

TEST(SmoothPoints, RaisesTheSmallestAngleAndKeepsEveryPointOnTheInput) {
  const testing::SurfaceModel model = testing::surface_model(sphere_surface({0, 0, 0}, 1.0, 0.05));
  ASSERT_EQ(model.features.patches.size(), 1u);
  const UniformSize field(0.2);
  SurfaceMeshState s(model.surface, model.features, field, 1.2);
  // A coarse sphere, jittered by a third of its edges.
  testing::add_on_the_input(testing::jittered(sphere_surface({0, 0, 0}, 1.0, 0.2), 0.06, 7), s);
  // Three points anchored, as line points are: they must not move.
  for (const Index q : {0, 10, 20}) s.anchor[q] = model.surface.triangle(s.host[q])[0];
  const std::vector<Point> before = s.points;
  const std::vector<Triangle> triangles = s.triangles;
  const double smallest_before = testing::smallest_angle(s);

  const absl::StatusOr<std::int64_t> moves = smooth_points(s);
  ASSERT_TRUE(moves.ok()) << moves.status();
  std::printf("smallest angle %.2f -> %.2f after %lld moves\n", smallest_before,
              testing::smallest_angle(s), static_cast<long long>(*moves));
  EXPECT_GT(*moves, 0);
  EXPECT_GT(testing::smallest_angle(s), smallest_before + 5.0);
  EXPECT_EQ(s.triangles, triangles);
  for (const Index q : {0, 10, 20}) EXPECT_EQ(s.points[q], before[q]);
  const double turn = std::cos(30.0 * std::numbers::pi / 180.0);
  for (const Triangle& t : s.triangles)
    EXPECT_GT(dot(normal_of(s.points, t), normal_of(before, t)), turn - 1e-12);
  for (std::size_t q = 0; q < s.points.size(); ++q) {
    const Located on = model.surface.nearest_face(s.points[q]);
    EXPECT_LT(on.squared_distance, 1e-24) << "point " << q;
    EXPECT_LT(std::sqrt(model.surface.locate(s.points[q], s.host[q]).squared_distance), 1e-12);
  }
}

// A unit square (two input triangles, z = 0) meshed by a 4 x 4 grid whose rim points are its
// four lines' points (the corners and three points on each line, points_along_lines as the line
// splitting sets them) and whose 3 x 3 inner points are the patch's.
struct GridOnSquare {
  static Mesh square() {
    Mesh m;
    m.points = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
    m.triangles = {{0, 1, 2}, {0, 2, 3}};
    return m;
  }
  testing::SurfaceModel model;
  UniformSize field{0.25};
  SurfaceMeshState s;
  std::vector<Index> at;  // grid point (i, j) is s's point at[5 j + i]

  GridOnSquare()
      : model(testing::surface_model(square())),
        s(model.surface, model.features, field, 1.2),
        at(25, kInvalidIndex) {
    const auto grid = [&](const Point& local) {
      const Point x = model.surface.to_global(local);
      return static_cast<int>(std::lround(4 * x[0]) + 5 * std::lround(4 * x[1]));
    };
    const std::vector<Point>& corner = model.surface.local_points();
    // The lines first (line points precede a patch's), then the inner points.
    for (const DiscreteLine& line : model.features.lines) {
      const Index a = line.vertices.front(), b = line.vertices.back();
      SurfaceMeshState::LinePoints along;
      for (int k = 0; k <= 4; ++k) {
        const Point x = add(corner[a], scale(sub(corner[b], corner[a]), k / 4.0));
        Index& q = at[grid(x)];
        if (q == kInvalidIndex) {
          const Index anchor = k == 4 ? b : a;
          q = s.add_point(x, 0.25, model.surface.faces_at(anchor).empty()
                                       ? FaceId{0}
                                       : FaceId{model.surface.faces_at(anchor)[0]},
                          anchor);
        }
        along.ids.push_back(q);
        along.segment.push_back(0);
      }
      for (int k = 0; k < 4; ++k)
        s.line_sides.insert({std::min(along.ids[k], along.ids[k + 1]),
                             std::max(along.ids[k], along.ids[k + 1])});
      s.points_along_lines.push_back(along);
    }
    s.line_points = static_cast<Index>(s.points.size());
    for (int j = 1; j < 4; ++j)
      for (int i = 1; i < 4; ++i) {
        const Point x = model.surface.to_local({i / 4.0, j / 4.0, 0.0});
        at[5 * j + i] = s.add_point(x, 0.25, model.surface.nearest_face(x).face, kInvalidIndex);
      }
    for (int j = 0; j < 4; ++j)
      for (int i = 0; i < 4; ++i) {
        const Index a = at[5 * j + i], b = at[5 * j + i + 1], c = at[5 * j + i + 6],
                    d = at[5 * j + i + 5];
        s.add_triangle({a, b, c}, PatchId{0});
        s.add_triangle({a, c, d}, PatchId{0});
      }
  }
};

TEST(SmoothPoints, ALinePointSlidesAlongItsLineAndStaysOnIt) {
  GridOnSquare g;
  ASSERT_EQ(g.model.features.lines.size(), 4u);
  ASSERT_EQ(g.s.points.size(), 25u);
  // The middle point of the bottom line, moved along it to x = 0.6: its fan's triangles are
  // stretched and squeezed, and sliding back towards x = 0.5 mends them.
  const Index q = g.at[2];
  const auto global = [&](Index p) { return g.model.surface.to_global(g.s.points[p]); };
  g.s.points[q] = g.model.surface.to_local({0.6, 0.0, 0.0});
  const std::vector<Point> before = g.s.points;
  const std::vector<Triangle> triangles = g.s.triangles;
  const auto sides = g.s.line_sides;
  const double smallest_before = testing::smallest_angle(g.s);

  const absl::StatusOr<std::int64_t> moves = smooth_points(g.s);
  ASSERT_TRUE(moves.ok()) << moves.status();
  EXPECT_GT(*moves, 0);
  EXPECT_GT(testing::smallest_angle(g.s), smallest_before + 3.0);
  // On the line (the input's edge y = 0), between its neighbours and nearer the middle.
  EXPECT_EQ(global(q)[1], 0.0);
  EXPECT_EQ(global(q)[2], 0.0);
  EXPECT_LT(std::abs(global(q)[0] - 0.5), 0.06) << global(q)[0];
  // Every other rim point stays on its line, the corners where they were; the triangles and the
  // lines' sides are the same.
  for (const Index c : {g.at[0], g.at[4], g.at[20], g.at[24]}) EXPECT_EQ(g.s.points[c], before[c]);
  for (Index p = 0; p < g.s.line_points; ++p) {
    const Point x = global(p);
    EXPECT_TRUE(x[0] == 0.0 || x[0] == 1.0 || x[1] == 0.0 || x[1] == 1.0) << "point " << p;
    EXPECT_LT(std::sqrt(g.model.surface.locate(g.s.points[p], g.s.host[p]).squared_distance),
              1e-15);
  }
  EXPECT_EQ(g.s.triangles, triangles);
  EXPECT_EQ(g.s.line_sides, sides);
  for (const Triangle& t : g.s.triangles) EXPECT_GT(normal_of(g.s.points, t)[2], 0.99);

  // With the slides off, the line point stays where it was put.
  GridOnSquare off;
  const Point moved = off.model.surface.to_local({0.6, 0.0, 0.0});
  off.s.points[off.at[2]] = moved;
  SmoothParams params;
  params.slide_line_points = false;
  ASSERT_TRUE(smooth_points(off.s, params).ok());
  EXPECT_EQ(off.s.points[off.at[2]], moved);
}

// cgal_bones at its mean edge: a coarse scan whose 1,175 lines (ridges at 30 degrees) run
// closer to each other than the size in many places; the strips between them are spanned from
// line to line. With the line points fixed, 98.66% of its triangles were at 30 degrees or more
// and 5 were under 15 away from thinner input corners; with the slides, 99.03% and none.
TEST(Regression, Issue11LinePointsSlideSoTheBonesStripsKeepTheirAngles) {
  const absl::StatusOr<SurfaceResult> r = testing::mesh_corpus_at_mean_edge("cgal_bones.stl");
  ASSERT_TRUE(r.ok()) << r.status();
  const testing::AngleCounts counts = testing::angle_counts(r->mesh);
  EXPECT_GE(static_cast<double>(counts.at_least_30), 0.99 * r->mesh.triangles.size());
  EXPECT_EQ(counts.under_15, r->report.thin_triangles_at_thinner_input);
}

TEST(SmoothPoints, StopsWithCancelled) {
  const testing::SurfaceModel model = testing::surface_model(sphere_surface({0, 0, 0}, 1.0, 0.1));
  const UniformSize field(0.2);
  SurfaceMeshState s(model.surface, model.features, field, 1.2);
  testing::add_on_the_input(testing::jittered(sphere_surface({0, 0, 0}, 1.0, 0.05), 0.01, 3), s);
  CancelledProgress cancelled;
  EXPECT_EQ(smooth_points(s, {}, cancelled).status().code(), absl::StatusCode::kCancelled);
}

}  // namespace
}  // namespace afmesh
