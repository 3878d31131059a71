// MeshSurface on real dirty inputs (../shared/corpus, README there): where a front stops because
// the input crosses itself, the error says so and where, beside the side it stopped at, so that
// a user knows to repair the input rather than to change the size (explain_stuck).
#include <gtest/gtest.h>

#include <string>

#include "core/quality/measures.h"
#include "core/quality/validate.h"
#include "core/shapes/shapes.h"
#include "core/surface/generate_surface_mesh.h"
#include "gmock/gmock.h"
#include "tests/surface/surface_test_shapes.h"

namespace afmesh {
namespace {

using ::testing::HasSubstr;

const absl::Status kStuck = absl::FailedPreconditionError("the surface front got stuck at side");

// libcgal-demo's bones: 26 components, 366 pairs of crossing triangles (corpus README).
TEST(DirtyInput, AStopOnASelfIntersectingInputNamesTheCrossings) {
  const Mesh bones = testing::corpus_mesh("cgal_bones.stl");
  ASSERT_FALSE(bones.triangles.empty());
  const absl::Status explained = explain_stuck(kStuck, bones);
  EXPECT_EQ(explained.code(), absl::StatusCode::kFailedPrecondition);
  EXPECT_THAT(explained.message(), HasSubstr("got stuck at side. The input surface intersects "
                                             "itself: 366 pairs of its triangles cross, the "
                                             "first near ("));
}

TEST(DirtyInput, AStopOnACleanInputAndOtherErrorsAreLeftAsTheyAre) {
  const Mesh sphere = sphere_surface({0, 0, 0}, 1.0, 0.2);
  EXPECT_EQ(explain_stuck(kStuck, sphere), kStuck);
  const absl::Status cancelled = absl::CancelledError("surface meshing cancelled");
  EXPECT_EQ(explain_stuck(cancelled, testing::corpus_mesh("cgal_bones.stl")), cancelled);
}

// End to end: bones at its mean edge is re-triangulated component by component (issue 11 part 6:
// crossing components are each meshed on their own). Every check of the output passes but the
// one the input fails too: the bones cross where the input's do.
TEST(DirtyInput, BonesAreReTriangulatedComponentByComponent) {
  const Mesh bones = testing::corpus_mesh("cgal_bones.stl");
  SurfaceParams params;
  params.size = mean_edge_length(bones);
  const absl::StatusOr<SurfaceResult> result = generate_surface_mesh(bones, params);
  ASSERT_TRUE(result.ok()) << result.status();
  const ValidationReport report = validate_surface(result->mesh);
  for (const Check& c : report.checks)
    EXPECT_TRUE(c.passed() || c.name == check::kNoSelfIntersections) << c.name << ": " << c.summary;
  const Check* crossings = report.find(check::kNoSelfIntersections);
  ASSERT_NE(crossings, nullptr);
  EXPECT_FALSE(crossings->passed()) << "the input's 366 crossing pairs are gone from the output";
}

}  // namespace
}  // namespace afmesh
