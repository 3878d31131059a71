// Background grids read from files (core/io/sized_grid.h): a linear size field saved by gmsh,
// and one written by afmesh, are reproduced exactly by the grid's interpolation.
#include <gtest/gtest.h>

#include <random>
#include <string>
#include <vector>

#include "core/io/sized_grid.h"
#include "core/sizing/background_grid.h"

namespace afmesh {
namespace {

// The field of tests/data/gmsh_box_sizes_*.msh over the box [0, 1] × [0, 1] × [0, 0.5].
double gmsh_field(const Point& x) { return 0.1 + 0.2 * x[0] + 0.3 * x[1] + 0.4 * x[2]; }

BackgroundGrid grid_from(SizedGrid file) {
  absl::StatusOr<BackgroundGrid> grid = BackgroundGrid::from_arrays(
      std::move(file.mesh.points), std::move(file.mesh.tets), std::move(file.sizes));
  EXPECT_TRUE(grid.ok()) << grid.status();
  return *std::move(grid);
}

// Random points in the box and its corners, edge midpoints and centre: the size is the linear
// field to 1e-12 relative (gmsh's ascii values carry 16 digits, its binary ones are exact).
void expect_linear_field_reproduced(const std::string& name) {
  absl::StatusOr<SizedGrid> file =
      read_sized_grid(std::string(AFMESH_SOURCE_DIR) + "/tests/data/" + name);
  ASSERT_TRUE(file.ok()) << file.status();
  const BackgroundGrid grid = grid_from(*std::move(file));
  std::vector<Point> probes = {
      {0, 0, 0}, {1, 1, 0.5}, {0.5, 0.5, 0.25}, {1, 0, 0.25}, {0, 0.5, 0.5}};
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (int i = 0; i < 1000; ++i) probes.push_back({u(rng), u(rng), 0.5 * u(rng)});
  BackgroundGrid::Hint hint;
  for (const Point& x : probes) {
    const double expected = gmsh_field(x);
    EXPECT_NEAR(grid.size_at(x, &hint), expected, 1e-12 * expected)
        << name << " at " << x[0] << " " << x[1] << " " << x[2];
  }
}

TEST(BackgroundGridFile, GmshMsh41AsciiReproducesALinearField) {
  expect_linear_field_reproduced("gmsh_box_sizes_41.msh");
}

TEST(BackgroundGridFile, GmshMsh41BinaryReproducesALinearField) {
  expect_linear_field_reproduced("gmsh_box_sizes_41_binary.msh");
}

TEST(BackgroundGridFile, GmshMsh22ReproducesALinearField) {
  expect_linear_field_reproduced("gmsh_box_sizes_22.msh");
}

// A grid written by write_sized_grid and read back gives the same size, bit for bit, as the grid
// it was written from.
TEST(BackgroundGridFile, WrittenGridAnswersLikeTheOriginal) {
  const BackgroundGrid original = BackgroundGrid::box_grid(Box{{-1, 0, 2}, {3, 0.5, 2.7}}, 1.0);
  Mesh mesh;
  mesh.points = original.points();
  mesh.tets = original.tets();
  mesh.tet_tags.assign(mesh.tets.size(), 0);
  std::vector<double> sizes;
  for (const Point& p : mesh.points) sizes.push_back(0.3 + 0.1 * p[0] + p[1] / 3.0 + 0.01 * p[2]);
  const BackgroundGrid reference = grid_from({mesh, sizes});
  const std::string dir = ::testing::TempDir();
  for (const std::string name : {"written_grid.msh", "written_grid.mesh"}) {
    ASSERT_TRUE(write_sized_grid(mesh, sizes, dir + "/" + name).ok());
    absl::StatusOr<SizedGrid> file = read_sized_grid(dir + "/" + name);
    ASSERT_TRUE(file.ok()) << file.status();
    const BackgroundGrid read = grid_from(*std::move(file));
    std::mt19937 rng(5);
    std::uniform_real_distribution<double> x(-1.5, 3.5), y(-0.2, 0.7), z(1.8, 2.9);
    for (int i = 0; i < 500; ++i) {
      const Point p{x(rng), y(rng), z(rng)};
      EXPECT_EQ(read.size_at(p), reference.size_at(p)) << name;
    }
  }
}

}  // namespace
}  // namespace afmesh
