// Cross-checks with other readers: every format afmesh writes must be read by meshio as the
// same mesh (points, elements, and tags where the format carries them), and MSH files by gmsh
// itself (with the $NodeData view of a sized grid). Runs tests/io/meshio_check.py and
// tests/io/gmsh_check.py with /usr/bin/python3; a missing python3, meshio or gmsh module is a
// failure, never a skip.
#include <sys/wait.h>

#include <charconv>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

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
      << kPython << " is missing: install python3, python3-meshio and python3-gmsh";
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
      << " (exit code 3: the python module is missing, install python3-meshio / python3-gmsh):\n"
      << result.output;
}

void expect_meshio_reads(const std::string& name, const Mesh& written, const Mesh& expected,
                         const std::string& tag_key, const std::string& match_points_by,
                         const WriteOptions& options = {}) {
  expect_reader_finds("meshio_check.py", name, written, expected, tag_key, match_points_by,
                      options);
}

TEST(MeshioCrossCheck, GmshMsh41WithPhysicalTags) {
  expect_meshio_reads("box.msh", tagged_box(), tagged_box(), "gmsh:physical", "index");
}

TEST(MeshioCrossCheck, MeditWithReferences) {
  expect_meshio_reads("box.mesh", tagged_box(), tagged_box(), "medit:ref", "index");
}

TEST(MeshioCrossCheck, VtuWithTagCellData) {
  expect_meshio_reads("box.vtu", tagged_box(), tagged_box(), "tag", "index");
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

TEST(GmshCrossCheck, GmshReadsMsh41WithPhysicalGroups) {
  expect_reader_finds("gmsh_check.py", "box.msh", tagged_box(), tagged_box(), "gmsh:physical",
                      "index");
}

TEST(GmshCrossCheck, GmshReadsTagZeroAsNoPhysicalGroup) {
  Mesh mesh = tagged_box();
  mesh.triangle_tags = {0, 2, 0, 2, 0, 2, 0, 2, 0, 2, 0, 2};
  mesh.tet_tags = {0, 0, 0, 0, 0, 0};
  expect_reader_finds("gmsh_check.py", "untagged.msh", mesh, mesh, "gmsh:physical", "index");
}

TEST(GmshCrossCheck, GmshReadsSizedGridNodeDataAsAView) {
  const std::vector<double> sizes = {0.1, 1.0 / 3.0, 2.5e-3, 7.0, 1e-300, 1e300, 0.3, 5e-324};
  expect_reader_finds("gmsh_check.py", "grid.msh", tagged_box(), tagged_box(), "gmsh:physical",
                      "index", {}, &sizes);
}

}  // namespace
}  // namespace afmesh
