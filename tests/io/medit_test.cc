#include "core/io/medit.h"

#include <string>

#include "gmock/gmock.h"
#include "gtest/gtest.h"
#include "tests/io/io_test_support.h"

namespace afmesh {
namespace {

using io_test::expect_same_mesh;
using io_test::tagged_box;
using io_test::written;
using ::testing::Contains;
using ::testing::HasSubstr;

TEST(Medit, RoundTripIsBitExactWithTags) {
  Mesh mesh = tagged_box();
  mesh.points[2][0] = -0.0;
  mesh.points[6][1] = 1.7976931348623157e308;
  const std::string text = written([&](OutputBuffer& out) { return write_medit(mesh, out); });
  ReadReport report;
  absl::StatusOr<Mesh> read = parse_medit(text, "box.mesh", &report);
  ASSERT_TRUE(read.ok()) << read.status();
  expect_same_mesh(*read, mesh);
  EXPECT_TRUE(report.notes.empty());
}

TEST(Medit, EmptyMeshRoundTrips) {
  const std::string text = written([&](OutputBuffer& out) { return write_medit(Mesh{}, out); });
  absl::StatusOr<Mesh> read = parse_medit(text, "empty.mesh");
  ASSERT_TRUE(read.ok()) << read.status();
  expect_same_mesh(*read, Mesh{});
}

TEST(Medit, ReadsKeywordsInAnyCaseCommentsAndSkippedSections) {
  const std::string text =
      "# written by hand\nmeshversionformatted 1\n\nDimension\n3\n"
      "VERTICES\n4\n0 0 0 1\n1 0 0 0\n0 1 0 0\n0 0 1 2  # vertex refs are dropped\n"
      "Corners\n2\n1\n2\nRidges\n1\n1\nRequiredVertices\n1\n4\n"
      "Edges\n2\n1 2 5\n2 3 5\nNormals\n1\n0 0 1\nNormalAtVertices\n1\n1 1\n"
      "Triangles\n2\n1 2 3 11\n1 3 4 12\ntetrahedra\n1\n1 2 3 4 -3\nEnd\n";
  ReadReport report;
  absl::StatusOr<Mesh> read = parse_medit(text, "mixed.mesh", &report);
  ASSERT_TRUE(read.ok()) << read.status();
  EXPECT_EQ(read->points.size(), 4u);
  EXPECT_EQ(read->triangles, (std::vector<Triangle>{{0, 1, 2}, {0, 2, 3}}));
  EXPECT_EQ(read->triangle_tags, (std::vector<Index>{11, 12}));
  EXPECT_EQ(read->tets, (std::vector<Tet>{{0, 1, 2, 3}}));
  EXPECT_EQ(read->tet_tags, (std::vector<Index>{-3}));
  EXPECT_THAT(report.notes, Contains(HasSubstr("2 of 4 vertices had a nonzero ref")));
  EXPECT_THAT(report.notes, Contains(HasSubstr("Corners (2 entries)")));
  EXPECT_THAT(report.notes, Contains(HasSubstr("Edges (2 entries)")));
  EXPECT_THAT(report.notes, Contains(HasSubstr("NormalAtVertices (1 entry)")));
}

void expect_error(const std::string& text, const std::string& where, const std::string& what) {
  const absl::StatusOr<Mesh> read = parse_medit(text, "bad.mesh");
  ASSERT_FALSE(read.ok());
  EXPECT_EQ(read.status().code(), absl::StatusCode::kInvalidArgument);
  const std::string message(read.status().message());
  EXPECT_THAT(message, HasSubstr(where));
  EXPECT_THAT(message, HasSubstr(what));
}

constexpr const char* kHeader = "MeshVersionFormatted 2\nDimension 3\n";
constexpr const char* kVertices = "Vertices\n3\n0 0 0 0\n1 0 0 0\n0 1 0 0\n";

std::string with_body(const std::string& body) { return std::string(kHeader) + kVertices + body; }

TEST(MeditMalformed, EmptyFile) { expect_error("", "bad.mesh", "empty"); }

TEST(MeditMalformed, MissingVersion) {
  expect_error("Dimension 3\n",
               "bad.mesh:1:", "expected 'MeshVersionFormatted', found 'Dimension'");
}

TEST(MeditMalformed, TwoDimensional) {
  expect_error("MeshVersionFormatted 2\nDimension 2\n",
               "bad.mesh:2:", "Dimension 2 is not supported");
}

TEST(MeditMalformed, CountLargerThanEntries) {
  expect_error(with_body("Triangles\n2\n1 2 3 0\nEnd\n"),
               "bad.mesh:11:", "expected an integer (a vertex index), found 'End'");
}

TEST(MeditMalformed, CountSmallerThanEntries) {
  expect_error(with_body("Triangles\n1\n1 2 3 0\n3 2 1 0\nEnd\n"),
               "bad.mesh:11:", "found the number '3' (does the previous section hold more entries");
}

TEST(MeditMalformed, IndexZero) {
  expect_error(with_body("Triangles\n1\n0 1 2 0\nEnd\n"),
               "bad.mesh:10:", "vertex index 0 is out of range [1, 3]");
}

TEST(MeditMalformed, IndexPastTheLastVertex) {
  expect_error(with_body("Tetrahedra\n1\n1 2 3 4 0\nEnd\n"),
               "bad.mesh:10:", "vertex index 4 is out of range [1, 3]");
}

TEST(MeditMalformed, NegativeIndex) {
  expect_error(with_body("Triangles\n1\n1 -2 3 0\nEnd\n"),
               "bad.mesh:10:", "vertex index -2 is out of range");
}

TEST(MeditMalformed, NanCoordinate) {
  expect_error(std::string(kHeader) + "Vertices\n2\n0 0 0 0\n0 NaN 0 0\nEnd\n",
               "bad.mesh:6:", "expected a finite number (a vertex coordinate), found 'NaN'");
}

TEST(MeditMalformed, GarbageToken) {
  expect_error(with_body("Triangles\n1\n1 2 3x 0\nEnd\n"), "bad.mesh:10:", "found '3x'");
}

TEST(MeditMalformed, UnknownKeyword) {
  expect_error(with_body("Trianglez\n0\nEnd\n"),
               "bad.mesh:8:", "unknown Medit keyword 'Trianglez'");
}

TEST(MeditMalformed, UnsupportedElements) {
  expect_error(with_body("Hexahedra\n0\nEnd\n"),
               "bad.mesh:8:", "Medit section 'Hexahedra' is not supported");
}

TEST(MeditMalformed, MissingEnd) {
  expect_error(with_body("Triangles\n1\n1 2 3 0\n"),
               "bad.mesh:11:", "expected a section keyword or 'End', found end of file");
}

TEST(MeditMalformed, ElementsBeforeVertices) {
  expect_error(std::string(kHeader) + "Triangles\n0\nEnd\n",
               "bad.mesh:3:", "section 'Triangles' before 'Vertices'");
}

TEST(MeditMalformed, NegativeCount) {
  expect_error(std::string(kHeader) + "Vertices\n-1\nEnd\n",
               "bad.mesh:4:", "Vertices count -1 is out of range");
}

}  // namespace
}  // namespace afmesh
