// `afmesh sizes` and `afmesh volume --spec` through the real binaries: the paper's dome
// specification (examples/dome/dome-sizes.json) reproduces its law, errors name the file, line
// or field, a box with a point source meshes into a valid volume mesh, and background grid files
// (.msh, .mesh + .sol) are read by the client, interpolated exactly and sent to the server.
#include <stdlib.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>
#include <string>
#include <vector>

#include "core/io/mesh_io.h"
#include "core/io/sized_grid.h"
#include "core/quality/validate.h"
#include "core/shapes/shapes.h"
#include "core/sizing/background_grid.h"
#include "gmock/gmock.h"
#include "gtest/gtest.h"
#include "tests/server/cli_test_support.h"

namespace afmesh {
namespace {

namespace fs = std::filesystem;
using cli_test::read_file;
using cli_test::shell_quoted;
using ::testing::HasSubstr;

fs::path dome_spec_path() { return fs::path(AFMESH_SOURCE_DIR) / "examples/dome/dome-sizes.json"; }

// The dome's law (eq. 10, 13, 14) by hand: delta0 (1 + a1 rho + a2 rho^2), rho = max(0, (r - r0)
// / r1), capped at maxSize (the default background grid is maxSize everywhere).
double dome_size(const Point& x) {
  constexpr double kMaxSize = 0.8, kDelta0 = 0.15, kR0 = 1.0, kR1 = 0.2, kA1 = 1.0, kA2 = 0.0;
  const double r = std::sqrt(x[0] * x[0] + x[1] * x[1] + x[2] * x[2]);
  const double rho = std::max(0.0, (r - kR0) / kR1);
  return std::min(kMaxSize, kDelta0 * (1.0 + kA1 * rho + kA2 * rho * rho));
}

// The number of tets of `mesh` whose centroid is within `radius` of `centre`.
int tets_near(const Mesh& mesh, const Point& centre, double radius) {
  int count = 0;
  for (const Tet& tet : mesh.tets) {
    double d2 = 0.0;
    for (int k = 0; k < 3; ++k) {
      const double c = (mesh.points[tet[0]][k] + mesh.points[tet[1]][k] + mesh.points[tet[2]][k] +
                        mesh.points[tet[3]][k]) / 4.0;
      d2 += (c - centre[k]) * (c - centre[k]);
    }
    count += d2 <= radius * radius ? 1 : 0;
  }
  return count;
}

class CliSizesTest : public ::testing::Test {
 protected:
  void SetUp() override {
    char pattern[] = "/tmp/afmesh-sizes-test-XXXXXX";
    ASSERT_NE(mkdtemp(pattern), nullptr);
    dir_ = pattern;
    fs::create_directory(dir_ / "tmp");
  }

  void TearDown() override { fs::remove_all(dir_); }

  static void write_file(const fs::path& path, const std::string& text) {
    std::ofstream(path) << text;
  }

  // Runs `afmesh ARGS` (stdin from `input` when given) with TMPDIR in the test folder; stdout and
  // stderr go to files. Returns the exit status.
  int run(const std::string& args, const std::string& input = "") {
    std::string command = "TMPDIR=" + shell_quoted(dir_ / "tmp") + " " + AFMESH_CLI_BINARY + " " +
                          args + " >" + shell_quoted(dir_ / "stdout.txt") + " 2>" +
                          shell_quoted(dir_ / "stderr.txt");
    if (!input.empty()) {
      write_file(dir_ / "stdin.txt", input);
      command += " <" + shell_quoted(dir_ / "stdin.txt");
    }
    const int status = std::system(command.c_str());
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  }

  std::string stdout_text() const { return read_file(dir_ / "stdout.txt"); }
  std::string stderr_text() const { return read_file(dir_ / "stderr.txt"); }

  // The numbers printed on stdout, one per line.
  std::vector<double> printed_sizes() const {
    std::istringstream in(stdout_text());
    std::vector<double> sizes;
    for (double size = 0.0; in >> size;) sizes.push_back(size);
    return sizes;
  }

  fs::path dir_;
};

// Probe points inside r0, on it, across the decay (in several directions) and beyond the cap.
const std::vector<Point> kDomeProbes = {
    {0, 0, 0},       {0.3, 0.4, 0},   {0, 0, 1.0},         {0, 1.1, 0},   {0.72, 0.96, 0},
    {0.9, 0.9, 0.3}, {1.5, 0, 0},     {-0.6, -0.8, -0.9},  {0, 2.0, 0},   {3, 3, 3},
};

std::string points_text(const std::vector<Point>& points) {
  std::ostringstream out;
  out.precision(17);
  for (const Point& p : points) out << p[0] << ' ' << p[1] << "\t" << p[2] << '\n';
  return out.str();
}

TEST_F(CliSizesTest, DomeSpecReproducesThePolynomialLawTo1e12) {
  write_file(dir_ / "probe.xyz", points_text(kDomeProbes));
  ASSERT_EQ(run("sizes --spec " + shell_quoted(dome_spec_path()) + " --points " +
                shell_quoted(dir_ / "probe.xyz")),
            0)
      << stderr_text();
  const std::vector<double> sizes = printed_sizes();
  ASSERT_EQ(sizes.size(), kDomeProbes.size()) << stdout_text();
  for (std::size_t i = 0; i < kDomeProbes.size(); ++i) {
    const double expected = dome_size(kDomeProbes[i]);
    EXPECT_NEAR(sizes[i], expected, 1e-12 * expected) << "probe " << i;
  }
  // The probes cover the constant core, the decay and the cap.
  EXPECT_EQ(dome_size(kDomeProbes[0]), 0.15);
  EXPECT_EQ(dome_size(kDomeProbes.back()), 0.8);
}

TEST_F(CliSizesTest, ReadsStdinWhenNoPointsFileAndSkipsBlankLines) {
  ASSERT_EQ(run("sizes --spec " + shell_quoted(dome_spec_path()), "1.2 0 0\n\n0 0 0\n"), 0)
      << stderr_text();
  const std::vector<double> sizes = printed_sizes();
  ASSERT_EQ(sizes.size(), 2u);
  EXPECT_NEAR(sizes[0], dome_size({1.2, 0, 0}), 1e-12);
  EXPECT_EQ(sizes[1], 0.15);
}

TEST_F(CliSizesTest, MalformedPointLineExitsBadInputNamingTheLine) {
  write_file(dir_ / "probe.xyz", "0 0 0\n1 2\n");
  EXPECT_EQ(run("sizes --spec " + shell_quoted(dome_spec_path()) + " --points " +
                shell_quoted(dir_ / "probe.xyz")),
            3);
  EXPECT_THAT(stderr_text(), HasSubstr("probe.xyz:2:"));
}

TEST_F(CliSizesTest, InvalidSpecExitsBadInputNamingFileAndField) {
  write_file(dir_ / "bad.json", R"({"maxSize": 1, "sources": [{"points": [{}], "delta0": 0.1,
      "r1": -1, "power": {"gamma": 1}}]})");
  EXPECT_EQ(run("sizes --spec " + shell_quoted(dir_ / "bad.json"), "0 0 0\n"), 3);
  EXPECT_THAT(stderr_text(), HasSubstr("bad.json"));
  EXPECT_THAT(stderr_text(), HasSubstr("sources[0].r1"));
}

TEST_F(CliSizesTest, MalformedJsonExitsBadInputNamingTheFile) {
  write_file(dir_ / "bad.json", R"({"maxSize": 1, "sources": [{"cubic": {}}]})");
  EXPECT_EQ(run("sizes --spec " + shell_quoted(dir_ / "bad.json"), "0 0 0\n"), 3);
  EXPECT_THAT(stderr_text(), HasSubstr("bad.json"));
  EXPECT_THAT(stderr_text(), HasSubstr("cubic"));
}

// A background grid file: the cube [-1, 2]^3 in five tets (BackgroundGrid::box_grid) with sizes
// scale (1 + 0.2 x + 0.3 y + 0.4 z) at its corners (scale 0.1 to 2.8), written as .msh or .mesh
// + .sol.
double linear_size(const Point& x) { return 1.0 + 0.2 * x[0] + 0.3 * x[1] + 0.4 * x[2]; }

void write_linear_grid(const fs::path& path, double scale = 1.0) {
  const BackgroundGrid cube = BackgroundGrid::box_grid(Box{{-1, -1, -1}, {2, 2, 2}}, 1.0);
  Mesh grid;
  grid.points = cube.points();
  grid.tets = cube.tets();
  grid.tet_tags.assign(grid.tets.size(), 0);
  std::vector<double> sizes;
  for (const Point& p : grid.points) sizes.push_back(scale * linear_size(p));
  ASSERT_TRUE(write_sized_grid(grid, sizes, path.string()).ok());
}

// Points inside the grid, in several of its tets.
const std::vector<Point> kGridProbes = {
    {0, 0, 0}, {0.5, 0.25, 0.125}, {1.9, -0.9, 0.3}, {-0.7, 1.3, 1.6}, {1, 1, 1}};

void expect_linear_sizes(const std::vector<double>& sizes) {
  ASSERT_EQ(sizes.size(), kGridProbes.size());
  for (std::size_t i = 0; i < sizes.size(); ++i) {
    const double expected = std::min(10.0, linear_size(kGridProbes[i]));
    EXPECT_NEAR(sizes[i], expected, 1e-12 * expected) << "probe " << i;
  }
}

TEST_F(CliSizesTest, BackgroundMshFileBesideTheSpecIsInterpolatedExactly) {
  fs::create_directories(dir_ / "specs" / "grids");
  write_linear_grid(dir_ / "specs" / "grids" / "linear.msh");
  write_file(dir_ / "specs" / "spec.json",
             R"({"maxSize": 10, "background": {"file": "grids/linear.msh"}})");
  ASSERT_EQ(
      run("sizes --spec " + shell_quoted(dir_ / "specs" / "spec.json"), points_text(kGridProbes)),
      0)
      << stderr_text();
  expect_linear_sizes(printed_sizes());
}

TEST_F(CliSizesTest, BackgroundMeditFileWithSolIsInterpolatedExactly) {
  write_linear_grid(dir_ / "linear.mesh");
  ASSERT_TRUE(fs::exists(dir_ / "linear.sol"));
  write_file(dir_ / "spec.json", R"({"maxSize": 10, "background": {"file": "linear.mesh"}})");
  ASSERT_EQ(run("sizes --spec " + shell_quoted(dir_ / "spec.json"), points_text(kGridProbes)), 0)
      << stderr_text();
  expect_linear_sizes(printed_sizes());
}

TEST_F(CliSizesTest, MalformedBackgroundFileExitsBadInputNamingFileAndLine) {
  write_linear_grid(dir_ / "linear.msh");
  std::string text = read_file(dir_ / "linear.msh");
  const std::size_t data = text.find("$NodeData");
  ASSERT_NE(data, std::string::npos);
  // Node 3's size (the 11th line of the section) becomes negative.
  std::size_t line = data;
  for (int k = 0; k < 11; ++k) line = text.find('\n', line) + 1;
  text.replace(line, text.find('\n', line) - line, "3 -0.5");
  write_file(dir_ / "bad.msh", text);
  const int bad_line = 1 + static_cast<int>(std::count(text.begin(), text.begin() + line, '\n'));
  write_file(dir_ / "spec.json", R"({"maxSize": 10, "background": {"file": "bad.msh"}})");
  EXPECT_EQ(run("sizes --spec " + shell_quoted(dir_ / "spec.json"), "0 0 0\n"), 3);
  EXPECT_THAT(stderr_text(), HasSubstr("spec.json: background.file (\"bad.msh\"): "));
  EXPECT_THAT(stderr_text(), HasSubstr("bad.msh:" + std::to_string(bad_line) +
                                       ": the size of node tag 3 must be finite and > 0"));
  EXPECT_TRUE(stdout_text().empty());
}

TEST_F(CliSizesTest, MissingBackgroundFileOrFileWithInlineGridExitsBadInput) {
  write_file(dir_ / "missing.json", R"({"maxSize": 1, "background": {"file": "nowhere.msh"}})");
  EXPECT_EQ(run("sizes --spec " + shell_quoted(dir_ / "missing.json"), "0 0 0\n"), 3);
  EXPECT_THAT(stderr_text(), HasSubstr("nowhere.msh"));
  write_file(dir_ / "sol.json", R"({"maxSize": 1, "background": {"file": "nosol.mesh"}})");
  write_linear_grid(dir_ / "nosol.mesh");
  fs::remove(dir_ / "nosol.sol");
  EXPECT_EQ(run("sizes --spec " + shell_quoted(dir_ / "sol.json"), "0 0 0\n"), 3);
  EXPECT_THAT(stderr_text(), HasSubstr("nosol.sol"));
  write_file(dir_ / "both.json", R"({"maxSize": 1, "background": {"file": "nosol.mesh",
      "sizes": [1, 1, 1, 1]}})");
  EXPECT_EQ(run("sizes --spec " + shell_quoted(dir_ / "both.json"), "0 0 0\n"), 3);
  EXPECT_THAT(stderr_text(), HasSubstr("background gives both a file"));
}

// The CLI reads the grid file and streams the grid: the server meshes with it, finer than
// the mesh grown up to maxSize without it (the grid asks for 0.25 to 0.7 in the box).
TEST_F(CliSizesTest, VolumeWithBackgroundFileMeshesValidlyAndFinerThanMaxSize) {
  const Mesh front = box_surface({0, 0, 0}, {2, 2, 2}, 0.25);
  ASSERT_TRUE(write_mesh(front, (dir_ / "box.mesh").string()).ok());
  write_linear_grid(dir_ / "linear.msh", 0.25);
  write_file(dir_ / "spec.json",
             R"({"maxSize": 1.0, "growth": 1.5, "background": {"file": "linear.msh"}})");
  ASSERT_EQ(
      run("volume " + shell_quoted(dir_ / "box.mesh") + " -o " + shell_quoted(dir_ / "graded.msh") +
          " --spec " + shell_quoted(dir_ / "spec.json") + " --quiet"),
      0)
      << stderr_text();
  ASSERT_EQ(run("volume " + shell_quoted(dir_ / "box.mesh") + " -o " +
                shell_quoted(dir_ / "uniform.msh") + " --size 1.0 --growth 1.5 --quiet"),
            0)
      << stderr_text();
  absl::StatusOr<Mesh> graded = read_mesh((dir_ / "graded.msh").string());
  absl::StatusOr<Mesh> uniform = read_mesh((dir_ / "uniform.msh").string());
  ASSERT_TRUE(graded.ok()) << graded.status();
  ASSERT_TRUE(uniform.ok()) << uniform.status();
  const ValidationReport report = validate_volume_mesh(*graded, &front);
  EXPECT_TRUE(report.valid()) << report.to_string();
  EXPECT_GT(graded->tets.size(), uniform->tets.size());
}

// The mean edge length of the tets of `mesh` whose centroid has lo <= x < hi.
double mean_edge_in_slab(const Mesh& mesh, double lo, double hi) {
  double sum = 0.0;
  int edges = 0;
  for (const Tet& tet : mesh.tets) {
    const double x = (mesh.points[tet[0]][0] + mesh.points[tet[1]][0] + mesh.points[tet[2]][0] +
                      mesh.points[tet[3]][0]) / 4.0;
    if (x < lo || x >= hi) continue;
    for (int a = 0; a < 4; ++a) {
      for (int b = a + 1; b < 4; ++b) {
        const Point& p = mesh.points[tet[a]];
        const Point& q = mesh.points[tet[b]];
        sum += std::hypot(q[0] - p[0], q[1] - p[1], q[2] - p[2]);
        ++edges;
      }
    }
  }
  return edges == 0 ? 0.0 : sum / edges;
}

// A grid far over gRPC's 4 MiB message limit (205 379 points, 1 170 672 tets: about 20 MB on the
// wire) is streamed in slices: the box meshes validly, its elements small where the grid's
// linear field 0.1 + 0.2 x is small.
TEST_F(CliSizesTest, VolumeWithA200kPointBackgroundGridStreamsItAndFollowsItsField) {
  const Mesh front = box_surface({0, 0, 0}, {1, 1, 1}, 0.2);
  ASSERT_TRUE(write_mesh(front, (dir_ / "box.mesh").string()).ok());
  Mesh grid = box_tets({-0.5, -0.5, -0.5}, {1.5, 1.5, 1.5}, 58);
  ASSERT_EQ(grid.points.size(), 205379u);
  std::vector<double> sizes;
  for (const Point& p : grid.points) sizes.push_back(0.1 + 0.2 * std::clamp(p[0], 0.0, 1.0));
  ASSERT_TRUE(write_sized_grid(grid, sizes, (dir_ / "big.msh").string()).ok());
  write_file(dir_ / "spec.json",
             R"({"maxSize": 0.5, "growth": 1.5, "background": {"file": "big.msh"}})");
  ASSERT_EQ(
      run("volume " + shell_quoted(dir_ / "box.mesh") + " -o " + shell_quoted(dir_ / "box.msh") +
          " --spec " + shell_quoted(dir_ / "spec.json") + " --quiet"),
      0)
      << stderr_text();
  absl::StatusOr<Mesh> mesh = read_mesh((dir_ / "box.msh").string());
  ASSERT_TRUE(mesh.ok()) << mesh.status();
  const ValidationReport report = validate_volume_mesh(*mesh, &front);
  EXPECT_TRUE(report.valid()) << report.to_string();
  const double fine = mean_edge_in_slab(*mesh, 0.0, 0.25);
  const double coarse = mean_edge_in_slab(*mesh, 0.75, 1.0);
  EXPECT_GT(fine, 0.0);
  EXPECT_LT(fine, 0.75 * coarse) << fine << " vs " << coarse;
}

// A point source at the centre of a box refines the interior: the mesh is valid and has more
// tets within r1 of the source than the uniform mesh of the same box (without --spec).
TEST_F(CliSizesTest, VolumeWithPointSourceSpecMeshesABoxValidlyAndRefinesNearTheSource) {
  const Mesh front = box_surface({0, 0, 0}, {2, 2, 2}, 0.5);
  ASSERT_TRUE(write_mesh(front, (dir_ / "box.mesh").string()).ok());
  write_file(dir_ / "spec.json", R"({"maxSize": 0.5, "growth": 1.2, "sources": [
      {"points": [{"x": 1, "y": 1, "z": 1}], "delta0": 0.15, "r0": 0.0, "r1": 0.5,
       "power": {"gamma": 1.0}}]})");
  ASSERT_EQ(
      run("volume " + shell_quoted(dir_ / "box.mesh") + " -o " + shell_quoted(dir_ / "spec.msh") +
          " --spec " + shell_quoted(dir_ / "spec.json") + " --quiet"),
      0)
      << stderr_text();
  ASSERT_EQ(run("volume " + shell_quoted(dir_ / "box.mesh") + " -o " +
                shell_quoted(dir_ / "uniform.msh") + " --size 0.5 --growth 1.2 --quiet"),
            0)
      << stderr_text();
  absl::StatusOr<Mesh> refined = read_mesh((dir_ / "spec.msh").string());
  absl::StatusOr<Mesh> uniform = read_mesh((dir_ / "uniform.msh").string());
  ASSERT_TRUE(refined.ok()) << refined.status();
  ASSERT_TRUE(uniform.ok()) << uniform.status();
  const ValidationReport report = validate_volume_mesh(*refined, &front);
  EXPECT_TRUE(report.valid()) << report.to_string();
  const int refined_near = tets_near(*refined, {1, 1, 1}, 0.5);
  const int uniform_near = tets_near(*uniform, {1, 1, 1}, 0.5);
  EXPECT_GT(refined_near, 2 * uniform_near) << refined_near << " vs " << uniform_near;
}

TEST_F(CliSizesTest, VolumeSpecErrorExitsBadInputBeforeMeshing) {
  ASSERT_TRUE(write_mesh(box_surface({0, 0, 0}, {1, 1, 1}, 0.5), (dir_ / "box.mesh").string()).ok());
  write_file(dir_ / "spec.json", R"({"maxSize": 0.5, "sources": [{"delta0": 0.2, "r1": 0.5,
      "power": {"gamma": 1.0}}]})");
  EXPECT_EQ(
      run("volume " + shell_quoted(dir_ / "box.mesh") + " -o " + shell_quoted(dir_ / "box.msh") +
          " --spec " + shell_quoted(dir_ / "spec.json") + " --quiet"),
      3);
  EXPECT_THAT(stderr_text(), HasSubstr("sources[0].points"));
  EXPECT_FALSE(fs::exists(dir_ / "box.msh"));
}

}  // namespace
}  // namespace afmesh
