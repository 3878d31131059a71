// Integration tests of the volume front: real solids meshed, then checked against invariants.
#include <cmath>
#include <numbers>

#include "core/quality/measures.h"
#include "core/quality/optimise.h"
#include "core/quality/validate.h"
#include "core/shapes/shapes.h"
#include "core/volume/generate_volume_mesh.h"
#include "gtest/gtest.h"
#include "tests/volume/mesh_and_check.h"

namespace afmesh {
namespace {

TEST(VolumeMesh, SingleTetFrontGivesOneTet) {
  Mesh front;
  front.points = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  front.triangles = {{0, 2, 1}, {0, 1, 3}, {1, 2, 3}, {0, 3, 2}};
  front.triangle_tags = {0, 0, 0, 0};
  const VolumeResult r = mesh_and_check(front, 1.0);
  EXPECT_EQ(r.mesh.tets.size(), 1u);
  EXPECT_EQ(r.mesh.points.size(), 4u);
}

TEST(VolumeMesh, CubeIsValidAndBoundaryEqualsFront) {
  const Mesh front = box_surface({0, 0, 0}, {1, 1, 1}, 0.25);
  const VolumeResult r = mesh_and_check(front, 0.25);
  EXPECT_GT(r.mesh.tets.size(), 100u);
}

TEST(VolumeMesh, SphereIsValid) {
  const Mesh front = sphere_surface({0, 0, 0}, 1.0, 0.2);
  mesh_and_check(front, 0.2);
}

TEST(VolumeMesh, TorusIsValid) {
  const Mesh front = torus_surface(1.0, 0.35, 0.12);
  mesh_and_check(front, 0.12);
}

TEST(VolumeMesh, LBlockWithHoleIsValid) {
  const Mesh front = l_block_with_hole_surface(1.0, 0.25);
  mesh_and_check(front, 0.25);
}

// Schönhardt's twisted prism: its three side quads are split along reflex diagonals, so no
// tetrahedralisation of its six corners exists. The front closes it only through the end game
// (F11): a pocket filled from a new kernel point.
TEST(VolumeMesh, SchoenhardtPrismNeedsAndGetsAKernelPoint) {
  const Mesh front = schoenhardt_prism_surface();
  const VolumeResult r = mesh_and_check(front, 1.0);
  EXPECT_GT(r.mesh.points.size(), 6u);  // a Steiner point was needed
}

// Sizes and shapes where the front used to churn at its end: every one must close, valid.
TEST(VolumeMesh, EveryShapeClosesAtManySizes) {
  const Mesh sphere = sphere_surface({0, 0, 0}, 1.0, 0.15);
  const Mesh torus = torus_surface(1.0, 0.35, 0.13);
  const Mesh box = box_surface({0, 0, 0}, {1, 1, 1}, 0.13);
  const Mesh lblock = l_block_with_hole_surface(1.0, 0.12);
  for (double h : {0.13, 0.16}) {
    SCOPED_TRACE(h);
    mesh_and_check(sphere, h);
    mesh_and_check(torus, h);
    mesh_and_check(box, h);
    mesh_and_check(lblock, h);
  }
}

// At this size the end game used to spawn ever tinier elements at one spot (points 1e-5 apart)
// without end: new points now keep a share of the wanted size from the front's points.
TEST(VolumeMesh, LBlockAtHalfTenthFinishes) {
  const Mesh front = l_block_with_hole_surface(0.5, 0.05);
  mesh_and_check(front, 0.05);
}

TEST(VolumeMesh, GrowthGivesFewerElements) {
  const Mesh front = box_surface({0, 0, 0}, {2, 2, 2}, 0.25);
  const VolumeResult uniform = mesh_and_check(front, 1.0, 1.0);
  const VolumeResult graded = mesh_and_check(front, 1.0, 1.3);
  EXPECT_LT(graded.mesh.tets.size(), uniform.mesh.tets.size());
}

TEST(VolumeMesh, SameInputGivesIdenticalOutput) {
  const Mesh front = sphere_surface({0, 0, 0}, 1.0, 0.25);
  const VolumeResult a = mesh_and_check(front, 0.25);
  const VolumeResult b = mesh_and_check(front, 0.25);
  EXPECT_EQ(a.mesh.points, b.mesh.points);
  EXPECT_EQ(a.mesh.tets, b.mesh.tets);
}

// describe_input_near: each cause it names comes with what avoids it, and the client's
// --remesh-surface hint keys on kRetriangulatedSurfaceAdvice (client/cmd_volume.cc).
TEST(VolumeMesh, FailureMessagesNameTheInputNearWhereTheFrontStopped) {
  const auto one_triangle = [](const Point& a, const Point& b, const Point& c) {
    Mesh m;
    m.points = {a, b, c};
    m.triangles = {{0, 1, 2}};
    m.triangle_tags = {0};
    return m;
  };
  const Point at{0.3, 0.1, 0.0};
  const std::string sliver =
      describe_input_near(one_triangle({0, 0, 0}, {1, 0, 0}, {0.5, 0.01, 0}), at, 1.0, 0.5);
  EXPECT_NE(sliver.find("sliver triangles"), std::string::npos) << sliver;
  EXPECT_NE(sliver.find(kRetriangulatedSurfaceAdvice), std::string::npos) << sliver;

  const Mesh coarse = one_triangle({0, 0, 0}, {1, 0, 0}, {0.5, 0.8, 0});
  const std::string longer = describe_input_near(coarse, at, 1.0, 0.1);
  EXPECT_NE(longer.find("far longer than the size"), std::string::npos) << longer;
  EXPECT_NE(longer.find(kRetriangulatedSurfaceAdvice), std::string::npos) << longer;

  const std::string shorter = describe_input_near(coarse, at, 1.0, 10.0);
  EXPECT_NE(shorter.find("far shorter than the size"), std::string::npos) << shorter;
  EXPECT_NE(shorter.find("--growth"), std::string::npos) << shorter;
  EXPECT_NE(shorter.find(kRetriangulatedSurfaceAdvice), std::string::npos) << shorter;

  const std::string fits = describe_input_near(coarse, at, 1.0, 1.0);
  EXPECT_EQ(fits.find(kRetriangulatedSurfaceAdvice), std::string::npos) << fits;
  EXPECT_NE(fits.find("the 1 input triangles within 1 of there"), std::string::npos) << fits;

  const std::string none = describe_input_near(coarse, {10, 10, 10}, 1.0, 1.0);
  EXPECT_NE(none.find("no input triangle within 1 of there"), std::string::npos) << none;
}

TEST(VolumeMesh, MeshedAgainSaysOnceForOneRerun) {
  EXPECT_EQ(meshed_again_times(1), "after meshing again once");
  EXPECT_EQ(meshed_again_times(3), "after meshing again 3 times");
}

TEST(VolumeMesh, RejectsOpenFront) {
  Mesh front = box_surface({0, 0, 0}, {1, 1, 1}, 0.5);
  front.triangles.pop_back();
  front.triangle_tags.pop_back();
  VolumeParams params;
  params.size = 0.5;
  const auto r = generate_volume_mesh(front, params, no_progress());
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.status().code(), absl::StatusCode::kInvalidArgument);
  EXPECT_NE(r.status().message().find("closed"), std::string_view::npos) << r.status();
}

TEST(VolumeMesh, RejectsInwardFront) {
  Mesh front = box_surface({0, 0, 0}, {1, 1, 1}, 0.5);
  for (Triangle& t : front.triangles) std::swap(t[1], t[2]);
  VolumeParams params;
  params.size = 0.5;
  const auto r = generate_volume_mesh(front, params, no_progress());
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.status().code(), absl::StatusCode::kInvalidArgument);
}

TEST(VolumeMesh, RejectsBadParams) {
  const Mesh front = box_surface({0, 0, 0}, {1, 1, 1}, 0.5);
  VolumeParams params;
  params.size = -1;
  EXPECT_EQ(generate_volume_mesh(front, params, no_progress()).status().code(),
            absl::StatusCode::kInvalidArgument);
  params.size = 0.5;
  params.growth = 0.5;
  EXPECT_EQ(generate_volume_mesh(front, params, no_progress()).status().code(),
            absl::StatusCode::kInvalidArgument);
  params.growth = 1.0;
  params.local_refinements = -1;
  EXPECT_EQ(generate_volume_mesh(front, params, no_progress()).status().code(),
            absl::StatusCode::kInvalidArgument);
  params.local_refinements = 0;
  params.budget_share = 0;
  const auto r = generate_volume_mesh(front, params, no_progress());
  EXPECT_EQ(r.status().code(), absl::StatusCode::kInvalidArgument);
  EXPECT_NE(r.status().message().find("budget_share"), std::string_view::npos) << r.status();
}

class CancelAfter : public Progress {
 public:
  explicit CancelAfter(int n) : n_(n) {}
  bool cancelled() const override { return ++calls_ > n_; }

 private:
  int n_;
  mutable int calls_ = 0;
};

TEST(VolumeMesh, CancellationStopsTheFront) {
  const Mesh front = sphere_surface({0, 0, 0}, 1.0, 0.1);
  VolumeParams params;
  params.size = 0.1;
  CancelAfter progress(2);
  const auto r = generate_volume_mesh(front, params, progress);
  EXPECT_EQ(r.status().code(), absl::StatusCode::kCancelled);
}

}  // namespace
}  // namespace afmesh


namespace afmesh {
namespace {

// Mean edge length of the tets whose centroid lies within [r_lo, r_hi) of x.
double mean_edge_near(const Mesh& m, const Point& x, double r_lo, double r_hi) {
  double sum = 0;
  int n = 0;
  for (const Tet& t : m.tets) {
    Point c{0, 0, 0};
    for (Index p : t)
      for (int a = 0; a < 3; ++a) c[a] += m.points[p][a] / 4;
    const double r = std::sqrt((c[0] - x[0]) * (c[0] - x[0]) + (c[1] - x[1]) * (c[1] - x[1]) +
                               (c[2] - x[2]) * (c[2] - x[2]));
    if (r < r_lo || r >= r_hi) continue;
    for (int i = 0; i < 4; ++i)
      for (int j = i + 1; j < 4; ++j) {
        const Point& a = m.points[t[i]];
        const Point& b = m.points[t[j]];
        sum += std::sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) +
                         (a[2] - b[2]) * (a[2] - b[2]));
        ++n;
      }
  }
  return n ? sum / n : 0.0;
}

TEST(VolumeMesh, PointSourceMakesElementsSmallNearIt) {
  // A box with a coarse boundary, a point source at its centre.
  const Mesh front = box_surface({-1, -1, -1}, {1, 1, 1}, 0.4);
  VolumeParams params;
  SizeSpec spec;
  spec.max_size = 0.4;
  spec.growth = 1.2;
  SizeSource source;
  source.points = {{0, 0, 0}};
  source.delta0 = 0.12;
  source.r0 = 0.1;
  source.r1 = 0.5;
  source.law = PowerLaw{1.0};
  spec.sources.push_back(source);
  params.spec = spec;
  absl::StatusOr<VolumeResult> r = generate_volume_mesh(front, params, no_progress());
  ASSERT_TRUE(r.ok()) << r.status();
  EXPECT_TRUE(validate_volume_mesh(r->mesh, &front).valid());
  const double near = mean_edge_near(r->mesh, {0, 0, 0}, 0.0, 0.3);
  const double far = mean_edge_near(r->mesh, {0, 0, 0}, 0.9, 2.0);
  EXPECT_GT(near, 0.0);
  EXPECT_LT(near, 0.6 * far) << "near " << near << " far " << far;
}

TEST(VolumeMesh, BadSpecIsRejectedNamingTheField) {
  const Mesh front = box_surface({0, 0, 0}, {1, 1, 1}, 0.5);
  VolumeParams params;
  SizeSpec spec;
  spec.max_size = 0.5;
  SizeSource source;
  source.points = {{0, 0, 0}};
  source.delta0 = 0.1;
  source.r1 = -1;
  source.law = PowerLaw{1.0};
  spec.sources.push_back(source);
  params.spec = spec;
  const auto r = generate_volume_mesh(front, params, no_progress());
  ASSERT_EQ(r.status().code(), absl::StatusCode::kInvalidArgument);
  EXPECT_NE(r.status().message().find("sources[0].r1"), std::string_view::npos) << r.status();
}

}  // namespace
}  // namespace afmesh
