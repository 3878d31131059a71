// A target size well below the input surface's edge lengths (paper §1, F5/F9 with eq. 15): the
// front must shrink its elements from the coarse boundary down to the size wanted inside and
// still close, also along the solid's edges, where two boundary faces meet at 90°.
#include <cstdint>
#include <string>

#include "core/io/mesh_io.h"
#include "core/quality/validate.h"
#include "core/shapes/shapes.h"
#include "core/volume/end_game_watch.h"
#include "core/volume/generate_volume_mesh.h"
#include "gtest/gtest.h"

namespace afmesh {
namespace {

void expect_valid_volume_mesh(const Mesh& surface, double size) {
  VolumeParams params;
  params.size = size;
  absl::StatusOr<VolumeResult> result = generate_volume_mesh(surface, params, no_progress());
  ASSERT_TRUE(result.ok()) << "size " << size << ": " << result.status();
  const ValidationReport report = validate_volume_mesh(result->mesh, &surface);
  EXPECT_TRUE(report.valid()) << "size " << size << ": " << report.to_string();
}

// The shipped cube (unstructured triangles with edges 0.12–0.20) at about 0.4 × its edges.
TEST(CoarseSurface, CubeExampleMeshesAtSizeWellBelowItsEdges) {
  absl::StatusOr<Mesh> cube = read_mesh(std::string(AFMESH_SOURCE_DIR) + "/examples/cube/cube.msh");
  ASSERT_TRUE(cube.ok()) << cube.status();
  cube->tets.clear();
  cube->tet_tags.clear();
  expect_valid_volume_mesh(*cube, 0.07);
}

// A structured box surface with edges 0.25 (right triangles) at 0.4 × its edges.
TEST(CoarseSurface, BoxMeshesAtSizeWellBelowItsEdges) {
  expect_valid_volume_mesh(box_surface({0, 0, 0}, {1, 1, 1}, 0.25), 0.1);
}

// Regression for issue 10 (never hang): the shipped cube at 0.02, 7.5 × under its edges, meshed
// all but 2e-4 of its volume after 1M steps and then built ever smaller elements in the last
// gaps along its faces without end (no answer after 400 s). The end game must shrink the front;
// a front that stops shrinking ends the job with FAILED_PRECONDITION saying where and why.
// When such a front meshes, this becomes a test that it is valid.
TEST(Regression, Issue10EndGameThatStopsClosingEndsTheJob) {
  absl::StatusOr<Mesh> cube = read_mesh(std::string(AFMESH_SOURCE_DIR) + "/examples/cube/cube.msh");
  ASSERT_TRUE(cube.ok()) << cube.status();
  cube->tets.clear();
  cube->tet_tags.clear();
  VolumeParams params;
  params.size = 0.02;
  params.optimise = false;
  absl::StatusOr<VolumeResult> result = generate_volume_mesh(*cube, params, no_progress());
  ASSERT_FALSE(result.ok());
  EXPECT_EQ(result.status().code(), absl::StatusCode::kFailedPrecondition);
  EXPECT_NE(result.status().message().find("the front stopped closing"), std::string::npos)
      << result.status();
  EXPECT_NE(result.status().message().find("input edges far longer than the size"),
            std::string::npos)
      << result.status();
}

// Issue 10 part 2 (never hang): the end game's watch. Before the elements hold all but
// EndGameWatch::kShare of the volume it never fires; after, a front that does not beat its
// smallest size for kSteps + kStepsPerFace × that size has stalled, and every new record starts
// the count again.
TEST(EndGameWatch, FiresOnlyWhenTheLastFacesStopShrinking) {
  using volume::EndGameWatch;
  EndGameWatch watch;
  const double all = 1.0, nearly = 1.0 - 0.5 * EndGameWatch::kShare;
  for (std::int64_t step = 0; step < 10 * EndGameWatch::kSteps; ++step)
    ASSERT_FALSE(watch.stalled(0.5, all, 100, step)) << step;  // not in the end game yet
  const std::int64_t start = 10 * EndGameWatch::kSteps;
  const std::int64_t patience = EndGameWatch::kSteps + EndGameWatch::kStepsPerFace * 100;
  EXPECT_FALSE(watch.stalled(nearly, all, 100, start));  // the first record
  EXPECT_EQ(watch.smallest_front(), 100);
  EXPECT_FALSE(watch.stalled(nearly, all, 150, start + patience));  // larger: not a record
  EXPECT_TRUE(watch.stalled(nearly, all, 150, start + patience + 1));
  EXPECT_FALSE(watch.stalled(nearly, all, 99, start + patience + 2));  // a record: count again
  EXPECT_EQ(watch.smallest_front(), 99);
  const std::int64_t record = start + patience + 2;
  const std::int64_t patience_now = EndGameWatch::kSteps + EndGameWatch::kStepsPerFace * 99;
  EXPECT_FALSE(watch.stalled(nearly, all, 120, record + patience_now));
  EXPECT_TRUE(watch.stalled(nearly, all, 120, record + patience_now + 1));
}

}  // namespace
}  // namespace afmesh
