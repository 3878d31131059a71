// Files written by gmsh and tetgen (tests/data, see its README.md). The expected counts are
// what meshio reports for the same files.
#include <map>
#include <string>

#include "core/io/mesh_io.h"
#include "gmock/gmock.h"
#include "gtest/gtest.h"
#include "tests/io/io_test_support.h"

namespace afmesh {
namespace {

using io_test::data_file;
using ::testing::Contains;
using ::testing::HasSubstr;

std::map<Index, int> count_tags(const std::vector<Index>& tags) {
  std::map<Index, int> counts;
  for (const Index tag : tags) ++counts[tag];
  return counts;
}

void expect_gmsh_box(const std::string& name) {
  ReadReport report;
  const absl::StatusOr<Mesh> mesh = read_mesh(data_file(name), &report);
  ASSERT_TRUE(mesh.ok()) << mesh.status();
  EXPECT_EQ(mesh->points.size(), 305u);
  EXPECT_EQ(mesh->triangles.size(), 508u);
  EXPECT_EQ(count_tags(mesh->triangle_tags), (std::map<Index, int>{{1, 136}, {2, 136}, {3, 236}}));
  EXPECT_EQ(mesh->tets.size(), 968u);
  EXPECT_EQ(count_tags(mesh->tet_tags), (std::map<Index, int>{{10, 968}}));
  EXPECT_THAT(report.notes, Contains(HasSubstr("skipped 1 point elements")));
  EXPECT_THAT(report.notes, Contains(HasSubstr("skipped 4 line elements")));
}

TEST(RealFiles, GmshMsh41Ascii) { expect_gmsh_box("gmsh_box_41.msh"); }

TEST(RealFiles, GmshMsh41Binary) { expect_gmsh_box("gmsh_box_41_binary.msh"); }

TEST(RealFiles, GmshMsh22) { expect_gmsh_box("gmsh_box_22.msh"); }

TEST(RealFiles, GmshAsciiAndBinaryGiveTheSameMesh) {
  const absl::StatusOr<Mesh> ascii = read_mesh(data_file("gmsh_box_41.msh"));
  const absl::StatusOr<Mesh> binary = read_mesh(data_file("gmsh_box_41_binary.msh"));
  const absl::StatusOr<Mesh> old = read_mesh(data_file("gmsh_box_22.msh"));
  ASSERT_TRUE(ascii.ok() && binary.ok() && old.ok());
  for (const Mesh* other : {&*binary, &*old}) {
    ASSERT_EQ(other->points.size(), ascii->points.size());
    // gmsh prints ascii coordinates with 16 significant digits, binary ones exactly.
    for (std::size_t i = 0; i < ascii->points.size(); ++i) {
      for (int axis = 0; axis < 3; ++axis) {
        EXPECT_NEAR(other->points[i][axis], ascii->points[i][axis], 1e-15) << "point " << i;
      }
    }
    EXPECT_EQ(other->triangles, ascii->triangles);
    EXPECT_EQ(other->triangle_tags, ascii->triangle_tags);
    EXPECT_EQ(other->tets, ascii->tets);
    EXPECT_EQ(other->tet_tags, ascii->tet_tags);
  }
}

TEST(RealFiles, TruncatedGmshBinaryNamesTheByteOffset) {
  const std::string path = data_file("gmsh_box_41_binary.msh");
  absl::StatusOr<Mesh> whole = read_mesh(path);
  ASSERT_TRUE(whole.ok());
  io_test::TempDir dir;
  std::string bytes;
  {
    std::FILE* file = std::fopen(path.c_str(), "rb");
    ASSERT_NE(file, nullptr);
    char buffer[4096];
    while (const std::size_t got = std::fread(buffer, 1, sizeof buffer, file))
      bytes.append(buffer, got);
    std::fclose(file);
  }
  bytes.resize(bytes.size() / 2);
  io_test::write_file(dir.file("cut.msh"), bytes);
  const absl::StatusOr<Mesh> cut = read_mesh(dir.file("cut.msh"));
  ASSERT_FALSE(cut.ok());
  EXPECT_THAT(std::string(cut.status().message()), HasSubstr(dir.file("cut.msh") + ": byte "));
  EXPECT_THAT(std::string(cut.status().message()), HasSubstr("but the file ends"));
}

TEST(RealFiles, GmshMultiSolidAsciiStl) {
  const absl::StatusOr<Mesh> mesh = read_mesh(data_file("gmsh_box_surface.stl"));
  ASSERT_TRUE(mesh.ok()) << mesh.status();
  EXPECT_EQ(mesh->points.size(), 256u);
  EXPECT_EQ(mesh->triangles.size(), 508u);
  // One solid per physical surface, in file order.
  EXPECT_EQ(count_tags(mesh->triangle_tags), (std::map<Index, int>{{1, 136}, {2, 136}, {3, 236}}));
}

TEST(RealFiles, TetgenMedit) {
  ReadReport report;
  const absl::StatusOr<Mesh> mesh = read_mesh(data_file("tetgen_cube.mesh"), &report);
  ASSERT_TRUE(mesh.ok()) << mesh.status();
  EXPECT_EQ(mesh->points.size(), 78u);
  EXPECT_EQ(mesh->triangles.size(), 416u);
  EXPECT_EQ(count_tags(mesh->triangle_tags),
            (std::map<Index, int>{{0, 272}, {1, 24}, {2, 24}, {3, 24}, {4, 24}, {5, 24}, {6, 24}}));
  EXPECT_EQ(mesh->tets.size(), 172u);
  EXPECT_EQ(count_tags(mesh->tet_tags), (std::map<Index, int>{{0, 172}}));
  EXPECT_THAT(report.notes, Contains(HasSubstr("Edges (48 entries)")));
  EXPECT_THAT(report.notes, Contains(HasSubstr("Corners (8 entries)")));
}

}  // namespace
}  // namespace afmesh
