// The a-priori element count (core/volume/estimate_elements.h) against the counts the front
// really makes: within 1.5x (the goal is 2x) on the bench shapes at uniform sizes finer and coarser than their
// surfaces, and with a point source; exact where it can be (a uniform size, in closed form).
#include "core/volume/estimate_elements.h"

#include <cmath>
#include <cstdio>

#include "core/shapes/shapes.h"
#include "core/sizing/spec_size_field.h"
#include "gmock/gmock.h"
#include "gtest/gtest.h"
#include "tests/volume/mesh_and_check.h"

namespace afmesh {
namespace {

struct Case {
  const char* name;
  Mesh front;
  double size;
};

double ratio_for(const Case& c, const VolumeParams& params) {
  absl::StatusOr<VolumeEstimate> estimate = estimate_volume_mesh(c.front, params);
  EXPECT_TRUE(estimate.ok()) << estimate.status();
  absl::StatusOr<VolumeResult> mesh = generate_volume_mesh(c.front, params, no_progress());
  EXPECT_TRUE(mesh.ok()) << mesh.status();
  if (!estimate.ok() || !mesh.ok()) return 0.0;
  const double real = static_cast<double>(mesh->mesh.tets.size());
  std::printf("%-28s size %-6g estimate %9.0f real %9.0f  estimate/real %.2f\n", c.name,
              c.size, estimate->tets, real, estimate->tets / real);
  return estimate->tets / real;
}

TEST(EstimateElements, UniformSizesOnTheBenchShapesWithinTwiceTheRealCount) {
  const Case cases[] = {
      {"sphere surface 0.1", sphere_surface({0, 0, 0}, 1.0, 0.1), 0.1},
      {"sphere surface 0.1", sphere_surface({0, 0, 0}, 1.0, 0.1), 0.3},
      {"torus surface 0.06", torus_surface(1.0, 0.35, 0.06), 0.2},
      {"box surface 0.1", box_surface({0, 0, 0}, {1, 1, 1}, 0.1), 0.1},
      {"box surface 0.1", box_surface({0, 0, 0}, {1, 1, 1}, 0.1), 0.5},
      {"lblock surface 0.1", l_block_with_hole_surface(0.5, 0.1), 0.1},
      {"lblock surface 0.1", l_block_with_hole_surface(0.5, 0.1), 0.07},
  };
  for (const Case& c : cases) {
    VolumeParams params;
    params.size = c.size;
    const double ratio = ratio_for(c, params);
    // The goal is 2x; today's figures are 1.00 to 1.40, so a drift shows before that.
    EXPECT_GT(ratio, 0.75) << c.name << " at " << c.size;
    EXPECT_LT(ratio, 1.5) << c.name << " at " << c.size;
  }
}

TEST(EstimateElements, APointSourceWithinTwiceTheRealCount) {
  const Case c{"box surface 0.05, source", box_surface({0, 0, 0}, {1, 1, 1}, 0.05), 0.25};
  VolumeParams params;
  params.spec = SizeSpec{};
  params.spec->max_size = 0.25;
  params.spec->growth = 1.2;
  params.spec->sources.push_back(
      SizeSource{{{0.0, 0.0, 0.0}}, 0.05, 0.1, 0.3, PowerLaw{.gamma = 1.0}});
  const double ratio = ratio_for(c, params);
  EXPECT_GT(ratio, 0.75);
  EXPECT_LT(ratio, 1.5);
}

// The lattice integral (any field that is not a UniformSize) equals the closed form for a field
// that happens to be uniform: the divergence theorem is exact for it.
TEST(EstimateElements, LatticeIntegralOfAUniformFieldIsTheClosedForm) {
  const Mesh front = torus_surface(1.0, 0.35, 0.05);
  SizeSpec spec;
  spec.max_size = 0.04;
  absl::StatusOr<SpecSizeField> field =
      SpecSizeField::create(spec, Box{{-1.35, -1.35, -0.35}, {1.35, 1.35, 0.35}});
  ASSERT_TRUE(field.ok()) << field.status();
  const VolumeEstimate lattice = estimate_volume_mesh(front, *field, 0.04, 1.0);
  const VolumeEstimate closed = estimate_volume_mesh(front, UniformSize(0.04), 0.04, 1.0);
  EXPECT_NEAR(lattice.tets / closed.tets, 1.0, 1e-6);
}

// What the server refuses before meshing: the unit sphere at 1e-4 asks for about 10^13 tets,
// the volume over a regular tet times the mesh's extra tets per such volume.
TEST(EstimateElements, AHugeRequestIsCountedWithoutMeshing) {
  const Mesh front = sphere_surface({0, 0, 0}, 1.0, 0.1);
  VolumeParams params;
  params.size = 1e-4;
  absl::StatusOr<VolumeEstimate> estimate = estimate_volume_mesh(front, params);
  ASSERT_TRUE(estimate.ok());
  const double volume = 4.0 / 3.0 * M_PI;  // the polyhedron's volume is a little less
  const double regular = std::pow(1e-4, 3) / (6 * std::sqrt(2.0));
  EXPECT_GT(estimate->tets, 0.9 * volume / regular);
  EXPECT_LT(estimate->tets, 2.0 * volume / regular);
  EXPECT_GT(estimate->bytes, 100 * estimate->tets);
}

// Never hang (issue 10, part 2): a front over its element limit stops, saying where it was.
TEST(EstimateElements, AFrontOverItsTetLimitStopsWithAReport) {
  VolumeParams params;
  params.size = 0.1;
  params.max_tets = 1000;
  absl::StatusOr<VolumeResult> result =
      generate_volume_mesh(sphere_surface({0, 0, 0}, 1.0, 0.1), params, no_progress());
  ASSERT_FALSE(result.ok());
  EXPECT_EQ(result.status().code(), absl::StatusCode::kFailedPrecondition);
  EXPECT_THAT(std::string(result.status().message()),
              ::testing::HasSubstr("over its limit of 1000 (the size field asks for about 3"));
}

TEST(EstimateElements, AnInvalidSpecIsItsError) {
  VolumeParams params;
  params.spec = SizeSpec{};
  params.spec->max_size = -1;
  EXPECT_FALSE(estimate_volume_mesh(sphere_surface({0, 0, 0}, 1.0, 0.3), params).ok());
}

}  // namespace
}  // namespace afmesh
