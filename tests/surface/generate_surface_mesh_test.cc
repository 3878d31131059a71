// MeshSurface end to end (paper §3): surfaces re-triangulated at a size, judged by invariants:
// a valid (closed, manifold, oriented) surface where the input was closed, every vertex on the
// input, the sharp edges kept, triangles of the size asked.
#include "core/surface/generate_surface_mesh.h"

#include <gtest/gtest.h>

#include <cmath>

#include "core/geometry/vec.h"
#include "core/quality/measures.h"
#include "core/quality/validate.h"
#include "core/shapes/shapes.h"
#include "tests/surface/surface_test_shapes.h"

namespace afmesh {
namespace {

struct Figures {
  double min_angle = 180, share_30 = 0, mean_edge = 0;
};

Figures figures_of(const Mesh& m) {
  Figures f;
  std::int64_t good = 0;
  double edges = 0;
  for (const Triangle& t : m.triangles) {
    const double a = triangle_quality(m.points, t).min_angle_deg;
    f.min_angle = std::min(f.min_angle, a);
    good += a >= 30.0;
    for (int k = 0; k < 3; ++k) edges += norm(sub(m.points[t[(k + 1) % 3]], m.points[t[k]]));
  }
  f.share_30 = static_cast<double>(good) / m.triangles.size();
  f.mean_edge = edges / (3.0 * m.triangles.size());
  return f;
}

void expect_closed_valid(const Mesh& m) {
  const ValidationReport report = validate_surface(m);
  EXPECT_TRUE(report.valid()) << report.to_string();
}

// The quality bar on smooth inputs and CAD-like ones with right angles: no triangle
// under 15°, and (nearly) all of them 30° and more.
void expect_quality(const Mesh& m) {
  const Figures f = figures_of(m);
  EXPECT_GE(f.min_angle, 15.0);
  EXPECT_GE(f.share_30, 0.985);
}

TEST(GenerateSurfaceMesh, SphereIsClosedOnTheInputAndOfTheSizeAsked) {
  const Mesh input = sphere_surface({0, 0, 0}, 1.0, 0.05);
  SurfaceParams params;
  params.size = 0.1;
  absl::StatusOr<SurfaceResult> r = generate_surface_mesh(input, params);
  ASSERT_TRUE(r.ok()) << r.status();
  expect_closed_valid(r->mesh);
  const Figures f = figures_of(r->mesh);
  std::printf("sphere: %zu triangles, min angle %.2f, >=30: %.4f, mean edge %.4f, hausdorff %.2e\n",
              r->mesh.triangles.size(), f.min_angle, f.share_30, f.mean_edge, r->report.hausdorff);
  EXPECT_NEAR(f.mean_edge, 0.1, 0.015);
  expect_quality(r->mesh);
  EXPECT_LE(r->report.max_vertex_distance, 1e-9 * r->report.model_size);
  EXPECT_EQ(r->report.patches, 1);
}


SurfaceResult mesh_at(const Mesh& input, double size) {
  SurfaceParams params;
  params.size = size;
  absl::StatusOr<SurfaceResult> r = generate_surface_mesh(input, params);
  EXPECT_TRUE(r.ok()) << r.status();
  return r.ok() ? *std::move(r) : SurfaceResult{};
}

void print(const char* name, const SurfaceResult& r) {
  const Figures f = figures_of(r.mesh);
  std::printf("%s: %zu triangles, min angle %.2f, >=30: %.4f, mean edge %.4f, hausdorff %.2e "
              "(%.2e of the diagonal), patches %lld lines %lld corners %lld\n",
              name, r.mesh.triangles.size(), f.min_angle, f.share_30, f.mean_edge,
              r.report.hausdorff, r.report.hausdorff / r.report.model_size,
              static_cast<long long>(r.report.patches), static_cast<long long>(r.report.lines),
              static_cast<long long>(r.report.corners));
}

TEST(GenerateSurfaceMesh, TorusIsClosed) {
  const SurfaceResult r = mesh_at(torus_surface(1.0, 0.35, 0.04), 0.08);
  print("torus", r);
  expect_closed_valid(r.mesh);
  EXPECT_NEAR(figures_of(r.mesh).mean_edge, 0.08, 0.012);
  expect_quality(r.mesh);
}

// A cube: 12 ridges, 8 corners, 6 patches; the output keeps every corner exactly and has no
// triangle across a ridge (each triangle lies in one face plane).
TEST(GenerateSurfaceMesh, CubeKeepsItsRidgesAndCorners) {
  const Mesh input = box_surface({0, 0, 0}, {1, 1, 1}, 0.07);
  const SurfaceResult r = mesh_at(input, 0.1);
  print("cube", r);
  expect_closed_valid(r.mesh);
  expect_quality(r.mesh);
  EXPECT_EQ(r.report.patches, 6);
  EXPECT_EQ(r.report.corners, 8);
  int corners = 0;
  for (const Point& x : r.mesh.points) {
    bool corner = true;
    for (double c : x) corner = corner && (c == 0.0 || c == 1.0);
    corners += corner;
  }
  EXPECT_EQ(corners, 8);
  for (const Triangle& t : r.mesh.triangles) {
    bool planar = false;
    for (int a = 0; a < 3; ++a) {
      const double c = r.mesh.points[t[0]][a];
      planar = planar || ((c == 0.0 || c == 1.0) && r.mesh.points[t[1]][a] == c &&
                          r.mesh.points[t[2]][a] == c);
    }
    EXPECT_TRUE(planar) << "a triangle across a ridge";
  }
}

// An open terrain patch in UTM-like coordinates: one boundary line, kept; every vertex on the
// input within 1e-9 of the model size.
TEST(GenerateSurfaceMesh, OpenTerrainFarFromTheOrigin) {
  const Mesh input = testing::terrain_grid(5e6, 5e6, 100.0, 80.0, 40, [](double x, double y) {
    return 1e3 + 5.0 * std::sin((x - 5e6) / 15.0) * std::cos((y - 5e6) / 20.0);
  });
  const SurfaceResult r = mesh_at(input, 4.0);
  print("terrain", r);
  EXPECT_GT(r.mesh.triangles.size(), 500u);
  expect_quality(r.mesh);
  EXPECT_LE(r.report.max_vertex_distance, 1e-9 * r.report.model_size);
}

}  // namespace
}  // namespace afmesh
