// Tests of the sizes from the gaps between lines (gap_sizes.h): a slab thinner than the size has
// side faces that are strips between two ridges, whose vertices take the strip's width as their
// size, and its re-triangulation keeps its triangles shaped there.
#include "core/surface/gap_sizes.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "core/quality/measures.h"
#include "core/quality/validate.h"
#include "core/shapes/shapes.h"
#include "core/sizing/size_field.h"
#include "core/surface/generate_surface_mesh.h"
#include "tests/surface/surface_test_shapes.h"

namespace afmesh {
namespace {

// A 1 × 1 × 0.05 slab, triangulated at 0.05.
Mesh thin_slab() { return box_surface({0, 0, 0}, {1, 1, 0.05}, 0.05); }

TEST(GapSizes, TheRidgesOfAThinSlabTakeItsThicknessAsTheirSize) {
  const testing::SurfaceModel model = testing::surface_model(thin_slab());
  ASSERT_EQ(model.features.lines.size(), 12u);
  const std::vector<double> sizes = line_gap_sizes(model.surface, model.features, UniformSize(0.2));
  const std::vector<Point>& p = model.surface.local_points();
  int on_ridges = 0;
  for (const DiscreteLine& line : model.features.lines) {
    for (const Index v : line.vertices) {
      const Point x = model.surface.to_global(p[v]);
      const bool corner = (x[0] == 0 || x[0] == 1) && (x[1] == 0 || x[1] == 1);
      if (corner) continue;  // where three lines meet the nearest facing edge can be nearer
      EXPECT_NEAR(sizes[v], 0.05, 1e-9) << "vertex " << v;
      ++on_ridges;
    }
  }
  EXPECT_GT(on_ridges, 100);
  // Off the lines nothing is attached; the slab's faces are 1 wide, over the size.
  for (Index v = 0; v < static_cast<Index>(sizes.size()); ++v) {
    const Point x = model.surface.to_global(p[v]);
    if (x[0] > 0 && x[0] < 1 && x[1] > 0 && x[1] < 1) {
      EXPECT_TRUE(std::isinf(sizes[v])) << "vertex " << v;
    }
  }
}

TEST(GapSizes, AGapNeverTakesTheSizeBelowAFractionOfTheField) {
  const testing::SurfaceModel model =
      testing::surface_model(box_surface({0, 0, 0}, {1, 1, 0.005}, 0.05));
  const std::vector<double> sizes = line_gap_sizes(model.surface, model.features, UniformSize(0.2));
  double smallest = std::numeric_limits<double>::infinity();
  for (const double d : sizes) smallest = std::min(smallest, d);
  EXPECT_NEAR(smallest, 0.15 * 0.2, 1e-12);
}

// End to end: the slab at 0.2, four times its thickness. Its sides were strips of slivers (the
// lines split at 0.2 across a 0.05 gap); they are now meshed at their width.
TEST(GapSizes, AThinSlabIsReTriangulatedWithoutSlivers) {
  SurfaceParams params;
  params.size = 0.2;
  const absl::StatusOr<SurfaceResult> r = generate_surface_mesh(thin_slab(), params);
  ASSERT_TRUE(r.ok()) << r.status();
  EXPECT_TRUE(validate_surface(r->mesh).valid());
  double smallest = 180.0;
  std::size_t under_30 = 0;
  for (const Triangle& t : r->mesh.triangles) {
    const double angle = triangle_quality(r->mesh.points, t).min_angle_deg;
    smallest = std::min(smallest, angle);
    if (angle < 30.0) ++under_30;
  }
  std::printf("thin slab: %zu triangles, smallest angle %.2f, %zu under 30°\n",
              r->mesh.triangles.size(), smallest, under_30);
  EXPECT_GE(smallest, 15.0);
  EXPECT_LE(static_cast<double>(under_30), 0.01 * static_cast<double>(r->mesh.triangles.size()));
}

// The gaps ask for ~10 times the triangles the size alone would (1,374 against ~130): a limit
// between the two refuses the job before the front runs, naming the estimate.
TEST(GapSizes, ASurfaceWhoseAttachedSizesAskForTooManyTrianglesIsRefusedFirst) {
  SurfaceParams params;
  params.size = 0.2;
  params.max_triangles = 500;
  const absl::StatusOr<SurfaceResult> r = generate_surface_mesh(thin_slab(), params);
  ASSERT_EQ(r.status().code(), absl::StatusCode::kResourceExhausted) << r.status();
  EXPECT_NE(r.status().message().find("sizes attached to the surface"), std::string::npos)
      << r.status();
}

// The same count goes to params.admit_expected (the server's memory admission), and a refusal
// there ends the job with the refusal's own status.
TEST(GapSizes, TheCountTheAttachedSizesAskForIsHandedToTheAdmission) {
  SurfaceParams params;
  params.size = 0.2;
  double admitted = 0.0;
  params.admit_expected = [&](double expected) {
    admitted = expected;
    return absl::ResourceExhaustedError("budget held");
  };
  const absl::StatusOr<SurfaceResult> r = generate_surface_mesh(thin_slab(), params);
  EXPECT_EQ(r.status(), absl::ResourceExhaustedError("budget held"));
  EXPECT_GT(admitted, 500.0);
  EXPECT_LT(admitted, 5000.0);
}

}  // namespace
}  // namespace afmesh
