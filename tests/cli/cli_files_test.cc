// The file commands of the CLI, run as a user runs them: exit codes tell a valid mesh from an
// invalid one from an unreadable file, and convert keeps the mesh.
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include "core/io/mesh_io.h"
#include "gtest/gtest.h"

namespace afmesh {
namespace {

namespace fs = std::filesystem;

int run(const std::string& args, const fs::path& out) {
  const std::string command = std::string(AFMESH_CLI_BINARY) + " " + args + " > " +
                              out.string() + " 2>&1";
  const int status = std::system(command.c_str());
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

std::string slurp(const fs::path& p) {
  std::ifstream in(p);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

class CliFiles : public ::testing::Test {
 protected:
  void SetUp() override {
    // Unique per process: several checkouts may run the suite on one machine at once.
    dir_ = fs::temp_directory_path() /
           ("afmesh_cli_" + std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()) +
            "_" + std::to_string(getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  fs::path dir_;
  const std::string source_ = AFMESH_SOURCE_DIR;
};

Mesh two_tets() {  // a valid volume mesh: two positive tets sharing face (1, 2, 3)
  Mesh m;
  m.points = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {1, 1, 1}};
  m.tets = {{0, 1, 2, 3}, {1, 4, 2, 3}};
  m.tet_tags = {1, 2};
  return m;
}

TEST_F(CliFiles, StatsOnAValidGmshMeshExitsZeroAndPrintsQuality) {
  EXPECT_EQ(run("stats " + source_ + "/examples/cube/cube.msh", dir_ / "out"), 0);
  const std::string out = slurp(dir_ / "out");
  EXPECT_NE(out.find("tetrahedra 1125"), std::string::npos) << out;
  EXPECT_NE(out.find("validity: valid"), std::string::npos) << out;
  EXPECT_NE(out.find("min dihedral"), std::string::npos) << out;
}

TEST_F(CliFiles, StatsJsonIsOneObjectWithCounts) {
  EXPECT_EQ(run("stats --json " + source_ + "/tests/data/tetgen_cube.mesh", dir_ / "out"), 0);
  const std::string out = slurp(dir_ / "out");
  EXPECT_EQ(out.front(), '{') << out;
  EXPECT_NE(out.find("\"tetrahedra\":172"), std::string::npos) << out;
  EXPECT_NE(out.find("\"valid\":true"), std::string::npos) << out;
}

TEST_F(CliFiles, StatsOnAnInvertedTetExitsFourAndNamesIt) {
  Mesh m = two_tets();
  std::swap(m.tets[1][0], m.tets[1][1]);
  ASSERT_TRUE(write_mesh(m, (dir_ / "bad.msh").string()).ok());
  EXPECT_EQ(run("stats " + (dir_ / "bad.msh").string(), dir_ / "out"), 4);
  EXPECT_NE(slurp(dir_ / "out").find("tet 1"), std::string::npos) << slurp(dir_ / "out");
}

TEST_F(CliFiles, StatsOnAMalformedFileExitsThreeAndNamesTheLine) {
  std::ofstream(dir_ / "broken.mesh") << "MeshVersionFormatted 2\nDimension 3\nVertices\n2\n0 0 0 0\n";
  EXPECT_EQ(run("stats " + (dir_ / "broken.mesh").string(), dir_ / "out"), 3);
  EXPECT_NE(slurp(dir_ / "out").find("broken.mesh:"), std::string::npos) << slurp(dir_ / "out");
}

TEST_F(CliFiles, BadCommandLineExitsTwo) {
  EXPECT_EQ(run("stats", dir_ / "out"), 2);
  EXPECT_EQ(run("no-such-command", dir_ / "out"), 2);
}

TEST_F(CliFiles, ConvertKeepsPointsTetsAndTags) {
  const Mesh m = two_tets();
  ASSERT_TRUE(write_mesh(m, (dir_ / "in.msh").string()).ok());
  for (const char* ext : {".mesh", ".msh"}) {
    const fs::path out = dir_ / (std::string("out") + ext);
    ASSERT_EQ(run("convert " + (dir_ / "in.msh").string() + " " + out.string(), dir_ / "log"), 0)
        << slurp(dir_ / "log");
    absl::StatusOr<Mesh> back = read_mesh(out.string());
    ASSERT_TRUE(back.ok()) << back.status();
    EXPECT_EQ(back->points, m.points);
    EXPECT_EQ(back->tets, m.tets);
    EXPECT_EQ(back->tet_tags, m.tet_tags);
  }
}

TEST_F(CliFiles, ConvertRefusesToDropTetsIntoStl) {
  ASSERT_TRUE(write_mesh(two_tets(), (dir_ / "in.msh").string()).ok());
  EXPECT_NE(run("convert " + (dir_ / "in.msh").string() + " " + (dir_ / "out.stl").string(),
                dir_ / "out"),
            0);
  EXPECT_FALSE(fs::exists(dir_ / "out.stl"));
}

// One positive tet (0, 1, 2, 3) with its boundary: face (0, 2, 1) (opposite point 3) tagged
// 1, face (1, 2, 3) (opposite point 0) tagged 2, the others 0. Point 0 is then on environment 1
// only, point 3 on environment 2 only, points 1 and 2 on both (-1): the tet joins environments
// 1 and 2 across the gap.
// A bipyramid of three tets around the axis from its apex 0 (z = 1) to its apex 4 (z = -1):
// the faces at apex 0 are environment 1, those at apex 4 environment 2, so the equator points
// are on both (ridge points) and every tet joins point 0 of environment 1 with point 4 of
// environment 2.
Mesh tet_across_a_gap() {
  Mesh m;
  m.points = {{0, 0, 1}, {1, 0, 0}, {-0.5, 0.9, 0}, {-0.5, -0.9, 0}, {0, 0, -1}};
  m.triangles = {{0, 1, 2}, {0, 2, 3}, {0, 3, 1}, {4, 2, 1}, {4, 3, 2}, {4, 1, 3}};
  m.triangle_tags = {1, 1, 1, 2, 2, 2};
  m.tets = {{0, 4, 2, 1}, {0, 4, 3, 2}, {0, 4, 1, 3}};
  m.tet_tags = {0, 0, 0};
  return m;
}

TEST_F(CliFiles, StatsReportsTetsAcrossAGapAsAWarningWhenTagsArePresent) {
  ASSERT_TRUE(write_mesh(tet_across_a_gap(), (dir_ / "gap.mesh").string()).ok());
  EXPECT_EQ(run("stats " + (dir_ / "gap.mesh").string(), dir_ / "out"), 0);
  const std::string out = slurp(dir_ / "out");
  EXPECT_NE(out.find("environment_gap            warning"), std::string::npos) << out;
  EXPECT_NE(out.find("tet 0 (0,4,2,1) joins environment 1 (point 0) and environment 2 (point 4)"),
            std::string::npos)
      << out;
}

TEST_F(CliFiles, StatsWithEnvsTagsFailsOnTetsAcrossAGap) {
  ASSERT_TRUE(write_mesh(tet_across_a_gap(), (dir_ / "gap.mesh").string()).ok());
  EXPECT_EQ(run("stats --envs tags " + (dir_ / "gap.mesh").string(), dir_ / "out"), 4);
  EXPECT_NE(slurp(dir_ / "out").find("environment_gap            FAILED"), std::string::npos)
      << slurp(dir_ / "out");
  EXPECT_EQ(run("stats --envs none " + (dir_ / "gap.mesh").string(), dir_ / "out"), 0);
  EXPECT_EQ(slurp(dir_ / "out").find("environment_gap"), std::string::npos) << slurp(dir_ / "out");
}

TEST_F(CliFiles, StatsWithoutTagsHasNoGapCheck) {
  Mesh m = tet_across_a_gap();
  m.triangle_tags.assign(6, 0);
  ASSERT_TRUE(write_mesh(m, (dir_ / "untagged.mesh").string()).ok());
  EXPECT_EQ(run("stats " + (dir_ / "untagged.mesh").string(), dir_ / "out"), 0);
  EXPECT_EQ(slurp(dir_ / "out").find("environment_gap"), std::string::npos) << slurp(dir_ / "out");
}

TEST_F(CliFiles, StatsChecksThinExamplesWithTheRelaxedRuleUnderEnvsTags) {
  for (const char* example : {"/examples/dome/dome.mesh", "/examples/sails/sails.mesh"}) {
    EXPECT_EQ(run("stats --envs tags " + source_ + example, dir_ / "out"), 0)
        << slurp(dir_ / "out");
    EXPECT_NE(slurp(dir_ / "out").find("environments               passed"), std::string::npos)
        << slurp(dir_ / "out");
    // Without environments their crossing sides are self-intersections.
    EXPECT_EQ(run("stats " + source_ + example, dir_ / "out"), 4);
    EXPECT_NE(slurp(dir_ / "out").find("no_self_intersections      FAILED"), std::string::npos);
  }
}

TEST_F(CliFiles, StatsEnvsTagsWithNegativeTagsIsBadInputAndBadValueIsUsage) {
  Mesh m = tet_across_a_gap();
  m.triangle_tags[3] = -4;
  ASSERT_TRUE(write_mesh(m, (dir_ / "negative.mesh").string()).ok());
  EXPECT_EQ(run("stats --envs tags " + (dir_ / "negative.mesh").string(), dir_ / "out"), 3);
  EXPECT_NE(slurp(dir_ / "out").find("triangle 3 has tag -4"), std::string::npos)
      << slurp(dir_ / "out");
  EXPECT_EQ(run("stats --envs auto " + (dir_ / "negative.mesh").string(), dir_ / "out"), 2);
}

}  // namespace
}  // namespace afmesh
