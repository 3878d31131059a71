// Background-grid files (core/io/sized_grid.h): MSH $NodeData and Medit .mesh + .sol, written
// and read back exactly, files written by gmsh itself, and malformed files named by line.
#include "core/io/sized_grid.h"

#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include "core/io/file_bytes.h"
#include "core/io/medit.h"
#include "core/io/mesh_io.h"
#include "core/io/msh.h"
#include "gmock/gmock.h"
#include "gtest/gtest.h"
#include "tests/io/io_test_support.h"

namespace afmesh {
namespace {

using io_test::data_file;
using io_test::expect_same_mesh;
using io_test::same_bits;
using io_test::tagged_box;
using io_test::TempDir;
using io_test::write_file;
using io_test::written;
using ::testing::Contains;
using ::testing::HasSubstr;

// Awkward sizes (not exact in binary, tiny and huge), one per point of tagged_box().
std::vector<double> awkward_sizes() {
  return {0.1, 1.0 / 3.0, 2.5e-3, 7.0, 1e-300, 1e300, 0.30000000000000004, 5e-324};
}

// tagged_box() as a grid file reads it: tets only.
Mesh tagged_box_tets() {
  Mesh mesh = tagged_box();
  mesh.triangles.clear();
  mesh.triangle_tags.clear();
  return mesh;
}

void expect_same_sizes(const std::vector<double>& actual, const std::vector<double>& expected) {
  ASSERT_EQ(actual.size(), expected.size());
  for (std::size_t i = 0; i < actual.size(); ++i) {
    EXPECT_TRUE(same_bits(actual[i], expected[i]))
        << "size " << i << ": " << actual[i] << " vs " << expected[i];
  }
}

void expect_round_trip(const std::string& name) {
  TempDir dir;
  const std::string path = dir.file(name);
  ASSERT_TRUE(write_sized_grid(tagged_box(), awkward_sizes(), path).ok());
  ReadReport report;
  absl::StatusOr<SizedGrid> grid = read_sized_grid(path, &report);
  ASSERT_TRUE(grid.ok()) << grid.status();
  expect_same_mesh(grid->mesh, tagged_box_tets());
  expect_same_sizes(grid->sizes, awkward_sizes());
  EXPECT_THAT(report.notes, Contains(HasSubstr("ignored the 12 triangles")));
}

TEST(SizedGrid, MshRoundTripIsBitExact) { expect_round_trip("grid.msh"); }

TEST(SizedGrid, MeditWithSolRoundTripIsBitExact) { expect_round_trip("grid.mesh"); }

TEST(SizedGrid, MeditWriteCreatesTheSolBesideTheMesh) {
  TempDir dir;
  ASSERT_TRUE(write_sized_grid(tagged_box(), awkward_sizes(), dir.file("g.mesh")).ok());
  EXPECT_TRUE(std::filesystem::exists(dir.file("g.sol")));
  EXPECT_EQ(medit_sol_path("/a/b.c/grid.mesh"), "/a/b.c/grid.sol");
}

TEST(SizedGrid, WriteRefusesBadSizesBeforeCreatingAFile) {
  TempDir dir;
  std::vector<double> sizes = awkward_sizes();
  sizes[3] = 0.0;
  const absl::Status status = write_sized_grid(tagged_box(), sizes, dir.file("bad.msh"));
  EXPECT_THAT(status.message(), HasSubstr("size 3 must be finite and > 0"));
  EXPECT_FALSE(std::filesystem::exists(dir.file("bad.msh")));
  sizes.pop_back();
  EXPECT_THAT(write_sized_grid(tagged_box(), sizes, dir.file("bad.mesh")).message(),
              HasSubstr("8 points but 7 sizes"));
}

// gmsh_box_sizes_*.msh (tests/data/README.md): the sizes are 0.1 + 0.2 x + 0.3 y + 0.4 z.
void expect_gmsh_sizes(const std::string& name, double tolerance) {
  ReadReport report;
  absl::StatusOr<SizedGrid> grid = read_sized_grid(data_file(name), &report);
  ASSERT_TRUE(grid.ok()) << grid.status();
  EXPECT_EQ(grid->mesh.points.size(), 56u);
  EXPECT_EQ(grid->sizes.size(), 56u);
  EXPECT_GT(grid->mesh.tets.size(), 100u);
  EXPECT_TRUE(grid->mesh.triangles.empty());
  for (std::size_t i = 0; i < grid->sizes.size(); ++i) {
    const Point& p = grid->mesh.points[i];
    const double law = 0.1 + 0.2 * p[0] + 0.3 * p[1] + 0.4 * p[2];
    EXPECT_NEAR(grid->sizes[i], law, tolerance * law) << "point " << i;
  }
  EXPECT_THAT(report.notes, Contains(HasSubstr("$InterpolationScheme")));
}

// gmsh prints ascii values with 16 significant digits; binary ones are exact.
TEST(SizedGrid, ReadsGmshMsh41AsciiNodeData) { expect_gmsh_sizes("gmsh_box_sizes_41.msh", 1e-15); }

TEST(SizedGrid, ReadsGmshMsh41BinaryNodeData) {
  expect_gmsh_sizes("gmsh_box_sizes_41_binary.msh", 1e-16);
}

TEST(SizedGrid, ReadsGmshMsh22NodeData) { expect_gmsh_sizes("gmsh_box_sizes_22.msh", 1e-15); }

TEST(SizedGrid, PlainMeshReadingStillSkipsNodeDataWithANote) {
  ReadReport report;
  absl::StatusOr<std::string> bytes = read_file_bytes(data_file("gmsh_box_sizes_41.msh"));
  ASSERT_TRUE(bytes.ok());
  absl::StatusOr<Mesh> mesh = parse_msh(*bytes, "box.msh", &report);
  ASSERT_TRUE(mesh.ok()) << mesh.status();
  EXPECT_THAT(report.notes, Contains(HasSubstr("skipped MSH section $NodeData")));
}

// ---------------------------------------------------------------------------------------------
// Malformed MSH node data.

// A one-tet MSH 4.1 file followed by `node_data` (the lines after "$NodeData").
std::string one_tet_msh(const std::string& node_data) {
  return "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n"
         "$Nodes\n1 4 1 4\n3 1 0 4\n1\n2\n3\n4\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n$EndNodes\n"
         "$Elements\n1 1 1 1\n3 1 4 1\n1 1 2 3 4\n$EndElements\n"
         "$NodeData\n" +
         node_data + "$EndNodeData\n";
}

constexpr const char* kViewHeader = "1\n\"size\"\n1\n0\n3\n0\n1\n4\n";  // lines 22 to 29

absl::Status msh_error(const std::string& text) {
  return parse_msh_sized_grid(text, "grid.msh").status();
}

TEST(SizedGridMsh, OneTetFileReads) {
  absl::StatusOr<SizedGrid> grid =
      parse_msh_sized_grid(one_tet_msh(std::string(kViewHeader) + "1 1\n2 2\n3 3\n4 0.5\n"), "g");
  ASSERT_TRUE(grid.ok()) << grid.status();
  EXPECT_EQ(grid->sizes, (std::vector<double>{1, 2, 3, 0.5}));
}

TEST(SizedGridMsh, NodesInBlocksOutOfOrderMapByTag) {
  const std::string text =
      "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n"
      "$Nodes\n2 4 10 40\n3 1 0 2\n40\n10\n0 0 1\n0 0 0\n3 1 0 2\n30\n20\n0 1 0\n1 0 0\n"
      "$EndNodes\n$Elements\n1 1 1 1\n3 1 4 1\n1 10 20 30 40\n$EndElements\n"
      "$NodeData\n1\n\"a view name with blanks\"\n0\n4\n0\n1\n4\n0\n"
      "10 1\n20 2\n30 3\n40 4\n$EndNodeData\n";
  absl::StatusOr<SizedGrid> grid = parse_msh_sized_grid(text, "g");
  ASSERT_TRUE(grid.ok()) << grid.status();
  // Points in file order: tags 40, 10, 30, 20.
  EXPECT_EQ(grid->sizes, (std::vector<double>{4, 1, 3, 2}));
}

TEST(SizedGridMsh, MissingNodeDataIsAnError) {
  const std::string text = one_tet_msh("");
  const std::string no_data = text.substr(0, text.find("$NodeData"));
  EXPECT_THAT(msh_error(no_data).message(), HasSubstr("grid.msh: no $NodeData section"));
}

TEST(SizedGridMsh, WrongCountNamesTheLine) {
  const std::string header = "1\n\"size\"\n1\n0\n3\n0\n1\n3\n";
  EXPECT_THAT(msh_error(one_tet_msh(header + "1 1\n2 2\n3 3\n")).message(),
              HasSubstr("grid.msh:29: the $NodeData view gives values for 3 nodes, but $Nodes "
                        "defines 4"));
}

TEST(SizedGridMsh, FewerEntriesThanDeclaredIsAnError) {
  EXPECT_THAT(msh_error(one_tet_msh(std::string(kViewHeader) + "1 1\n2 2\n3 3\n")).message(),
              HasSubstr("grid.msh:33: expected an integer (a node tag), found '$EndNodeData'"));
}

TEST(SizedGridMsh, VectorViewIsRefused) {
  const std::string header = "1\n\"v\"\n1\n0\n3\n0\n3\n4\n";
  EXPECT_THAT(msh_error(one_tet_msh(header)).message(),
              HasSubstr("grid.msh:29: the $NodeData view has 3 components per node"));
}

TEST(SizedGridMsh, NonFiniteSizeNamesTheLine) {
  EXPECT_THAT(msh_error(one_tet_msh(std::string(kViewHeader) + "1 1\n2 nan\n3 3\n4 4\n")).message(),
              HasSubstr("grid.msh:31: the size of node tag 2 must be finite and > 0, found nan"));
  EXPECT_THAT(msh_error(one_tet_msh(std::string(kViewHeader) + "1 1\n2 2\n3 inf\n4 4\n")).message(),
              HasSubstr("grid.msh:32: the size of node tag 3 must be finite and > 0, found inf"));
}

TEST(SizedGridMsh, SizeNotPositiveNamesTheLine) {
  EXPECT_THAT(msh_error(one_tet_msh(std::string(kViewHeader) + "1 1\n2 2\n3 3\n4 0\n")).message(),
              HasSubstr("grid.msh:33: the size of node tag 4 must be finite and > 0, found 0"));
  EXPECT_THAT(msh_error(one_tet_msh(std::string(kViewHeader) + "1 -1\n2 2\n3 3\n4 4\n")).message(),
              HasSubstr("grid.msh:30: the size of node tag 1 must be finite and > 0, found -1"));
}

TEST(SizedGridMsh, UnknownNodeTagNamesTheLine) {
  EXPECT_THAT(msh_error(one_tet_msh(std::string(kViewHeader) + "1 1\n2 2\n7 3\n4 4\n")).message(),
              HasSubstr("grid.msh:32: $NodeData gives a size for node tag 7, which $Nodes does "
                        "not define"));
}

TEST(SizedGridMsh, RepeatedNodeTagNamesTheLine) {
  EXPECT_THAT(msh_error(one_tet_msh(std::string(kViewHeader) + "1 1\n2 2\n2 3\n4 4\n")).message(),
              HasSubstr("grid.msh:32: $NodeData gives node tag 2 a second size"));
}

TEST(SizedGridMsh, GarbageSizeNamesTheLine) {
  EXPECT_THAT(msh_error(one_tet_msh(std::string(kViewHeader) + "1 1\n2 big\n3 3\n4 4\n")).message(),
              HasSubstr("grid.msh:31: expected a number (the size of a node), found 'big'"));
}

TEST(SizedGridMsh, TooFewIntegerTagsIsAnError) {
  EXPECT_THAT(msh_error(one_tet_msh("0\n0\n2\n0\n1\n")).message(),
              HasSubstr("needs at least 3 integer tags"));
}

TEST(SizedGridMsh, NodeDataBeforeNodesIsAnError) {
  const std::string text =
      "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$NodeData\n0\n0\n3\n0\n1\n0\n$EndNodeData\n";
  EXPECT_THAT(msh_error(text).message(), HasSubstr("grid.msh:4: $NodeData before $Nodes"));
}

TEST(SizedGridMsh, LaterViewsAreSkippedWithANote) {
  std::string text = one_tet_msh(std::string(kViewHeader) + "1 1\n2 2\n3 3\n4 4\n");
  text += "$NodeData\n" + std::string(kViewHeader) + "1 9\n2 9\n3 9\n4 9\n$EndNodeData\n";
  ReadReport report;
  absl::StatusOr<SizedGrid> grid = parse_msh_sized_grid(text, "g", &report);
  ASSERT_TRUE(grid.ok()) << grid.status();
  EXPECT_EQ(grid->sizes, (std::vector<double>{1, 2, 3, 4}));
  EXPECT_THAT(report.notes, Contains(HasSubstr("skipped a later $NodeData section")));
}

TEST(SizedGridMsh, Msh22NodeDataErrorsNameTheLine) {
  const std::string text =
      "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n"
      "$Nodes\n4\n1 0 0 0\n2 1 0 0\n3 0 1 0\n4 0 0 1\n$EndNodes\n"
      "$Elements\n1\n1 4 2 0 1 1 2 3 4\n$EndElements\n"
      "$NodeData\n1\n\"size\"\n1\n0\n3\n0\n1\n4\n1 1\n2 2\n3 3\n5 4\n$EndNodeData\n";
  EXPECT_THAT(msh_error(text).message(),
              HasSubstr("grid.msh:27: $NodeData gives a size for node tag 5"));
}

TEST(SizedGridMsh, TruncatedBinaryNodeDataNamesTheByteOffset) {
  absl::StatusOr<std::string> bytes = read_file_bytes(data_file("gmsh_box_sizes_41_binary.msh"));
  ASSERT_TRUE(bytes.ok());
  const std::string cut = bytes->substr(0, bytes->size() - 40);
  EXPECT_THAT(msh_error(cut).message(), HasSubstr("grid.msh: byte "));
}

// ---------------------------------------------------------------------------------------------
// Malformed Medit .sol files.

constexpr const char* kSolHeader = "MeshVersionFormatted 2\nDimension 3\nSolAtVertices\n";

absl::Status sol_error(const std::string& text, std::size_t vertices = 3) {
  return parse_medit_sol(text, "grid.sol", vertices).status();
}

TEST(SizedGridSol, ReadsScalarsWithCommentsAndAnyCase) {
  absl::StatusOr<std::vector<double>> sizes = parse_medit_sol(
      "# sizes\nmeshversionformatted 1\ndimension 3\nsolatvertices\n3\n1 1\n0.5\n1e-3 # x\n2\n"
      "end\n",
      "g.sol", 3);
  ASSERT_TRUE(sizes.ok()) << sizes.status();
  EXPECT_EQ(*sizes, (std::vector<double>{0.5, 1e-3, 2}));
}

TEST(SizedGridSol, WrongCountNamesTheLine) {
  EXPECT_THAT(sol_error(std::string(kSolHeader) + "2\n1 1\n1\n2\nEnd\n").message(),
              HasSubstr("grid.sol:4: SolAtVertices gives values for 2 vertices, but the mesh has "
                        "3"));
}

TEST(SizedGridSol, SeveralSolutionsOrNonScalarTypesAreRefused) {
  EXPECT_THAT(sol_error(std::string(kSolHeader) + "3\n2 1 1\n").message(),
              HasSubstr("grid.sol:5: SolAtVertices holds 2 solutions per vertex"));
  EXPECT_THAT(sol_error(std::string(kSolHeader) + "3\n1 3\n").message(),
              HasSubstr("grid.sol:5: solution type 3 (a symmetric tensor (an anisotropic "
                        "metric)) is not supported"));
  EXPECT_THAT(sol_error(std::string(kSolHeader) + "3\n1 2\n").message(),
              HasSubstr("solution type 2 (a vector)"));
}

TEST(SizedGridSol, BadValuesNameTheLine) {
  EXPECT_THAT(sol_error(std::string(kSolHeader) + "3\n1 1\n1\n-2\n3\nEnd\n").message(),
              HasSubstr("grid.sol:7: the size of vertex 2 must be finite and > 0, found -2"));
  EXPECT_THAT(sol_error(std::string(kSolHeader) + "3\n1 1\n1\n2\nnan\nEnd\n").message(),
              HasSubstr("grid.sol:8: the size of vertex 3 must be finite and > 0, found nan"));
  EXPECT_THAT(sol_error(std::string(kSolHeader) + "3\n1 1\n1\n2\nEnd\n").message(),
              HasSubstr("grid.sol:8: expected a number (the size of a vertex), found 'End'"));
}

TEST(SizedGridSol, MissingSectionOtherKeywordsAndMissingEndAreErrors) {
  EXPECT_THAT(sol_error("MeshVersionFormatted 2\nDimension 3\nEnd\n").message(),
              HasSubstr("grid.sol:3: no SolAtVertices section"));
  EXPECT_THAT(sol_error("MeshVersionFormatted 2\nDimension 3\nSolAtTetrahedra\n1\n").message(),
              HasSubstr("grid.sol:3: expected 'SolAtVertices' or 'End', found "
                        "'SolAtTetrahedra'"));
  EXPECT_THAT(sol_error(std::string(kSolHeader) + "3\n1 1\n1\n2\n3\n").message(),
              HasSubstr("expected 'SolAtVertices' or 'End', found end of file"));
  EXPECT_THAT(sol_error("MeshVersionFormatted 2\nDimension 2\n").message(),
              HasSubstr("grid.sol:2: Dimension 2 is not supported"));
}

TEST(SizedGridSol, MissingSolNamesTheExpectedPath) {
  TempDir dir;
  ASSERT_TRUE(write_mesh(tagged_box(), dir.file("g.mesh")).ok());
  const absl::Status status = read_sized_grid(dir.file("g.mesh")).status();
  EXPECT_EQ(status.code(), absl::StatusCode::kNotFound);
  EXPECT_THAT(status.message(), HasSubstr(dir.file("g.sol")));
}

TEST(SizedGridSol, BinarySolbIsRefusedClearly) {
  TempDir dir;
  ASSERT_TRUE(write_mesh(tagged_box(), dir.file("g.mesh")).ok());
  write_file(dir.file("g.solb"), std::string("\x01\x00\x00\x00", 4));
  const absl::Status status = read_sized_grid(dir.file("g.mesh")).status();
  EXPECT_EQ(status.code(), absl::StatusCode::kInvalidArgument);
  EXPECT_THAT(status.message(), HasSubstr("binary Medit solutions (.solb) are not read"));
}

TEST(SizedGrid, OtherExtensionsAndGridsWithoutTetsAreRefused) {
  EXPECT_THAT(read_sized_grid("grid.vtu").status().message(),
              HasSubstr("expected .msh (gmsh, sizes in a $NodeData view) or .mesh"));
  EXPECT_THAT(read_sized_grid("grid.sol").status().message(), HasSubstr("name the .mesh file"));
  TempDir dir;
  Mesh surface = tagged_box();
  surface.tets.clear();
  surface.tet_tags.clear();
  ASSERT_TRUE(write_sized_grid(surface, awkward_sizes(), dir.file("s.msh")).ok());
  EXPECT_THAT(read_sized_grid(dir.file("s.msh")).status().message(),
              HasSubstr("no tetrahedra: a background grid is a tetrahedral mesh"));
}

}  // namespace
}  // namespace afmesh
