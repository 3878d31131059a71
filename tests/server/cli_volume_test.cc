// `afmesh volume` as a user runs it: the afmesh and afmesh-server binaries, with a private server
// (started beside the CLI, stopped afterwards) and with a shared one, on a tiny closed front.
#include <signal.h>
#include <stdlib.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <thread>
#include <vector>

#include "absl/strings/str_split.h"
#include "core/io/mesh_io.h"
#include "core/quality/validate.h"
#include "core/shapes/shapes.h"
#include "core/volume/generate_volume_mesh.h"
#include "gmock/gmock.h"
#include "gtest/gtest.h"
#include "tests/server/cli_test_support.h"

namespace afmesh {
namespace {

namespace fs = std::filesystem;
using cli_test::kTetrahedronFront;
using cli_test::read_file;
using cli_test::shell_quoted;
using ::testing::HasSubstr;
using ::testing::Not;

// The same front with one triangle missing: not closed.
constexpr const char* kOpenFront = R"(MeshVersionFormatted 2
Dimension 3
Vertices
4
0 0 0 0
1 0 0 0
0 1 0 0
0 0 1 0
Triangles
3
1 2 4 7
1 4 3 7
2 3 4 7
End
)";

class CliVolumeTest : public ::testing::Test {
 protected:
  void SetUp() override {
    char pattern[] = "/tmp/afmesh-cli-test-XXXXXX";
    ASSERT_NE(mkdtemp(pattern), nullptr);
    dir_ = pattern;
    fs::create_directory(dir_ / "tmp");
    write_file(dir_ / "front.mesh", kTetrahedronFront);
    write_file(dir_ / "open.mesh", kOpenFront);
  }

  void TearDown() override { fs::remove_all(dir_); }

  static void write_file(const fs::path& path, const char* text) { std::ofstream(path) << text; }

  // Runs `afmesh volume ARGS` with TMPDIR in the test folder; stdout and stderr go to files.
  // Returns the exit status.
  int run_volume(const std::string& args) {
    const std::string command = "TMPDIR=" + shell_quoted(dir_ / "tmp") + " " + AFMESH_CLI_BINARY +
                                " volume " + args + " >" + shell_quoted(dir_ / "stdout.txt") +
                                " 2>" + shell_quoted(dir_ / "stderr.txt");
    const int status = std::system(command.c_str());
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  }

  std::string stdout_text() const { return read_file(dir_ / "stdout.txt"); }
  std::string stderr_text() const { return read_file(dir_ / "stderr.txt"); }

  // True once the private server's folder is gone from TMPDIR.
  bool private_folders_removed() const { return fs::is_empty(dir_ / "tmp"); }

  fs::path dir_;
};

TEST_F(CliVolumeTest, PrivateServerMeshesTetrahedronFrontAndIsCleanedUp) {
  const fs::path out = dir_ / "volume.msh";
  ASSERT_EQ(run_volume(shell_quoted(dir_ / "front.mesh") + " -o " + shell_quoted(out) +
                       " --size 1 --json"),
            0)
      << stderr_text();
  EXPECT_THAT(stdout_text(), HasSubstr("\"tetCount\""));
  EXPECT_THAT(stdout_text(), HasSubstr("\"passed\": true"));
  EXPECT_TRUE(private_folders_removed());

  absl::StatusOr<Mesh> mesh = read_mesh(out.string());
  ASSERT_TRUE(mesh.ok()) << mesh.status();
  EXPECT_GE(mesh->tets.size(), 1u);
  EXPECT_EQ(mesh->triangles.size(), 4u);
  EXPECT_EQ(mesh->triangle_tags, std::vector<Index>(4, 7));
}

TEST_F(CliVolumeTest, OpenFrontExitsWithBadInputNamingTheProblem) {
  EXPECT_EQ(run_volume(shell_quoted(dir_ / "open.mesh") + " -o " + shell_quoted(dir_ / "v.msh") +
                       " --quiet"),
            3);
  EXPECT_THAT(stderr_text(), HasSubstr("edge"));
  EXPECT_FALSE(fs::exists(dir_ / "v.msh"));
  EXPECT_TRUE(private_folders_removed());
}

// A front with a triangle that repeats a point and a hole elsewhere (occt-misc's bearing.stl and
// motor.stl): refused, naming the repeated point, and saying why that triangle was not dropped.
TEST_F(CliVolumeTest, RepeatedPointsOnAnOpenFrontAreRefusedWithWhyTheyStayed) {
  Mesh front = box_surface({0, 0, 0}, {1, 1, 1}, 0.5);
  front.triangles.pop_back();
  front.triangles.push_back({4, 4, 5});
  front.triangle_tags.assign(front.triangles.size(), 0);
  ASSERT_TRUE(write_mesh(front, (dir_ / "repeated.mesh").string()).ok());
  EXPECT_EQ(run_volume(shell_quoted(dir_ / "repeated.mesh") + " -o " +
                       shell_quoted(dir_ / "v.msh") + " --quiet"),
            3);
  EXPECT_THAT(stderr_text(), HasSubstr("repeats a point"));
  EXPECT_THAT(stderr_text(),
              HasSubstr("the 1 triangle(s) that repeat a point were not dropped: without them 3 "
                        "triangle side(s) still have no single neighbour across them"));
  EXPECT_FALSE(fs::exists(dir_ / "v.msh"));
}

// Regression for issue 10 (a gmsh-written STL of a sphere with a cavity was refused for a few
// flipped facets): a sphere with a box cavity whose cavity faces the same way as the outer wall
// and five of whose outer facets are flipped meshes valid, with warnings that count the changes,
// and the written boundary is the repaired (consistently oriented, outward) front.
TEST_F(CliVolumeTest, FlippedFacetsAndAnOutwardCavityAreRepairedWithAWarning) {
  Mesh front = sphere_surface({0, 0, 0}, 1.0, 0.3);
  const std::size_t outer = front.triangles.size();
  const Mesh cavity = box_surface({-0.3, -0.3, -0.3}, {0.3, 0.3, 0.3}, 0.2);
  const Index offset = static_cast<Index>(front.points.size());
  front.points.insert(front.points.end(), cavity.points.begin(), cavity.points.end());
  for (Triangle t : cavity.triangles) {
    for (Index& p : t) p += offset;
    front.triangles.push_back(t);  // facing out of the cavity: wrong for a cavity
  }
  front.triangle_tags.assign(front.triangles.size(), 0);
  for (std::size_t t : {0, 3, 17, 30, 31}) std::swap(front.triangles[t][1], front.triangles[t][2]);
  ASSERT_TRUE(write_mesh(front, (dir_ / "cavity.mesh").string()).ok());

  const fs::path out = dir_ / "cavity.msh";
  ASSERT_EQ(run_volume(shell_quoted(dir_ / "cavity.mesh") + " -o " + shell_quoted(out) +
                       " --size 0.3 --json"),
            0)
      << stderr_text();
  EXPECT_THAT(stderr_text(), HasSubstr("re-oriented " +
                                       std::to_string(5 + cavity.triangles.size()) +
                                       " triangle(s)"));
  EXPECT_THAT(stdout_text(), HasSubstr("\"trianglesReoriented\": \"" +
                                       std::to_string(5 + cavity.triangles.size()) + "\""));
  EXPECT_THAT(stdout_text(), HasSubstr("\"cavities\": \"1\""));
  EXPECT_THAT(stdout_text(), HasSubstr("\"passed\": true"));
  absl::StatusOr<Mesh> mesh = read_mesh(out.string());
  ASSERT_TRUE(mesh.ok()) << mesh.status();
  ASSERT_EQ(mesh->triangles.size(), front.triangles.size());
  Mesh boundary{mesh->points, mesh->triangles, mesh->triangle_tags, {}, {}};
  EXPECT_TRUE(validate_surface(boundary).valid()) << validate_surface(boundary).to_string();
  EXPECT_TRUE(validate_volume_mesh(*mesh, &boundary).valid());
  EXPECT_GT(outer, 0u);
}

// The core's warnings reach the user: occt-misc's shape.stl at 0.8 times its mean edge (at its
// mean edge it closes on the first run since sliver needles take points as other faces do) is
// meshed again with the size halved where its front stopped, each time a warning, and the mesh
// is valid.
TEST_F(CliVolumeTest, FrontMeshedAgainWhereItStoppedIsWarnedAbout) {
  const std::string in = std::string(AFMESH_SOURCE_DIR) + "/tests/data/occt_shape.stl";
  const fs::path out = dir_ / "shape.vtu";
  ASSERT_EQ(run_volume(shell_quoted(in) + " -o " + shell_quoted(out) + " --size 20.8867 --json"),
            0)
      << stderr_text();
  EXPECT_THAT(stderr_text(), HasSubstr("warning: the front got stuck at face"));
  EXPECT_THAT(stderr_text(), HasSubstr("meshed again with the size halved within"));
  EXPECT_THAT(stdout_text(), HasSubstr("\"passed\": true"));
}

// A raw CAD tessellation the volume front cannot fill as given (libcgal-demo's boeing, 945 of
// its 2,564 triangles with angles under 5 degrees, down to 0.1, at its mean edge: every run
// stops over its budget among the slivers; netgen-doc's hinge at a 25th of its diagonal, used
// here before, closes on its first run since sliver needles take points as other faces do), here
// allowed one rerun only. The volume is then filled from its points (its triangles recovered by
// flips and by refilling cavities with points inside); the warning says why, that a
// re-triangulated surface avoids it, and the CLI names the flags that may give a mesh of the size
// asked: --remesh-surface, which the user had not given, and --max-reruns with more.
TEST_F(CliVolumeTest, SliverFrontThatStopsIsFilledAndToldOfRemeshSurface) {
  const std::string in = std::string(AFMESH_SOURCE_DIR) + "/tests/data/cgal_boeing.stl";
  const fs::path out = dir_ / "boeing.msh";
  ASSERT_EQ(run_volume(shell_quoted(in) + " -o " + shell_quoted(out) + " --max-reruns 1 --json"),
            0)
      << stderr_text();
  EXPECT_THAT(stderr_text(), HasSubstr("after meshing again once"));
  EXPECT_THAT(stderr_text(), HasSubstr(kDelaunayFillWords));
  EXPECT_THAT(stderr_text(), HasSubstr("--max-reruns N (up to 32) meshes it again more times"));
  EXPECT_THAT(stderr_text(), HasSubstr("sliver triangles"));
  EXPECT_THAT(stderr_text(), Not(HasSubstr("give a size near")));  // the size already is
  EXPECT_THAT(stderr_text(), HasSubstr(kRetriangulatedSurfaceAdvice));
  EXPECT_THAT(stderr_text(), HasSubstr("--remesh-surface re-triangulates IN at the size first"));
  EXPECT_THAT(stdout_text(), HasSubstr("\"passed\": true"));
  EXPECT_TRUE(fs::exists(out));
}

// Issue 10, part 3: the same hinge got stuck in each of its first 9 runs, each time elsewhere,
// when a run stopped at its first stuck face; it failed with the default 8 reruns and closed with
// --max-reruns 9. A run now sets each stuck face aside and goes on (ParkedFaces in
// generate_volume_mesh.cc), and the next run has the size halved at every place the first got
// stuck at: with the default reruns the hinge was valid after two, the first naming several
// places. Since sliver needles take points as other faces do the hinge closes on its first run;
// occt-misc's shape.stl at 0.8 times its mean edge stops at three places and is valid after one
// rerun.
TEST_F(CliVolumeTest, FrontStuckAtSeveralPlacesIsRefinedAtAllOfThemInOneRerun) {
  const std::string in = std::string(AFMESH_SOURCE_DIR) + "/tests/data/occt_shape.stl";
  const fs::path out = dir_ / "shape.msh";
  ASSERT_EQ(run_volume(shell_quoted(in) + " -o " + shell_quoted(out) + " --size 20.8867 --json"),
            0)
      << stderr_text();
  std::vector<std::string> reruns;
  for (const absl::string_view line : absl::StrSplit(stderr_text(), '\n')) {
    const std::size_t at = line.find("meshed again with the size halved within");
    if (at != absl::string_view::npos) reruns.emplace_back(line.substr(at));
  }
  ASSERT_EQ(reruns.size(), 1u) << stderr_text();
  std::size_t places = 0;
  for (std::size_t at = 0; (at = reruns[0].find(" of (", at)) != std::string::npos; ++at) ++places;
  EXPECT_GE(places, 2u) << reruns[0];
  EXPECT_THAT(stdout_text(), HasSubstr("\"passed\": true"));
}

// A CAD tessellation's slivers make the tets round them flat; the summary says so and gives the
// quality away from them (QualityFigures' boundary and away-from-slivers figures).
TEST_F(CliVolumeTest, SummarySaysWhatTheInputsSliversForceAndTheQualityAwayFromThem) {
  const std::string in = std::string(AFMESH_SOURCE_DIR) + "/../shared/corpus/netgen_part1.stl";
  ASSERT_TRUE(fs::exists(in)) << in;
  const fs::path out = dir_ / "part1.msh";
  ASSERT_EQ(run_volume(shell_quoted(in) + " -o " + shell_quoted(out)), 0) << stderr_text();
  EXPECT_THAT(stdout_text(), ::testing::MatchesRegex(
                                 "(.|\n)*input slivers +[1-9][0-9]* boundary triangles with an "
                                 "angle under 20° \\(down to [0-9.]+°\\)(.|\n)*"));
  EXPECT_THAT(stdout_text(), HasSubstr("away from them   min dihedral"));

  ASSERT_EQ(run_volume(shell_quoted(in) + " -o " + shell_quoted(out) + " --json"), 0)
      << stderr_text();
  EXPECT_THAT(stdout_text(), HasSubstr("\"boundarySliverCount\""));
  EXPECT_THAT(stdout_text(), HasSubstr("\"minDihedralAwayFromSliversDeg\""));
}

TEST_F(CliVolumeTest, MaxRerunsOutOfRangeIsAUsageError) {
  EXPECT_EQ(run_volume(shell_quoted(dir_ / "front.mesh") + " -o " + shell_quoted(dir_ / "v.msh") +
                       " --max-reruns 33"),
            2);
  EXPECT_THAT(stderr_text(), HasSubstr("--max-reruns"));
}

TEST_F(CliVolumeTest, MissingInputFileExitsWithBadInput) {
  EXPECT_EQ(run_volume(shell_quoted(dir_ / "absent.stl") + " -o " + shell_quoted(dir_ / "v.msh")),
            3);
  EXPECT_THAT(stderr_text(), HasSubstr("absent.stl"));
}

TEST_F(CliVolumeTest, OutputFormatWithoutTetrahedraIsAUsageError) {
  EXPECT_EQ(run_volume(shell_quoted(dir_ / "front.mesh") + " -o " + shell_quoted(dir_ / "v.stl")),
            2);
  EXPECT_THAT(stderr_text(), HasSubstr("cannot hold tetrahedra"));
}

TEST_F(CliVolumeTest, UnreachableServerExitsWithUnavailable) {
  const std::string address = "unix:" + (dir_ / "nobody.sock").string();
  EXPECT_EQ(run_volume(shell_quoted(dir_ / "front.mesh") + " -o " + shell_quoted(dir_ / "v.msh") +
                       " --server " + address + " --retries 1"),
            5);
  EXPECT_THAT(stderr_text(), HasSubstr("retry 1 of 1 in"));
  EXPECT_THAT(stderr_text(), HasSubstr("cannot reach the server"));
}

// Backpressure (issue 12, part 2): a full server's refusal carries a retry hint; the CLI waits
// (jittered, growing) and sends the call again, saying so, until it passes or --retries runs out.
TEST_F(CliVolumeTest, BusySharedServerIsRetriedWithBackOffUntilItTakesTheCall) {
  const fs::path socket = dir_ / "busy.sock";
  const std::string address = "unix:" + socket.string();
  const pid_t server = cli_test::start_server_process(
      AFMESH_SERVER_BINARY, {"--listen", address, "--workers", "1", "--max-queue", "0", "--quiet"});
  ASSERT_GE(server, 0);
  ASSERT_TRUE(cli_test::wait_for_socket(socket));
  const auto give_up = std::chrono::steady_clock::now() + std::chrono::seconds(30);
  // A job of a few seconds takes the only worker (the L-block example at 0.1: about 136k tets).
  const fs::path busy_err = dir_ / "busy-stderr.txt";
  const std::string busy =
      std::string(AFMESH_CLI_BINARY) + " volume " +
      shell_quoted(fs::path(AFMESH_SOURCE_DIR) / "examples/lblock/lblock.stl") + " -o " +
      shell_quoted(dir_ / "busy.vtu") + " --size 0.1 --server " + address + " >/dev/null 2>" +
      shell_quoted(busy_err);
  std::thread busy_call([&busy] { EXPECT_EQ(std::system(busy.c_str()), 0); });
  while (read_file(busy_err).find("front") == std::string::npos &&
         std::chrono::steady_clock::now() < give_up) {
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }

  const std::string small = shell_quoted(dir_ / "front.mesh") + " -o " +
                            shell_quoted(dir_ / "v.msh") + " --server " + address;
  EXPECT_EQ(run_volume(small + " --retries 0"), 5);
  EXPECT_THAT(stderr_text(), HasSubstr("the server is busy"));
  EXPECT_THAT(stderr_text(), Not(HasSubstr("retry 1")));

  EXPECT_EQ(run_volume(small + " --retries 20"), 0) << stderr_text();
  EXPECT_THAT(stderr_text(), HasSubstr("the server is busy"));
  EXPECT_THAT(stderr_text(), HasSubstr("retry 1 of 20 in"));
  busy_call.join();
  EXPECT_EQ(cli_test::stop_server_process(server), 0);
}

TEST_F(CliVolumeTest, SharedServerServesCliAndExitsZeroOnSigterm) {
  const fs::path socket = dir_ / "shared.sock";
  const std::string address = "unix:" + socket.string();
  const pid_t server = cli_test::start_server_process(
      AFMESH_SERVER_BINARY, {"--listen", address, "--workers", "1", "--quiet"});
  ASSERT_GE(server, 0);
  ASSERT_TRUE(cli_test::wait_for_socket(socket));

  const fs::path out = dir_ / "shared.vtu";
  EXPECT_EQ(run_volume(shell_quoted(dir_ / "front.mesh") + " -o " + shell_quoted(out) +
                       " --server " + address + " --quiet"),
            0)
      << stderr_text();
  EXPECT_TRUE(fs::exists(out));
  EXPECT_TRUE(private_folders_removed());
  EXPECT_EQ(cli_test::stop_server_process(server), 0);
}

// Client-side balancing (issue 13 part 4): a comma list of replicas and dns:/// names; calls
// go round-robin over the addresses and skip those that cannot be reached.
TEST_F(CliVolumeTest, ReplicaListAndDnsNamesReachALiveReplicaPastADeadOne) {
  const fs::path log = dir_ / "replica.log";
  const pid_t server = cli_test::start_server_process(
      AFMESH_SERVER_BINARY, {"--listen", "127.0.0.1:0", "--workers", "1"}, log);
  ASSERT_GE(server, 0);
  std::string port;
  const auto give_up = std::chrono::steady_clock::now() + std::chrono::seconds(10);
  while (port.empty() && std::chrono::steady_clock::now() < give_up) {
    const std::string text = read_file(log);
    const std::string::size_type at = text.find("listening on 127.0.0.1:");
    if (at != std::string::npos && text.find(' ', at + 23) != std::string::npos)
      port = text.substr(at + 23, text.find(' ', at + 23) - at - 23);
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  ASSERT_FALSE(port.empty()) << read_file(log);
  const std::string front =
      shell_quoted(dir_ / "front.mesh") + " -o " + shell_quoted(dir_ / "v.vtu");
  // Port 1 refuses connections: the list's dead replica, first or second after the shuffle.
  for (int call = 0; call < 4; ++call) {
    EXPECT_EQ(run_volume(front + " --server 127.0.0.1:1,127.0.0.1:" + port + " --retries 0"), 0)
        << stderr_text();
  }
  EXPECT_EQ(run_volume(front + " --server dns:///localhost:" + port + " --retries 0"), 0)
      << stderr_text();
  EXPECT_EQ(cli_test::stop_server_process(server), 0);
  std::size_t calls = 0;
  for (std::string::size_type at = 0;
       (at = read_file(log).find("code=OK", at)) != std::string::npos; ++at) {
    ++calls;
  }
  EXPECT_EQ(calls, 5u);
}

// ----- --envs (crossing environments, paper §2) ----------------------------------------------

TEST_F(CliVolumeTest, BadEnvsValueIsAUsageError) {
  EXPECT_EQ(run_volume(shell_quoted(dir_ / "front.mesh") + " -o " + shell_quoted(dir_ / "v.msh") +
                       " --envs sometimes"),
            2);
  EXPECT_THAT(stderr_text(), HasSubstr("--envs"));
  EXPECT_FALSE(fs::exists(dir_ / "v.msh"));
}

TEST_F(CliVolumeTest, EnvsTagsWithoutTagsIsBadInput) {
  std::string untagged = kTetrahedronFront;
  for (std::size_t at = untagged.find(" 7\n"); at != std::string::npos;
       at = untagged.find(" 7\n", at)) {
    untagged.replace(at, 3, " 0\n");
  }
  write_file(dir_ / "untagged.mesh", untagged.c_str());
  EXPECT_EQ(run_volume(shell_quoted(dir_ / "untagged.mesh") + " -o " +
                       shell_quoted(dir_ / "v.msh") + " --envs tags"),
            3);
  EXPECT_THAT(stderr_text(), HasSubstr("--envs tags: none of the 4 triangles"));
  EXPECT_FALSE(fs::exists(dir_ / "v.msh"));
}

TEST_F(CliVolumeTest, EnvsTagsAndAutoReachTheServer) {
  // The tetrahedron's faces all carry tag 7: one environment, nothing crosses, so it meshes
  // with or without the front filtering; the server says what it marked.
  const fs::path out = dir_ / "tags.msh";
  ASSERT_EQ(run_volume(shell_quoted(dir_ / "front.mesh") + " -o " + shell_quoted(out) +
                       " --size 1 --envs tags"),
            0)
      << stderr_text();
  EXPECT_THAT(stderr_text(), HasSubstr("crossing environments from tags: 1 environment on 4 of 4"));
  EXPECT_THAT(stdout_text(), HasSubstr("environments"));  // the stage's timing
  ASSERT_EQ(run_volume(shell_quoted(dir_ / "front.mesh") + " -o " +
                       shell_quoted(dir_ / "auto.msh") + " --size 1 --envs auto"),
            0)
      << stderr_text();
  EXPECT_THAT(stderr_text(), HasSubstr("crossing environments found: 0 environments"));
}

}  // namespace
}  // namespace afmesh
