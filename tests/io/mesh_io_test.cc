#include "core/io/mesh_io.h"

#include <filesystem>
#include <string>

#include "gmock/gmock.h"
#include "gtest/gtest.h"
#include "tests/io/io_test_support.h"

namespace afmesh {
namespace {

using io_test::expect_same_mesh;
using io_test::rounded_to_float;
using io_test::tagged_box;
using io_test::tagged_box_surface;
using io_test::TempDir;
using io_test::triangle_corners;
using ::testing::HasSubstr;

std::string message(const absl::Status& status) { return std::string(status.message()); }

TEST(FormatFromPath, ChoosesByExtensionIgnoringCase) {
  EXPECT_EQ(*format_from_path("a/b/part.STL"), MeshFormat::kStl);
  EXPECT_EQ(*format_from_path("part.obj"), MeshFormat::kObj);
  EXPECT_EQ(*format_from_path("dir.v2/part.Msh"), MeshFormat::kMsh);
  EXPECT_EQ(*format_from_path("part.mesh"), MeshFormat::kMedit);
  EXPECT_EQ(*format_from_path("/tmp/out.vtu"), MeshFormat::kVtu);
}

TEST(FormatFromPath, RejectsUnknownOrMissingExtensions) {
  for (const char* path : {"part.ply", "dir.msh/part", "part", "part.meshb"}) {
    const absl::StatusOr<MeshFormat> format = format_from_path(path);
    ASSERT_FALSE(format.ok()) << path;
    EXPECT_EQ(format.status().code(), absl::StatusCode::kInvalidArgument);
    EXPECT_THAT(message(format.status()), HasSubstr(path));
    EXPECT_THAT(message(format.status()), HasSubstr(".stl, .obj, .msh, .mesh or .vtu"));
  }
}

TEST(MeshFiles, EveryReadableFormatRoundTripsThroughDisk) {
  TempDir dir;
  for (const char* name : {"box.msh", "box.mesh"}) {
    ASSERT_TRUE(write_mesh(tagged_box(), dir.file(name)).ok()) << name;
    absl::StatusOr<Mesh> read = read_mesh(dir.file(name));
    ASSERT_TRUE(read.ok()) << read.status();
    expect_same_mesh(*read, tagged_box());
  }
  ASSERT_TRUE(write_mesh(tagged_box_surface(), dir.file("box.obj")).ok());
  absl::StatusOr<Mesh> obj = read_mesh(dir.file("box.obj"));
  ASSERT_TRUE(obj.ok()) << obj.status();
  expect_same_mesh(*obj, tagged_box_surface());

  ASSERT_TRUE(write_mesh(tagged_box_surface(), dir.file("box.stl")).ok());
  absl::StatusOr<Mesh> stl = read_mesh(dir.file("box.stl"));
  ASSERT_TRUE(stl.ok()) << stl.status();
  EXPECT_EQ(triangle_corners(*stl), triangle_corners(rounded_to_float(tagged_box_surface())));
}

TEST(MeshFiles, AsciiStlOption) {
  TempDir dir;
  WriteOptions ascii;
  ascii.binary_stl = false;
  ASSERT_TRUE(write_mesh(tagged_box_surface(), dir.file("box.stl"), ascii).ok());
  absl::StatusOr<Mesh> read = read_mesh(dir.file("box.stl"));
  ASSERT_TRUE(read.ok()) << read.status();
  EXPECT_EQ(triangle_corners(*read), triangle_corners(tagged_box_surface()));
}

TEST(MeshFiles, ReadingVtuIsUnimplemented) {
  TempDir dir;
  ASSERT_TRUE(write_mesh(tagged_box(), dir.file("box.vtu")).ok());
  const absl::StatusOr<Mesh> read = read_mesh(dir.file("box.vtu"));
  EXPECT_EQ(read.status().code(), absl::StatusCode::kUnimplemented);
  EXPECT_THAT(message(read.status()), HasSubstr("reading .vtu is not supported"));
}

TEST(MeshFiles, MissingFileIsNotFoundNamingThePath) {
  TempDir dir;
  const absl::StatusOr<Mesh> read = read_mesh(dir.file("absent.msh"));
  EXPECT_EQ(read.status().code(), absl::StatusCode::kNotFound);
  EXPECT_THAT(message(read.status()), HasSubstr(dir.file("absent.msh")));
}

TEST(MeshFiles, DirectoryIsAnErrorNamingThePath) {
  TempDir dir;
  std::filesystem::create_directory(dir.file("looks_like.stl"));
  const absl::StatusOr<Mesh> read = read_mesh(dir.file("looks_like.stl"));
  ASSERT_FALSE(read.ok());
  EXPECT_THAT(message(read.status()), HasSubstr(dir.file("looks_like.stl")));
}

TEST(MeshFiles, MalformedFileErrorNamesPathAndLine) {
  TempDir dir;
  io_test::write_file(dir.file("bad.obj"), "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4\n");
  const absl::StatusOr<Mesh> read = read_mesh(dir.file("bad.obj"));
  EXPECT_EQ(read.status().code(), absl::StatusCode::kInvalidArgument);
  EXPECT_THAT(message(read.status()), HasSubstr(dir.file("bad.obj") + ":4: vertex index 4"));
}

TEST(MeshFiles, UnwritableDirectoryIsAnErrorNamingThePath) {
  TempDir dir;
  const std::string path = dir.file("no/such/dir/box.msh");
  const absl::Status status = write_mesh(tagged_box(), path);
  EXPECT_EQ(status.code(), absl::StatusCode::kNotFound);
  EXPECT_THAT(message(status), HasSubstr(path));
}

TEST(MeshFiles, InvalidMeshIsRefusedBeforeTheFileIsCreated) {
  TempDir dir;
  Mesh mesh = tagged_box();
  mesh.tets[3][1] = 8;
  const absl::Status status = write_mesh(mesh, dir.file("box.mesh"));
  EXPECT_EQ(status.code(), absl::StatusCode::kInvalidArgument);
  EXPECT_THAT(message(status),
              HasSubstr("tetrahedron 3 refers to point 8, but the mesh has 8 points"));
  EXPECT_FALSE(std::filesystem::exists(dir.file("box.mesh")));
}

TEST(MeshFiles, TagArrayOfTheWrongLengthIsRefused) {
  TempDir dir;
  Mesh mesh = tagged_box();
  mesh.triangle_tags.pop_back();
  const absl::Status status = write_mesh(mesh, dir.file("box.msh"));
  EXPECT_THAT(message(status), HasSubstr("12 triangles but 11 triangle tags"));
}

TEST(MeshFiles, NonFiniteCoordinateIsRefused) {
  TempDir dir;
  Mesh mesh = tagged_box();
  mesh.points[5][1] = std::numeric_limits<double>::infinity();
  const absl::Status status = write_mesh(mesh, dir.file("box.vtu"));
  EXPECT_THAT(message(status), HasSubstr("point 5 has a non-finite coordinate"));
  EXPECT_FALSE(std::filesystem::exists(dir.file("box.vtu")));
}

TEST(MeshFiles, VolumeMeshToStlIsRefusedWithoutCreatingTheFile) {
  TempDir dir;
  const absl::Status status = write_mesh(tagged_box(), dir.file("box.stl"));
  EXPECT_EQ(status.code(), absl::StatusCode::kInvalidArgument);
  EXPECT_THAT(message(status), HasSubstr(dir.file("box.stl")));
  EXPECT_THAT(message(status),
              HasSubstr("STL holds triangles only, but the mesh has 6 tetrahedra"));
  EXPECT_FALSE(std::filesystem::exists(dir.file("box.stl")));
}

TEST(MeshFiles, ReadReportCollectsNotes) {
  TempDir dir;
  io_test::write_file(dir.file("notes.mesh"),
                      "MeshVersionFormatted 2\nDimension 3\nVertices\n1\n0 0 0 4\n"
                      "Corners\n1\n1\nEnd\n");
  ReadReport report;
  ASSERT_TRUE(read_mesh(dir.file("notes.mesh"), &report).ok());
  EXPECT_EQ(report.notes.size(), 2u);
}

}  // namespace
}  // namespace afmesh
