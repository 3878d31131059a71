#include "core/io/msh.h"

#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

#include "absl/strings/str_split.h"
#include "gmock/gmock.h"
#include "gtest/gtest.h"
#include "tests/io/io_test_support.h"

namespace afmesh {
namespace {

using io_test::expect_same_mesh;
using io_test::tagged_box;
using io_test::written;
using ::testing::Contains;
using ::testing::ElementsAre;
using ::testing::EndsWith;
using ::testing::HasSubstr;

std::string msh_text(const Mesh& mesh) {
  return written([&](OutputBuffer& out) { return write_msh(mesh, out); });
}

TEST(Msh, RoundTripIsBitExactAndKeepsElementOrder) {
  Mesh mesh = tagged_box();
  mesh.points[1][2] = -0.0;
  mesh.points[4][0] = 1e-300;
  absl::StatusOr<Mesh> read = parse_msh(msh_text(mesh), "box.msh");
  ASSERT_TRUE(read.ok()) << read.status();
  expect_same_mesh(*read, mesh);
}

// The lines of the $Entities section after its counts line.
std::vector<std::string> entity_lines(const std::string& text) {
  const std::size_t begin = text.find("$Entities\n");
  const std::size_t end = text.find("$EndEntities\n");
  std::vector<std::string> lines = absl::StrSplit(
      text.substr(begin, end - begin), '\n', absl::SkipEmpty());
  lines.erase(lines.begin(), lines.begin() + 2);  // "$Entities", the counts
  return lines;
}

TEST(Msh, TagZeroElementsRoundTripAsPhysicalTagZero) {
  Mesh mesh = tagged_box();
  mesh.triangle_tags = {0, 3, 0, 3, 0, 3, 0, 3, 0, 3, 0, 3};
  mesh.tet_tags = {0, 0, 0, 0, 0, 0};
  const std::string text = msh_text(mesh);
  // Entities: "0 0 <surfaces> <volumes>": one surface per tag (0 and 3), one volume (tag 0).
  EXPECT_THAT(text, HasSubstr("$Entities\n0 0 2 1\n"));
  // Each ends "<numPhysicalTags> <tag> <numBounding>": one physical tag each, 0 included, so
  // that meshio finds a gmsh:physical array for every element block.
  EXPECT_THAT(entity_lines(text), ElementsAre(EndsWith(" 1 0 0"), EndsWith(" 1 3 0"),
                                              EndsWith(" 1 0 0")));
  absl::StatusOr<Mesh> read = parse_msh(text, "zero.msh");
  ASSERT_TRUE(read.ok()) << read.status();
  expect_same_mesh(*read, mesh);
}

TEST(Msh, PointsOnlyMeshRoundTrips) {
  Mesh mesh;
  mesh.points = {{1, 2, 3}, {4, 5, 6}};
  absl::StatusOr<Mesh> read = parse_msh(msh_text(mesh), "points.msh");
  ASSERT_TRUE(read.ok()) << read.status();
  expect_same_mesh(*read, mesh);
}

TEST(Msh, WriteRefusesNegativeTags) {
  Mesh mesh = tagged_box();
  mesh.tet_tags[2] = -4;
  std::string bytes;
  OutputBuffer out(&bytes);
  const absl::Status status = write_msh(mesh, out);
  EXPECT_EQ(status.code(), absl::StatusCode::kInvalidArgument);
  EXPECT_THAT(std::string(status.message()), HasSubstr("tetrahedron 2 has tag -4"));
}

// Nodes in three entity blocks with sparse tags (one above 2^32), elements out of tag order,
// a point and a line element, and a $PhysicalNames section.
constexpr const char* kSparse41 = R"($MeshFormat
4.1 0 8
$EndMeshFormat
$PhysicalNames
2
2 5 "wall"
3 9 "fluid"
$EndPhysicalNames
$Entities
1 1 1 1
1 0 0 0 1 15
1 0 0 0 1 0 0 0 2 1 -1
1 0 0 0 1 1 0 1 5 0
1 0 0 0 1 1 1 1 9 0
$EndEntities
$Nodes
3 5 5 1099511627776
0 1 0 1
1000
0 0 0
2 1 0 2
5
77
1 0 0
0 1 0
3 1 0 2
1099511627776
8
0 0 1
0.25 0.25 0.25
$EndNodes
$Elements
4 5 1 20
0 1 15 1
20 1000
1 1 1 1
19 1000 5
2 1 2 2
3 1000 5 77
2 1000 77 1099511627776
3 1 4 1
1 1000 5 77 1099511627776
$EndElements
)";

TEST(Msh, Reads41WithSparseNodeTagsInSeveralBlocks) {
  ReadReport report;
  absl::StatusOr<Mesh> read = parse_msh(kSparse41, "sparse.msh", &report);
  ASSERT_TRUE(read.ok()) << read.status();
  EXPECT_EQ(read->points,
            (std::vector<Point>{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {0.25, 0.25, 0.25}}));
  EXPECT_EQ(read->triangles, (std::vector<Triangle>{{0, 2, 3}, {0, 1, 2}}));
  EXPECT_EQ(read->triangle_tags, (std::vector<Index>{5, 5}));
  EXPECT_EQ(read->tets, (std::vector<Tet>{{0, 1, 2, 3}}));
  EXPECT_EQ(read->tet_tags, (std::vector<Index>{9}));
  EXPECT_THAT(report.notes, Contains(HasSubstr("skipped 1 point elements (gmsh type 15)")));
  EXPECT_THAT(report.notes, Contains(HasSubstr("skipped 1 line elements (gmsh type 1)")));
  EXPECT_THAT(report.notes, Contains(HasSubstr("$PhysicalNames")));
}

constexpr const char* kMsh22 = R"($MeshFormat
2.2 0 8
$EndMeshFormat
$Nodes
4
10 0 0 0
20 1 0 0
30 0 1 0
40 0 0 1
$EndNodes
$Elements
5
1 15 2 0 1 10
2 1 2 0 1 10 20
3 2 2 6 1 10 20 30
5 4 2 9 1 10 20 30 40
4 2 0 10 30 40
$EndElements
)";

TEST(Msh, Reads22WithPhysicalTags) {
  ReadReport report;
  absl::StatusOr<Mesh> read = parse_msh(kMsh22, "old.msh", &report);
  ASSERT_TRUE(read.ok()) << read.status();
  EXPECT_EQ(read->points.size(), 4u);
  EXPECT_EQ(read->triangles, (std::vector<Triangle>{{0, 1, 2}, {0, 2, 3}}));
  EXPECT_EQ(read->triangle_tags, (std::vector<Index>{6, 0}));
  EXPECT_EQ(read->tets, (std::vector<Tet>{{0, 1, 2, 3}}));
  EXPECT_EQ(read->tet_tags, (std::vector<Index>{9}));
  EXPECT_THAT(report.notes, Contains(HasSubstr("skipped 1 point elements")));
  EXPECT_THAT(report.notes, Contains(HasSubstr("skipped 1 line elements")));
}

// Malformed input.

void expect_error(const std::string& bytes, const std::string& where, const std::string& what) {
  const absl::StatusOr<Mesh> read = parse_msh(bytes, "bad.msh");
  ASSERT_FALSE(read.ok());
  EXPECT_EQ(read.status().code(), absl::StatusCode::kInvalidArgument);
  const std::string message(read.status().message());
  EXPECT_THAT(message, HasSubstr(where));
  EXPECT_THAT(message, HasSubstr(what));
}

// kSparse41 with the first occurrence of `from` replaced by `to`.
std::string sparse_with(const std::string& from, const std::string& to) {
  std::string text = kSparse41;
  const std::size_t at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  return text.replace(at, from.size(), to);
}

TEST(MshMalformed, EmptyFile) { expect_error("", "bad.msh", "empty"); }

TEST(MshMalformed, NotAnMshFile) {
  expect_error("solid x\n", "bad.msh:1:", "expected '$MeshFormat'");
}

TEST(MshMalformed, Version40) {
  expect_error("$MeshFormat\n4 0 8\n$EndMeshFormat\n",
               "bad.msh:2:", "MSH version '4' is not supported (afmesh reads 4.1 and 2.2)");
}

TEST(MshMalformed, Binary22) {
  expect_error("$MeshFormat\n2.2 1 8\n", "bad.msh:2:", "binary MSH 2 is not supported");
}

TEST(MshMalformed, HeaderDeclaresMoreNodesThanBlocksHold) {
  expect_error(sparse_with("3 5 5 1099511627776", "3 6 5 1099511627776"),
               "bad.msh:30:", "the $Nodes header declares 6 nodes, but its blocks hold 5");
}

TEST(MshMalformed, BlockDeclaresMoreNodesThanPresent) {
  expect_error(sparse_with("3 1 0 2\n", "3 1 0 3\n"),
               "bad.msh:", "node blocks hold more nodes than the 5 the $Nodes header declares");
}

TEST(MshMalformed, BlocksHoldFewerNodesThanTheyDeclare) {
  expect_error(sparse_with("3 5 5 1099511627776\n", "4 5 5 1099511627776\n"),
               "bad.msh:31:", "expected an integer (the entity dimension), found '$EndNodes'");
}

TEST(MshMalformed, ElementCountMismatch) {
  expect_error(sparse_with("4 5 1 20", "4 7 1 20"),
               "bad.msh:", "the $Elements header declares 7 elements, but its blocks hold 5");
}

TEST(MshMalformed, UnknownNodeTag) {
  expect_error(sparse_with("3 1000 5 77\n", "3 1000 5 78\n"),
               "bad.msh:39:", "element 3 refers to node tag 78, which $Nodes does not define");
}

TEST(MshMalformed, UnsupportedElementType) {
  expect_error(sparse_with("2 1 2 2\n", "2 1 3 2\n"),
               "bad.msh:38:", "element type 3 (4-node quadrangle) is not supported");
}

TEST(MshMalformed, SecondOrderTetrahedron) {
  expect_error(sparse_with("3 1 4 1\n", "3 1 11 1\n"), "bad.msh:41:",
               "element type 11 (10-node second order tetrahedron) is not supported");
}

TEST(MshMalformed, NanCoordinate) {
  expect_error(sparse_with("0 1 0\n", "0 nan 0\n"),
               "bad.msh:25:", "expected a finite number (a node coordinate), found 'nan'");
}

TEST(MshMalformed, DuplicateNodeTag) {
  expect_error(sparse_with("77\n", "5\n"), "bad.msh:23:", "node tag 5 appears twice");
}

TEST(MshMalformed, UndeclaredEntity) {
  expect_error(sparse_with("2 1 2 2\n", "2 4 2 2\n"),
               "bad.msh:38:", "refers to surface entity 4, which $Entities does not declare");
}

TEST(MshMalformed, GarbageToken) {
  expect_error(sparse_with("19 1000 5", "19 1000 5z"), "bad.msh:37:", "found '5z'");
}

TEST(MshMalformed, TruncatedInElements) {
  std::string text = kSparse41;
  text.resize(text.find("3 1 4 1"));
  expect_error(text, "bad.msh:41:", "found end of file");
}

TEST(MshMalformed, MissingElementsSection) {
  std::string text = kSparse41;
  text.resize(text.find("$Elements"));
  expect_error(text, "bad.msh:", "the file has no $Elements section");
}

TEST(MshMalformed, MissingSectionEnd) {
  std::string text = kSparse41;
  text.resize(text.find("$EndPhysicalNames"));
  expect_error(text, "bad.msh:4:", "section $PhysicalNames has no $EndPhysicalNames");
}

TEST(MshMalformed, Msh22IndexOutOfRange) {
  std::string text = kMsh22;
  text.replace(text.find("4 2 0 10 30 40"), 14, "4 2 0 10 30 41");
  expect_error(text, "bad.msh:17:", "element 4 refers to node tag 41");
}

TEST(MshMalformed, Msh22CountLargerThanElements) {
  std::string text = kMsh22;
  text.replace(text.find("\n5\n"), 3, "\n6\n");
  expect_error(text, "bad.msh:18:", "expected an integer (an element tag), found '$EndElements'");
}

TEST(MshMalformed, Msh22CountSmallerThanElements) {
  std::string text = kMsh22;
  text.replace(text.find("\n5\n"), 3, "\n4\n");
  expect_error(text, "bad.msh:17:", "expected '$EndElements', found '4'");
}

}  // namespace
}  // namespace afmesh
