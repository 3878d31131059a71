// The validators and the quality summary stop when their caller cancels (issue 12: a cancelled
// call frees its worker within 100 ms, and on millions of tets these run for seconds), and
// give the same answers as before when it does not.
#include <gtest/gtest.h>

#include <atomic>
#include <cstdint>

#include "core/common/progress.h"
#include "core/quality/measures.h"
#include "core/quality/mesh_topology.h"
#include "core/quality/optimise.h"
#include "core/quality/tet_complex.h"
#include "core/quality/validate.h"
#include "core/shapes/shapes.h"
#include "core/spatial/aabb_tree.h"
#include "tests/quality/test_meshes.h"

namespace afmesh {
namespace {

// cancelled() is false for the first `looks` calls, then true.
class CancelAfter final : public Progress {
 public:
  explicit CancelAfter(std::int64_t looks) : left_(looks) {}
  bool cancelled() const override { return left_.fetch_sub(1) <= 0; }
  std::int64_t looks_left() const { return left_.load(); }

 private:
  mutable std::atomic<std::int64_t> left_;
};

// 16^3 cubes of 6 tets: 24,576 tets, several cancellation looks in every loop over them.
const Mesh& grid() {
  static const Mesh mesh = testing::cube_grid(16);
  return mesh;
}

TEST(Cancellation, CancelCheckLooksOnceEveryIntervalAndStaysStopped) {
  CancelAfter progress(2);
  CancelCheck stop(progress, 10);
  int due_at = -1;
  for (int i = 1; i <= 100 && due_at < 0; ++i) {
    if (stop.due()) due_at = i;
  }
  EXPECT_EQ(due_at, 30);  // looks at calls 10 and 20 see false, the third (call 30) true
  EXPECT_TRUE(stop.stopped());
  EXPECT_TRUE(stop.due());
  EXPECT_EQ(progress.looks_left(), -1);  // no look after the one that saw the cancel
}

TEST(Cancellation, VolumeValidationStopsWhenCancelledAtAnyPoint) {
  const Mesh boundary = testing::boundary_by_brute_force(grid());
  const std::string expected = validate_volume_mesh(grid(), &boundary).to_string();
  // Cancelled before it starts, and after some looks (inside a later check).
  for (std::int64_t looks : {0, 3, 12}) {
    CancelAfter progress(looks);
    const absl::StatusOr<ValidationReport> report =
        validate_volume_mesh(grid(), &boundary, {}, progress);
    EXPECT_EQ(report.status().code(), absl::StatusCode::kCancelled) << "after " << looks;
  }
  CancelAfter never(1 << 30);
  const absl::StatusOr<ValidationReport> report =
      validate_volume_mesh(grid(), &boundary, {}, never);
  ASSERT_TRUE(report.ok()) << report.status();
  EXPECT_TRUE(report->valid());
  EXPECT_EQ(report->to_string(), expected);
}

TEST(Cancellation, SurfaceValidationStopsWhenCancelled) {
  const Mesh sphere = sphere_surface({0, 0, 0}, 1.0, 0.03);
  ASSERT_GT(sphere.triangles.size(), 20000u);
  const std::string expected = validate_surface(sphere).to_string();
  for (std::int64_t looks : {0, 1}) {
    CancelAfter progress(looks);
    EXPECT_EQ(validate_surface(sphere, {}, progress).status().code(), absl::StatusCode::kCancelled)
        << "after " << looks;
  }
  CancelAfter never(1 << 30);
  const absl::StatusOr<ValidationReport> report = validate_surface(sphere, {}, never);
  ASSERT_TRUE(report.ok()) << report.status();
  EXPECT_EQ(report->to_string(), expected);
}

TEST(Cancellation, QualitySummaryStopsWhenCancelled) {
  CancelAfter progress(2);
  EXPECT_EQ(summarize_quality(grid(), progress).status().code(), absl::StatusCode::kCancelled);
  CancelAfter never(1 << 30);
  const absl::StatusOr<QualitySummary> summary = summarize_quality(grid(), never);
  ASSERT_TRUE(summary.ok()) << summary.status();
  EXPECT_EQ(summary->tet_count, static_cast<std::int64_t>(grid().tets.size()));
  EXPECT_EQ(summary->tet_min_dihedral_deg.min, summarize_quality(grid())->tet_min_dihedral_deg.min);
}

TEST(Cancellation, TheOptimiserStopsWhileBuildingItsAdjacency) {
  Mesh mesh = grid();
  CancelAfter progress(0);
  EXPECT_EQ(TetComplex::build(mesh, progress).status().code(), absl::StatusCode::kCancelled);
  EXPECT_EQ(optimise_tets(mesh, 0, OptimiseParams{}, progress).status().code(),
            absl::StatusCode::kCancelled);
  CancelAfter never(1 << 30);
  EXPECT_TRUE(TetComplex::build(mesh, never).ok());
}

TEST(Cancellation, FaceAndPairVisitsEndEarlyOnceStopped) {
  std::vector<Index> ids(grid().tets.size());
  for (Index t = 0; t < static_cast<Index>(ids.size()); ++t) ids[t] = t;
  std::int64_t all = 0, some = 0;
  for_each_tet_face(grid().tets, ids, [&](std::span<const FaceUse>) { ++all; });
  // Filing the 24,576 tets takes three passes, 1152 looks at one per 64 tets; 8 more looks go
  // by 576 of the 4913 points, which own about a third of the faces (a face is grouped at its
  // smallest point, and the low indices are the smallest of many faces).
  CancelAfter late(1160);
  CancelCheck stop(late, 64);
  for_each_tet_face(
      grid().tets, ids, [&](std::span<const FaceUse>) { ++some; }, &stop);
  EXPECT_TRUE(stop.stopped());
  EXPECT_GT(some, 0);
  EXPECT_LT(some, all / 2);

  const Mesh sphere = sphere_surface({0, 0, 0}, 1.0, 0.05);
  std::vector<Box> boxes;
  for (const Triangle& t : sphere.triangles) boxes.push_back(triangle_box(sphere.points, t));
  const AabbTree tree(std::move(boxes));
  std::int64_t pairs = 0, pairs_until_stop = 0;
  tree.for_each_overlapping_pair([&](Index, Index) { ++pairs; });
  CancelAfter progress(0);
  CancelCheck tree_stop(progress, 16);
  tree.for_each_overlapping_pair([&](Index, Index) { ++pairs_until_stop; }, &tree_stop);
  EXPECT_TRUE(tree_stop.stopped());
  EXPECT_LT(pairs_until_stop, pairs / 4);
}

// analyze_triangle_topology stops in each of its passes (the half-edge sort, the edge runs, the
// vertex fans; MeshSurface's features on a 1M-face scan spent ~0.3 s there) and then returns an
// empty topology; never cancelled, the same as without a CancelCheck.
TEST(Cancellation, TheTopologyOfTrianglesStopsInEveryPass) {
  Mesh open = sphere_surface({0, 0, 0}, 1.0, 0.05);
  open.triangles.pop_back();  // one hole: three open edges to find
  const TriangleTopology whole = analyze_triangle_topology(open.triangles);
  ASSERT_EQ(whole.open_edges.size(), 3u);
  CancelAfter never(1 << 30);
  CancelCheck watched(never, 16);
  const TriangleTopology same = analyze_triangle_topology(open.triangles, &watched);
  EXPECT_FALSE(watched.stopped());
  EXPECT_EQ(same.open_edges.size(), whole.open_edges.size());
  EXPECT_EQ(same.edge_count, whole.edge_count);
  const std::int64_t looks = (1 << 30) - never.looks_left();
  ASSERT_GE(looks, 3);
  for (const std::int64_t at : {std::int64_t{0}, looks / 2, looks - 1}) {
    CancelAfter progress(at);
    CancelCheck stop(progress, 16);
    const TriangleTopology cut = analyze_triangle_topology(open.triangles, &stop);
    EXPECT_TRUE(stop.stopped()) << "cancelled at look " << at;
    EXPECT_TRUE(cut.open_edges.empty()) << "cancelled at look " << at;
    EXPECT_EQ(cut.edge_count, 0) << "cancelled at look " << at;
  }
}

}  // namespace
}  // namespace afmesh
