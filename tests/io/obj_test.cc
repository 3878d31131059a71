#include "core/io/obj.h"

#include <string>

#include "gmock/gmock.h"
#include "gtest/gtest.h"
#include "tests/io/io_test_support.h"

namespace afmesh {
namespace {

using io_test::expect_same_mesh;
using io_test::tagged_box;
using io_test::tagged_box_surface;
using io_test::written;
using ::testing::Contains;
using ::testing::HasSubstr;

TEST(Obj, RoundTripIsBitExactWithTags) {
  Mesh surface = tagged_box_surface();
  surface.points[3][1] = -0.0;
  surface.points[5][2] = 5e-324;  // smallest subnormal
  const std::string text = written([&](OutputBuffer& out) { return write_obj(surface, out); });
  absl::StatusOr<Mesh> read = parse_obj(text, "box.obj");
  ASSERT_TRUE(read.ok()) << read.status();
  expect_same_mesh(*read, surface);
}

TEST(Obj, ReadsCornerFormsAndNegativeIndices) {
  const std::string text =
      "# a square\nmtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 1 1 0 1.0\nv 0 1 0 0.5 0.5 0.5\n"
      "vt 0 0\nvn 0 0 1\ns off\nusemtl red\n"
      "f 1/1 2/1/1 3//1\n"
      "f -4 -2 -1  # relative\n";
  ReadReport report;
  absl::StatusOr<Mesh> read = parse_obj(text, "square.obj", &report);
  ASSERT_TRUE(read.ok()) << read.status();
  EXPECT_EQ(read->points.size(), 4u);
  EXPECT_EQ(read->triangles, (std::vector<Triangle>{{0, 1, 2}, {0, 2, 3}}));
  EXPECT_EQ(read->triangle_tags, (std::vector<Index>{0, 0}));
  EXPECT_THAT(report.notes, Contains(HasSubstr("1 'vn', 1 'vt', 1 's', 1 'mtllib', 1 'usemtl'")));
}

TEST(Obj, TagGroupsGiveTheirNumbers) {
  const std::string text =
      "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\ng tag_42\nf 1 2 3\no tag_7\nf 3 2 1\ng\nf 1 3 2\n";
  absl::StatusOr<Mesh> read = parse_obj(text, "groups.obj");
  ASSERT_TRUE(read.ok()) << read.status();
  EXPECT_EQ(read->triangle_tags, (std::vector<Index>{0, 42, 7, 0}));
}

TEST(Obj, OtherGroupNamesAreNumberedByFirstAppearance) {
  const std::string text =
      "v 0 0 0\nv 1 0 0\nv 0 1 0\ng lid\nf 1 2 3\ng side wall\nf 1 2 3\ng lid\nf 3 2 1\n";
  ReadReport report;
  absl::StatusOr<Mesh> read = parse_obj(text, "named.obj", &report);
  ASSERT_TRUE(read.ok()) << read.status();
  EXPECT_EQ(read->triangle_tags, (std::vector<Index>{1, 2, 1}));
  EXPECT_THAT(report.notes, Contains(HasSubstr("'lid' -> 1, 'side wall' -> 2")));
}

TEST(Obj, WriteRefusesTetrahedra) {
  std::string bytes;
  OutputBuffer out(&bytes);
  const absl::Status status = write_obj(tagged_box(), out);
  EXPECT_EQ(status.code(), absl::StatusCode::kInvalidArgument);
  EXPECT_THAT(std::string(status.message()), HasSubstr("OBJ holds triangles only"));
}

void expect_error(const std::string& text, const std::string& where, const std::string& what) {
  const absl::StatusOr<Mesh> read = parse_obj(text, "bad.obj");
  ASSERT_FALSE(read.ok());
  EXPECT_EQ(read.status().code(), absl::StatusCode::kInvalidArgument);
  const std::string message(read.status().message());
  EXPECT_THAT(message, HasSubstr(where));
  EXPECT_THAT(message, HasSubstr(what));
}

constexpr const char* kTriangle = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";

TEST(ObjMalformed, EmptyFile) { expect_error("", "bad.obj", "empty"); }

TEST(ObjMalformed, OnlyComments) { expect_error("# nothing\n\n", "bad.obj", "empty"); }

TEST(ObjMalformed, IndexZero) {
  expect_error(std::string(kTriangle) + "f 0 1 2\n",
               "bad.obj:4:", "vertex index 0 is out of range");
}

TEST(ObjMalformed, IndexPastTheLastVertex) {
  expect_error(std::string(kTriangle) + "f 1 2 4\n",
               "bad.obj:4:", "vertex index 4 is out of range: 3 vertices are defined");
}

TEST(ObjMalformed, NegativeIndexBeforeTheFirstVertex) {
  expect_error(std::string(kTriangle) + "f -1 -2 -4\n",
               "bad.obj:4:", "vertex index -4 is out of range");
}

TEST(ObjMalformed, PolygonFace) {
  expect_error(std::string(kTriangle) + "v 1 1 0\nf 1 2 4 3\n",
               "bad.obj:5:", "face with 4 corners: only triangles are supported");
}

TEST(ObjMalformed, FaceWithTwoCorners) {
  expect_error(std::string(kTriangle) + "f 1 2\n", "bad.obj:4:", "a face needs 3 corners, found 2");
}

TEST(ObjMalformed, GarbageCorner) {
  expect_error(std::string(kTriangle) + "f 1 2 x3\n", "bad.obj:4:", "found 'x3'");
}

TEST(ObjMalformed, BadTextureIndex) {
  expect_error(std::string(kTriangle) + "f 1/a 2 3\n", "bad.obj:4:", "found '1/a'");
}

TEST(ObjMalformed, NanCoordinate) {
  expect_error("v 0 0 0\nv nan 0 0\n",
               "bad.obj:2:", "expected a finite number (a vertex coordinate), found 'nan'");
}

TEST(ObjMalformed, VertexWithTwoCoordinates) {
  expect_error("v 0 0\nv 1 0 0\n", "bad.obj:1:", "a 'v' line needs 3 coordinates");
}

TEST(ObjMalformed, VertexWithTooManyNumbers) {
  expect_error("v 0 0 0 1 1 1 1 1\n", "bad.obj:1:", "expected the end of the 'v' line, found '1'");
}

TEST(ObjMalformed, UnknownStatement) {
  expect_error(std::string(kTriangle) + "curv2 1 2\n",
               "bad.obj:4:", "unknown OBJ statement 'curv2'");
}

}  // namespace
}  // namespace afmesh
