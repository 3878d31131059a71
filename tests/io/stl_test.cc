#include "core/io/stl.h"

#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <string>

#include "gmock/gmock.h"
#include "gtest/gtest.h"
#include "tests/io/io_test_support.h"

namespace afmesh {
namespace {

using io_test::rounded_to_float;
using io_test::tagged_box;
using io_test::tagged_box_surface;
using io_test::triangle_corners;
using io_test::written;
using ::testing::HasSubstr;

std::string stl_bytes(const Mesh& mesh, StlEncoding encoding) {
  return written([&](OutputBuffer& out) { return write_stl(mesh, encoding, out); });
}

// One ascii facet with the given corner lines.
std::string facet(const std::string& a, const std::string& b, const std::string& c) {
  return "facet normal 0 0 1\n outer loop\n  vertex " + a + "\n  vertex " + b + "\n  vertex " + c +
         "\n endloop\nendfacet\n";
}

TEST(Stl, BinaryRoundTripKeepsFloatCoordinatesAndMergesTheEightCorners) {
  const Mesh surface = tagged_box_surface();
  const std::string bytes = stl_bytes(surface, StlEncoding::kBinary);
  ASSERT_EQ(bytes.size(), 84u + 50u * 12u);
  ReadReport report;
  absl::StatusOr<Mesh> read = parse_stl(bytes, "box.stl", &report);
  ASSERT_TRUE(read.ok()) << read.status();
  EXPECT_EQ(read->points.size(), 8u);
  EXPECT_EQ(triangle_corners(*read), triangle_corners(rounded_to_float(surface)));
  EXPECT_EQ(read->triangle_tags, std::vector<Index>(12, 0));
  EXPECT_THAT(report.notes, testing::Contains(HasSubstr("36 STL triangle corners into 8 points")));
}

TEST(Stl, AsciiRoundTripIsBitExactAndTagsBecomeSolidOrdinals) {
  const Mesh surface = tagged_box_surface();
  absl::StatusOr<Mesh> read = parse_stl(stl_bytes(surface, StlEncoding::kAscii), "box.stl");
  ASSERT_TRUE(read.ok()) << read.status();
  EXPECT_EQ(read->points.size(), 8u);
  const auto expected = triangle_corners(surface);
  const auto actual = triangle_corners(*read);
  ASSERT_EQ(actual.size(), expected.size());
  for (std::size_t t = 0; t < expected.size(); ++t) {
    for (int k = 0; k < 3; ++k) {
      for (int axis = 0; axis < 3; ++axis) {
        EXPECT_TRUE(io_test::same_bits(actual[t][k][axis], expected[t][k][axis]));
      }
    }
  }
  // Every triangle is its own run of equal tags (1 2 3 4 5 6 1 2 ...): solids 1..12.
  for (Index t = 0; t < 12; ++t) EXPECT_EQ(read->triangle_tags[t], t + 1);
}

TEST(Stl, AsciiSolidsNumberTheirTrianglesFromOne) {
  const std::string text = "solid first\n" + facet("0 0 0", "1 0 0", "0 1 0") +
                           facet("1 0 0", "1 1 0", "0 1 0") + "endsolid first\nSOLID second\n" +
                           facet("0 0 1", "1 0 1", "0 1 1") + "ENDSOLID second\n";
  absl::StatusOr<Mesh> read = parse_stl(text, "two.stl");
  ASSERT_TRUE(read.ok()) << read.status();
  EXPECT_EQ(read->triangle_tags, (std::vector<Index>{1, 1, 2}));
  EXPECT_EQ(read->points.size(), 7u);
}

TEST(Stl, MergesNegativeZeroWithZeroButNotNeighbouringDoubles) {
  char exact[32];
  std::snprintf(exact, sizeof exact, "%.17g", std::nextafter(1.0, 2.0));
  const std::string text = "solid s\n" + facet("0 0 0", "1 0 0", "0 1 0") +
                           facet("-0 -0.0 0", "0 1 0", std::string(exact) + " 0 0") +
                           "endsolid s\n";
  absl::StatusOr<Mesh> read = parse_stl(text, "zeros.stl");
  ASSERT_TRUE(read.ok()) << read.status();
  ASSERT_EQ(read->points.size(), 4u);
  EXPECT_EQ(read->triangles[1][0], read->triangles[0][0]);
  EXPECT_FALSE(std::signbit(read->points[read->triangles[1][0]][0]));
  EXPECT_NE(read->triangles[1][2], read->triangles[0][1]);
}

TEST(Stl, BinaryFileWhoseHeaderStartsWithSolidIsReadAsBinary) {
  const Mesh surface = tagged_box_surface();
  std::string bytes = stl_bytes(surface, StlEncoding::kBinary);
  const std::string header = "solid exported by a tool that writes this in binary files";
  std::memcpy(bytes.data(), header.data(), header.size());
  absl::StatusOr<Mesh> read = parse_stl(bytes, "solid.stl");
  ASSERT_TRUE(read.ok()) << read.status();
  EXPECT_EQ(triangle_corners(*read), triangle_corners(rounded_to_float(surface)));
}

TEST(Stl, AcceptsNonFiniteFacetNormals) {
  const std::string text =
      "solid s\nfacet normal nan nan nan\nouter loop\nvertex 0 0 0\nvertex 1 0 0\n"
      "vertex 0 1 0\nendloop\nendfacet\nendsolid s\n";
  EXPECT_TRUE(parse_stl(text, "normals.stl").ok());
}

TEST(Stl, EmptyAsciiSolidIsAnEmptyMesh) {
  absl::StatusOr<Mesh> read = parse_stl("solid nothing\nendsolid nothing\n", "empty_solid.stl");
  ASSERT_TRUE(read.ok()) << read.status();
  EXPECT_TRUE(read->triangles.empty());
}

TEST(Stl, WriteRefusesTetrahedra) {
  std::string bytes;
  OutputBuffer out(&bytes);
  const absl::Status status = write_stl(tagged_box(), StlEncoding::kBinary, out);
  EXPECT_EQ(status.code(), absl::StatusCode::kInvalidArgument);
  EXPECT_THAT(std::string(status.message()),
              HasSubstr("STL holds triangles only, but the mesh has 6 tetrahedra"));
  EXPECT_TRUE(bytes.empty());
}

// Malformed input: every error names the source and the line or byte offset.

void expect_error(const std::string& bytes, const std::string& where, const std::string& what) {
  const absl::StatusOr<Mesh> read = parse_stl(bytes, "bad.stl");
  ASSERT_FALSE(read.ok());
  EXPECT_EQ(read.status().code(), absl::StatusCode::kInvalidArgument);
  const std::string message(read.status().message());
  EXPECT_THAT(message, HasSubstr(where));
  EXPECT_THAT(message, HasSubstr(what));
}

TEST(StlMalformed, EmptyFile) { expect_error("", "bad.stl", "empty"); }

TEST(StlMalformed, TruncatedBinary) {
  std::string bytes = stl_bytes(tagged_box_surface(), StlEncoding::kBinary);
  bytes.resize(bytes.size() - 7);
  expect_error(bytes, "bad.stl: byte 80",
               "declares 12 triangles, which take 684 bytes, but the file has 677");
}

TEST(StlMalformed, BinaryCountLargerThanData) {
  std::string bytes = stl_bytes(tagged_box_surface(), StlEncoding::kBinary);
  const std::uint32_t count = 13;
  std::memcpy(bytes.data() + 80, &count, 4);
  expect_error(bytes, "bad.stl: byte 80", "declares 13 triangles");
}

TEST(StlMalformed, BinaryNanCoordinate) {
  std::string bytes = stl_bytes(tagged_box_surface(), StlEncoding::kBinary);
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const std::size_t offset = 84 + 50 * 2 + 12 + 12 * 1 + 4 * 2;  // triangle 3, corner 2, z
  std::memcpy(bytes.data() + offset, &nan, 4);
  expect_error(bytes, "bad.stl: byte " + std::to_string(offset),
               "finite coordinate for corner 2 of triangle 3");
}

TEST(StlMalformed, TooShortForEitherEncoding) {
  expect_error(std::string("\x01\x02garbage", 9), "bad.stl: byte 0", "not an STL file");
}

TEST(StlMalformed, AsciiMissingEndsolid) {
  expect_error("solid s\n" + facet("0 0 0", "1 0 0", "0 1 0"),
               "bad.stl:9:", "expected 'facet' or 'endsolid', found end of file");
}

TEST(StlMalformed, AsciiTruncatedInsideAFacet) {
  expect_error("solid s\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0",
               "bad.stl:5:", "expected a finite number (a vertex coordinate), found end of file");
}

TEST(StlMalformed, AsciiGarbageCoordinate) {
  expect_error("solid s\n" + facet("0 0 0", "1 0x 0", "0 1 0") + "endsolid\n",
               "bad.stl:5:", "found '0x'");
}

TEST(StlMalformed, AsciiInfiniteCoordinate) {
  expect_error("solid s\n" + facet("0 0 0", "1 0 0", "0 inf 0") + "endsolid\n",
               "bad.stl:6:", "expected a finite number (a vertex coordinate), found 'inf'");
}

TEST(StlMalformed, AsciiFourCornerFacet) {
  expect_error(
      "solid s\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 1 1 0\n"
      "vertex 0 1 0\nendloop\nendfacet\nendsolid\n",
      "bad.stl:7:", "expected 'endloop', found 'vertex'");
}

TEST(StlMalformed, AsciiUnknownKeyword) {
  expect_error("solid s\nfacets normal 0 0 1\n", "bad.stl:2:", "found 'facets'");
}

}  // namespace
}  // namespace afmesh
