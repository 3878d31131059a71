// End to end: thin and crossing fronts meshed with crossing environments (paper §2, §5 (a),
// (b)), through the core mesher and through the CLI and server. The front filters by
// environment (core/volume/front_steps.h). The crossing X of two plates is DISABLED_ (see its
// test): it needs environments per quadrant.
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include "core/environments/detect_environments.h"
#include "core/environments/environments.h"
#include "core/io/mesh_io.h"
#include "core/quality/validate.h"
#include "core/shapes/thin_shapes.h"
#include "core/volume/generate_volume_mesh.h"
#include "proto/size_spec_convert.h"

namespace afmesh {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

std::string source_path(const std::string& relative) {
  return std::string(AFMESH_SOURCE_DIR) + "/" + relative;
}

Mesh read_front(const std::string& relative) {
  absl::StatusOr<Mesh> mesh = read_mesh(source_path(relative));
  EXPECT_TRUE(mesh.ok()) << mesh.status();
  return mesh.ok() ? *std::move(mesh) : Mesh{};
}

// The size specification of a shipped JSON file.
SizeSpec read_spec(const std::string& relative) {
  std::ifstream in(source_path(relative));
  const std::string json((std::istreambuf_iterator<char>(in)), {});
  absl::StatusOr<v1::SizeSpec> message = size_spec_proto_from_json(json);
  EXPECT_TRUE(message.ok()) << message.status();
  absl::StatusOr<SizeSpec> spec =
      message.ok() ? size_spec_from_proto(*message) : absl::StatusOr<SizeSpec>(message.status());
  EXPECT_TRUE(spec.ok()) << spec.status();
  return spec.ok() ? *std::move(spec) : SizeSpec{};
}

// Meshes `front` with `face_environments` and checks the result: valid against the front, and
// no tet across a gap. Prints the figures.
void expect_meshes_valid(const char* name, const Mesh& front, const std::optional<SizeSpec>& spec,
                         double size, std::vector<std::int32_t> face_environments) {
  VolumeParams params;
  params.size = size;
  params.spec = spec;
  params.face_environments = face_environments;
  const auto start = std::chrono::steady_clock::now();
  absl::StatusOr<VolumeResult> result = generate_volume_mesh(front, params, no_progress());
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  ASSERT_TRUE(result.ok()) << result.status();
  const std::vector<std::int32_t> lpocr =
      point_environments(front.points.size(), front.triangles, face_environments);
  ValidationParams validation;
  validation.point_environments = lpocr;
  const ValidationReport report = validate_volume_mesh(result->mesh, &front, validation);
  EXPECT_TRUE(report.valid()) << report.to_string();
  const Check* gap = report.find(check::kEnvironmentGap);
  ASSERT_NE(gap, nullptr);
  EXPECT_EQ(gap->finding_count, 0) << gap->summary;
  std::printf("%s: %zu points, %zu tets, %.3f s\n", name, result->mesh.points.size(),
              result->mesh.tets.size(), seconds);
}

TEST(ThinVolume, DomeWithTagEnvironmentsMeshesValid) {
  const Mesh dome = read_front("examples/dome/dome.mesh");
  expect_meshes_valid("dome (tags)", dome, read_spec("examples/dome/dome-sizes.json"), 0.8,
                      dome.triangle_tags);
}

TEST(ThinVolume, DomeWithAutoEnvironmentsMeshesValid) {
  const Mesh dome = read_front("examples/dome/dome.mesh");
  absl::StatusOr<DetectedEnvironments> found = detect_environments(dome, {}, no_progress());
  ASSERT_TRUE(found.ok()) << found.status();
  expect_meshes_valid("dome (auto)", dome, read_spec("examples/dome/dome-sizes.json"), 0.8,
                      found->environments.face);
}

TEST(ThinVolume, SailsWithTagEnvironmentsMeshValid) {
  const Mesh sails = read_front("examples/sails/sails.mesh");
  expect_meshes_valid("sails (tags)", sails, read_spec("examples/sails/sails-sizes.json"), 10.0,
                      sails.triangle_tags);
}

// Not yet: with one environment per sheet side, a side that crosses the other plate ignores that
// plate's faces on both of its halves, and the fronts of the four quadrants pass through the
// other plate into each other (the overlap guard stops it). The X needs environments per
// quadrant (the paper's "all the surfaces lying on one side of a troublesome region"), with the
// sheets split along the crossing line; see the issue note.
TEST(ThinVolume, DISABLED_CrossingPlatesMeshValid) {
  const Mesh plates = crossing_plates_surface();
  expect_meshes_valid("crossing plates (tags)", plates, std::nullopt, 0.5, plates.triangle_tags);
}

// With environments off the dome cannot be meshed: its sides cross. Today the input check
// already refuses it (INVALID_ARGUMENT); the paper's failure (a front stuck on the other side's
// points and faces) would show if that check were bypassed. Either way: not a mesh.
TEST(ThinVolume, DomeWithoutEnvironmentsFails) {
  const Mesh dome = read_front("examples/dome/dome.mesh");
  VolumeParams params;
  params.size = 0.8;
  params.spec = read_spec("examples/dome/dome-sizes.json");
  absl::StatusOr<VolumeResult> result = generate_volume_mesh(dome, params, no_progress());
  EXPECT_FALSE(result.ok());
}

// ----- through the CLI and a private server ---------------------------------------------------

class ThinVolumeCli : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("afmesh_thin_" +
            std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  int run(const std::string& args) {
    const std::string command = std::string(AFMESH_CLI_BINARY) + " " + args + " >" +
                                (dir_ / "out.txt").string() + " 2>&1";
    const int status = std::system(command.c_str());
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  }
  std::string output() const {
    std::ifstream in(dir_ / "out.txt");
    return std::string(std::istreambuf_iterator<char>(in), {});
  }

  // afmesh volume EXAMPLE --spec SIZES --envs ENVS, then afmesh stats --envs tags on the result.
  void mesh_and_check(const std::string& example, const std::string& sizes,
                      const std::string& envs) {
    const fs::path out = dir_ / "volume.msh";
    ASSERT_EQ(run("volume " + source_path(example) + " -o " + out.string() + " --spec " +
                  source_path(sizes) + " --envs " + envs),
              0)
        << output();
    std::printf("%s", output().c_str());
    ASSERT_EQ(run("stats --envs tags " + out.string()), 0) << output();
    EXPECT_THAT(output(), HasSubstr("environment_gap            passed"));
  }

  fs::path dir_;
};

TEST_F(ThinVolumeCli, DomeWithEnvsAuto) {
  mesh_and_check("examples/dome/dome.mesh", "examples/dome/dome-sizes.json", "auto");
}

TEST_F(ThinVolumeCli, DomeWithEnvsTags) {
  mesh_and_check("examples/dome/dome.mesh", "examples/dome/dome-sizes.json", "tags");
}

TEST_F(ThinVolumeCli, SailsWithEnvsTags) {
  mesh_and_check("examples/sails/sails.mesh", "examples/sails/sails-sizes.json", "tags");
}

TEST_F(ThinVolumeCli, SailsWithEnvsAuto) {
  mesh_and_check("examples/sails/sails.mesh", "examples/sails/sails-sizes.json", "auto");
}

}  // namespace
}  // namespace afmesh
