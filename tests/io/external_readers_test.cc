// Cross-checks with other readers: every format afmesh writes must be read by meshio as the
// same mesh (points, elements, and tags where the format carries them), .msh and .mesh also by
// gmsh itself (with the $NodeData view of a sized grid), .vtu also by VTK's XML reader. Each
// reader gets every tag layout that has broken one before: surface only, all tagged, tagged
// triangles around untagged tets, partially tagged, untagged, points only. Runs
// tests/io/{meshio,gmsh,vtk}_check.py with /usr/bin/python3; a missing python3, meshio, gmsh
// or vtk module is a failure, never a skip.
#include <sys/wait.h>

#include <algorithm>
#include <charconv>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <ostream>
#include <string>
#include <string_view>
#include <tuple>
#include <utility>
#include <vector>

#include "core/io/mesh_io.h"
#include "core/io/sized_grid.h"
#include "gtest/gtest.h"
#include "tests/io/io_test_support.h"

namespace afmesh {
namespace {

using io_test::rounded_to_float;
using io_test::tagged_box;
using io_test::tagged_box_surface;
using io_test::TempDir;

constexpr const char* kPython = "/usr/bin/python3";

std::string json_number(double value) {
  char text[32];
  return std::string(text, std::to_chars(text, text + sizeof text, value).ptr);
}

template <typename Rows>
std::string json_rows(const Rows& rows,
                      std::string (*item)(typename Rows::value_type::value_type)) {
  std::string json = "[";
  for (std::size_t r = 0; r < rows.size(); ++r) {
    json += r == 0 ? "[" : ", [";
    for (std::size_t k = 0; k < rows[r].size(); ++k) json += (k ? ", " : "") + item(rows[r][k]);
    json += "]";
  }
  return json + "]";
}

std::string json_index(Index i) { return std::to_string(i); }

std::string json_list(const std::vector<Index>& values) {
  std::string json = "[";
  for (std::size_t i = 0; i < values.size(); ++i)
    json += (i ? ", " : "") + std::to_string(values[i]);
  return json + "]";
}

// The expectation file read by meshio_check.py (and gmsh_check.py, with "sizes" when given).
std::string expected_json(const Mesh& mesh, const std::string& tag_key,
                          const std::string& match_points_by,
                          const std::vector<double>* sizes = nullptr) {
  std::string sizes_json;
  if (sizes != nullptr) {
    sizes_json = ",\n \"sizes\": [";
    for (std::size_t i = 0; i < sizes->size(); ++i) {
      sizes_json += (i ? ", " : "") + json_number((*sizes)[i]);
    }
    sizes_json += "]";
  }
  return "{\"points\": " + json_rows(mesh.points, &json_number) + sizes_json +
         ",\n \"triangles\": " + json_rows(mesh.triangles, &json_index) +
         ",\n \"triangle_tags\": " + json_list(mesh.triangle_tags) +
         ",\n \"tets\": " + json_rows(mesh.tets, &json_index) +
         ",\n \"tet_tags\": " + json_list(mesh.tet_tags) +
         ",\n \"tag_key\": " + (tag_key.empty() ? "null" : "\"" + tag_key + "\"") +
         ",\n \"match_points_by\": \"" + match_points_by + "\"}\n";
}

struct CommandResult {
  int exit_code = -1;
  std::string output;
};

CommandResult run(const std::string& command) {
  CommandResult result;
  std::FILE* pipe = popen((command + " 2>&1").c_str(), "r");
  if (pipe == nullptr) return result;
  char buffer[4096];
  while (const std::size_t got = std::fread(buffer, 1, sizeof buffer, pipe)) {
    result.output.append(buffer, got);
  }
  const int status = pclose(pipe);
  if (WIFEXITED(status)) result.exit_code = WEXITSTATUS(status);
  return result;
}

// Writes `written` to `name` in a temp dir and checks with `script` (meshio_check.py or
// gmsh_check.py) that the other reader finds `expected` in it. With `sizes`, writes a sized
// grid (write_sized_grid) and gmsh_check.py also checks the sizes.
void expect_reader_finds(const std::string& script, const std::string& name, const Mesh& written,
                         const Mesh& expected, const std::string& tag_key,
                         const std::string& match_points_by, const WriteOptions& options = {},
                         const std::vector<double>* sizes = nullptr) {
  ASSERT_TRUE(std::filesystem::exists(kPython))
      << kPython << " is missing: install python3, python3-meshio, python3-gmsh, python3-vtk9";
  TempDir dir;
  const std::string mesh_path = dir.file(name);
  const absl::Status status = sizes == nullptr ? write_mesh(written, mesh_path, options)
                                               : write_sized_grid(written, *sizes, mesh_path);
  ASSERT_TRUE(status.ok()) << status;
  const std::string json_path = dir.file(name + ".json");
  std::ofstream(json_path) << expected_json(expected, tag_key, match_points_by, sizes);
  const std::string script_path = std::string(AFMESH_SOURCE_DIR) + "/tests/io/" + script;
  const CommandResult result =
      run(std::string(kPython) + " '" + script_path + "' '" + mesh_path + "' '" + json_path + "'");
  EXPECT_EQ(result.exit_code, 0)
      << script << " finds a different mesh in what afmesh wrote to " << name
      << " (exit code 3: the python module is missing, install python3-meshio / python3-gmsh /"
      << " python3-vtk9, as scripts/install-deps.sh does):\n"
      << result.output;
}

void expect_meshio_reads(const std::string& name, const Mesh& written, const Mesh& expected,
                         const std::string& tag_key, const std::string& match_points_by,
                         const WriteOptions& options = {}) {
  expect_reader_finds("meshio_check.py", name, written, expected, tag_key, match_points_by,
                      options);
}

// The tag layouts every reader of a format with tags is given.
struct TagCase {
  const char* name;
  Mesh (*mesh)();
};

Mesh volume_with_tags(std::vector<Index> triangle_tags, std::vector<Index> tet_tags) {
  Mesh mesh = tagged_box();
  mesh.triangle_tags = std::move(triangle_tags);
  mesh.tet_tags = std::move(tet_tags);
  return mesh;
}

const TagCase kTagCases[] = {
    {"SurfaceOnly", &tagged_box_surface},
    {"AllTagged", &tagged_box},
    // What `afmesh volume --envs tags` writes: the input's patches around untagged tets.
    {"TaggedTrianglesUntaggedTets",
     [] { return volume_with_tags({1, 2, 3, 4, 5, 6, 1, 2, 3, 4, 5, 6}, {0, 0, 0, 0, 0, 0}); }},
    {"PartiallyTaggedSurface",
     [] {
       Mesh mesh = tagged_box_surface();
       mesh.triangle_tags = {0, 2, 0, 2, 0, 2, 0, 2, 0, 2, 0, 2};
       return mesh;
     }},
    {"PartiallyTaggedVolume",
     [] { return volume_with_tags({0, 2, 0, 2, 0, 2, 0, 2, 0, 2, 0, 3}, {0, 8, 0, 8, 9, 0}); }},
    {"Untagged", [] { return volume_with_tags(std::vector<Index>(12, 0), std::vector<Index>(6, 0)); }},
    {"PointsOnlyEmptyTagArrays",
     [] {
       Mesh mesh;
       mesh.points = tagged_box().points;
       return mesh;
     }},
};

// One reader of one format afmesh writes: the check script, the file extension and meshio's
// name for the tags (meshio_check.py only).
struct ExternalReader {
  const char* name;
  const char* script;
  const char* extension;
  const char* meshio_tag_key;
};

const ExternalReader kReaders[] = {
    {"MeshioMsh", "meshio_check.py", ".msh", "gmsh:physical"},
    {"MeshioMedit", "meshio_check.py", ".mesh", "medit:ref"},
    {"MeshioVtu", "meshio_check.py", ".vtu", "tag"},
    {"GmshMsh", "gmsh_check.py", ".msh", ""},
    {"GmshMedit", "gmsh_check.py", ".mesh", ""},
    {"VtkVtu", "vtk_check.py", ".vtu", ""},
};

void PrintTo(const TagCase& tag_case, std::ostream* os) { *os << tag_case.name; }
void PrintTo(const ExternalReader& reader, std::ostream* os) { *os << reader.name; }

using ReaderAndCase = std::tuple<ExternalReader, TagCase>;

// Every reader with every tag case, less two that the readers cannot hold at all, whatever the
// writer does: meshio 5 cannot read a .vtu without cells (it indexes the first cell type of an
// empty array; without a <Cells> element it finds the pieces inconsistent), and gmsh's Medit
// reader keeps only the vertices that elements use.
std::vector<ReaderAndCase> readers_and_cases() {
  std::vector<ReaderAndCase> all;
  for (const ExternalReader& reader : kReaders) {
    for (const TagCase& tag_case : kTagCases) {
      const std::string_view name = reader.name;
      if (tag_case.mesh().triangles.empty() && tag_case.mesh().tets.empty() &&
          (name == "MeshioVtu" || name == "GmshMedit")) {
        continue;
      }
      all.emplace_back(reader, tag_case);
    }
  }
  return all;
}

class ExternalReaderTest : public ::testing::TestWithParam<ReaderAndCase> {};

TEST_P(ExternalReaderTest, ReadsTheSameMeshAndTags) {
  const auto& [reader, tag_case] = GetParam();
  const Mesh mesh = tag_case.mesh();
  expect_reader_finds(reader.script, std::string("mesh") + reader.extension, mesh, mesh,
                      reader.meshio_tag_key, "index");
}

INSTANTIATE_TEST_SUITE_P(
    EveryWriter, ExternalReaderTest,
    ::testing::ValuesIn(readers_and_cases()),
    [](const ::testing::TestParamInfo<ExternalReaderTest::ParamType>& info) {
      return std::string(std::get<0>(info.param).name) + "_" + std::get<1>(info.param).name;
    });

// The dome of examples/dome tags 1048 of its 1264 triangles; meshio 5 refused the .msh that
// `afmesh volume --envs tags` and `afmesh convert` wrote from it ("Incompatible cell data
// 'gmsh:physical'") because the untagged entity had no physical tag.
TEST(Regression, Issue10MeshioAndGmshReadPartiallyTaggedDomeMsh) {
  const absl::StatusOr<Mesh> dome =
      read_mesh(std::string(AFMESH_SOURCE_DIR) + "/examples/dome/dome.mesh");
  ASSERT_TRUE(dome.ok()) << dome.status();
  ASSERT_TRUE(std::count(dome->triangle_tags.begin(), dome->triangle_tags.end(), 0) > 0);
  expect_reader_finds("meshio_check.py", "dome.msh", *dome, *dome, "gmsh:physical", "index");
  expect_reader_finds("gmsh_check.py", "dome.msh", *dome, *dome, "", "index");
}

TEST(MeshioCrossCheck, ObjTriangles) {
  expect_meshio_reads("box.obj", tagged_box_surface(), tagged_box_surface(), "", "index");
}

TEST(MeshioCrossCheck, AsciiStlWithExactCoordinates) {
  WriteOptions ascii;
  ascii.binary_stl = false;
  expect_meshio_reads("box.stl", tagged_box_surface(), tagged_box_surface(), "", "coordinates",
                      ascii);
}

TEST(MeshioCrossCheck, BinaryStlWithFloatCoordinates) {
  expect_meshio_reads("box.stl", tagged_box_surface(), rounded_to_float(tagged_box_surface()), "",
                      "coordinates");
}

TEST(GmshCrossCheck, GmshReadsSizedGridNodeDataAsAView) {
  const std::vector<double> sizes = {0.1, 1.0 / 3.0, 2.5e-3, 7.0, 1e-300, 1e300, 0.3, 5e-324};
  expect_reader_finds("gmsh_check.py", "grid.msh", tagged_box(), tagged_box(), "gmsh:physical",
                      "index", {}, &sizes);
}

}  // namespace
}  // namespace afmesh
