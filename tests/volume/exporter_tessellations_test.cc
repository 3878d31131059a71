// Closed surfaces as exporters tessellate primitives (issue 10, part 1: inputs nobody tuned the
// front to): latitude-longitude spheres, whose bands are quads of four coplanar points split in
// two and whose poles are fans of needles, and cylinders with fanned caps. Every STL writer of a
// sphere makes the first; libcgal-demo's sphere966.stl is one (44 around, 21 rings).
#include <cmath>
#include <numbers>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "core/io/mesh_io.h"
#include "core/mesh/mesh.h"
#include "core/quality/measures.h"
#include "core/quality/validate_common.h"
#include "gtest/gtest.h"
#include "tests/surface/surface_test_shapes.h"
#include "tests/volume/mesh_and_check.h"

namespace afmesh {
namespace {

// A closed cylinder of radius 1 and height `height` as bench/sweep/make_exporter_shapes.py writes
// it: the top centre, then `layers` + 1 circles of `around` points from the top down, the top a
// fan to its centre, the side quads split on the diagonal from a point to the next one a layer
// down, the bottom a fan to its centre (the last point).
Mesh fanned_cylinder(int around, int layers, double height) {
  Mesh mesh;
  mesh.points.push_back({0, 0, height});
  for (int k = 0; k <= layers; ++k) {
    const double z = height * (1.0 - static_cast<double>(k) / layers);
    for (int j = 0; j < around; ++j) {
      const double phi = 2.0 * std::numbers::pi * j / around;
      mesh.points.push_back({std::cos(phi), std::sin(phi), z});
    }
  }
  const auto bottom = static_cast<Index>(mesh.points.size());
  mesh.points.push_back({0, 0, 0});
  const auto ring = [&](int k, int j) { return static_cast<Index>(1 + k * around + j % around); };
  for (int j = 0; j < around; ++j) mesh.triangles.push_back({0, ring(0, j), ring(0, j + 1)});
  for (int k = 0; k < layers; ++k)
    for (int j = 0; j < around; ++j) {
      const Index a = ring(k, j), b = ring(k + 1, j), c = ring(k + 1, j + 1), d = ring(k, j + 1);
      mesh.triangles.push_back({a, b, c});
      mesh.triangles.push_back({a, c, d});
    }
  for (int j = 0; j < around; ++j)
    mesh.triangles.push_back({bottom, ring(layers, j + 1), ring(layers, j)});
  mesh.triangle_tags.assign(mesh.triangles.size(), 0);
  return mesh;
}

// Regression for issue 10: latitude-longitude spheres of radius 10 stopped at their mean edge,
// with and without reruns ("the front stopped closing: the elements hold all but 0.00036 of the
// enclosed volume, but the last front faces ... only make ever smaller elements", libcgal-demo's
// sphere966.stl, 0.6 s). The front left flat pockets: where an element's face took the other
// diagonal of a band's quad, whose four points are coplanar but for rounding, the two input
// triangles and the two faces over them enclose almost nothing, and only the element on all four
// points closes that (wedge_apex_candidates at kFlatWedgeAngleDeg, for a face that has failed
// once). 4 pockets of 4 to 276 faces were left at the first stop of 44 x 21, 1,165 of the
// 1,272 faces left on input points.
TEST(Regression, Issue10LatitudeLongitudeSpheresMeshAtTheirMeanEdge) {
  for (const auto& [around, rings] :
       std::vector<std::pair<int, int>>{{44, 21}, {60, 29}, {64, 15}, {40, 39}, {32, 63}}) {
    SCOPED_TRACE(::testing::Message() << around << " around, " << rings << " rings");
    const Mesh front = testing::uv_sphere({0, 0, 0}, 10.0, around, rings);
    VolumeParams params;
    params.size = mean_edge_length(front);
    params.local_refinements = 0;  // the first run closes
    mesh_and_check(front, params);
  }
}

// Regression for issue 10: where the poles' needles are under 5 degrees (sliver fronts) the
// spheres stopped at their mean edge on their first run (80 around and 19 rings after 3 reruns,
// with tets of 0.00 degrees; 100 and 49 not at all), and so did a cylinder whose caps are fans
// of 96 needles of 3.75 degrees (not after 8 reruns either): each needle took the far corner of
// the next as a cap does (neighbour_apex_candidates), and the flat elements folded the fan into
// faces reaching across it. A needle now takes points as other faces do.
TEST(Regression, Issue10FansOfNeedlesMeshAtTheirMeanEdge) {
  std::vector<Mesh> fronts = {testing::uv_sphere({0, 0, 0}, 10.0, 72, 19),
                              testing::uv_sphere({0, 0, 0}, 10.0, 96, 23),
                              testing::closed_cylinder(1.0, 1.0, 96, 4)};
  for (const Mesh& front : fronts) {
    SCOPED_TRACE(::testing::Message() << front.triangles.size() << " triangles");
    VolumeParams params;
    params.size = mean_edge_length(front);
    params.local_refinements = 0;  // the first run closes
    const VolumeResult result = mesh_and_check(front, params);
    // Elements of about the size asked, not a few flat ones folded across the fans: at least
    // half as many tets as regular tets of edge h fill the enclosed volume.
    const double enclosed = enclosed_volume(front.points, front.triangles, nullptr);
    const double h = params.size;
    const double regular = h * h * h / (6 * std::sqrt(2.0));
    EXPECT_GT(static_cast<double>(result.mesh.tets.size()), 0.5 * enclosed / regular);
  }
}

// Regression for issue 10: cylinders whose caps are fans of needles stopped at and under their
// mean edge (fanned_cylinder, 40-128 round, 2-6 layers, heights 1 and 0.5, at 0.5, 0.7 and 1
// times their mean edge: 47 of 108 meshed through the CLI, reruns allowed). A needle 1 long
// asked for elements of 0.2 had its best point so low above it that the element on it was under
// the first rules' shape, and none of its new points was a candidate; under the third rules it
// took a point of the wall half a radius away, and the fans' elements reached from the axis
// round to the wall, leaving thin layers over the wall's facets (min_quality_for_face in
// candidates.cc). Each of these three stopped on its first run before (64 x 4 also with the
// reruns of VolumeParams::local_refinements). Since elements keep clear of front points
// (Strictness::graze) 80 x 2 closes on a rerun, the others on their first runs.
TEST(Regression, Issue10CylindersWithFannedCapsMeshUnderTheirMeanEdge) {
  for (const auto& [around, layers, share, reruns] :
       std::vector<std::tuple<int, int, double, int>>{
           {64, 4, 0.7, 0}, {80, 2, 0.7, VolumeParams{}.local_refinements}, {96, 6, 0.5, 0}}) {
    SCOPED_TRACE(::testing::Message() << around << " round, " << layers << " layers, " << share
                                      << " of the mean edge");
    const Mesh front = fanned_cylinder(around, layers, 1.0);
    VolumeParams params;
    params.size = share * mean_edge_length(front);
    params.local_refinements = reruns;
    mesh_and_check(front, params);
  }
}

// Regression for issue 10: a cylinder with fanned caps (96 round, 4 layers) written as binary
// STL (tests/data/exporter_cylinder_96_4.stl: points in float, so the points of one angle have
// the same x and y on every ring and each side quad is exactly planar) stopped with no size, also
// with 16 reruns (the sweep's exporters group). Elements across the side had left flat faces on
// chords of the wall, from a point of a ring to the next but one; between such a chord and the
// two side quads it spans lies a lens 0.002 thick round whose quads the diagonals twist (a
// Schönhardt prism), which no element on existing points fills. The front made a cap in the lens
// on three points of a ring and got stuck at it: every new point in there lies nearer the walls
// than the clearance new points keep from front faces (a share of the element size). A cap stuck
// again where the front has re-opened before now also takes new points that keep that share of
// its own height (cap_clearance_size in candidates.cc).
TEST(Regression, Issue10CylinderOfExactlyPlanarQuadsMeshesWithNoSize) {
  absl::StatusOr<Mesh> front =
      read_mesh(std::string(AFMESH_SOURCE_DIR) + "/tests/data/exporter_cylinder_96_4.stl");
  ASSERT_TRUE(front.ok()) << front.status();
  VolumeParams params;
  params.size = mean_edge_length(*front);
  params.local_refinements = 0;  // the first run closes
  mesh_and_check(*front, params);
}

// Regression for issue 10: the cylinders of fanned_cylinder, built in double precision as an
// exporter writing OBJ does (each side quad is then planar but for rounding, its diagonal a
// fold of 1e-16 either way), stopped with no size on their first runs, and 39 of the 108 runs
// of the family (above) failed through the CLI with reruns allowed: elements reaching from one
// ring point over the next to the one after left faces a sagitta (0.0016-0.005 of the radius)
// above the wall's middle point, and the lens under them only fills with slivers or not at all.
// An element is now refused, under the first four rules, where a front point outside it lies
// within a share of its size of one of its new faces (Strictness::graze, element_crosses_front's
// `gap`): 85 of those 108 runs mesh. Each of these three stopped on its first run before.
TEST(Regression, Issue10CylindersOfNearlyPlanarQuadsMeshWithNoSize) {
  for (const auto& [around, layers, height] :
       std::vector<std::tuple<int, int, double>>{{64, 6, 0.5}, {80, 6, 0.5}, {112, 4, 0.5}}) {
    SCOPED_TRACE(::testing::Message() << around << " round, " << layers << " layers, height "
                                      << height);
    const Mesh front = fanned_cylinder(around, layers, height);
    VolumeParams params;
    params.size = mean_edge_length(front);
    params.local_refinements = 0;  // the first run closes
    mesh_and_check(front, params);
  }
}

// Regression for issue 10: a latitude-longitude sphere of 64 x 31 (the sweep's exporters group
// has it as float STL) stops in the end game at its mean edge, its last faces by a pole only
// making ever smaller elements (EndGameWatch). That stop named no place, so no rerun followed,
// where every other stop is meshed again with the size halved where it stopped
// (refine_where_stuck); it now names the face it stopped at, and the sphere closes on a rerun.
TEST(Regression, Issue10EndGameStopIsMeshedAgainWhereItStopped) {
  const Mesh front = testing::uv_sphere({0, 0, 0}, 10.0, 64, 31);
  VolumeParams params;
  params.size = mean_edge_length(front);
  const VolumeResult result = mesh_and_check(front, params);
  ASSERT_FALSE(result.warnings.empty());
  EXPECT_NE(result.warnings.front().find("the front stopped closing"), std::string::npos)
      << result.warnings.front();
}

// Regression for issue 10, part 3: cylinders with fanned caps in float STL that the front fails
// on however often it meshes them again (tests/data/exporter_cylinder_128_2_h0.5.stl: 128 round,
// 2 layers, height 0.5, at its mean edge: "did not close within its budget" after 7 reruns; 21
// of the family's 108 float and 22 of its 108 double runs failed so). The volume is then filled
// from the front's points and those its last run placed (conforming_fill: their Delaunay
// tetrahedralisation, the front's triangles recovered by flips), said in a warning; the mesh is
// valid and keeps the front exactly.
TEST(Regression, Issue10CylinderTheFrontCannotCloseIsFilledFromItsPoints) {
  absl::StatusOr<Mesh> read = read_mesh(std::string(AFMESH_SOURCE_DIR) +
                                        "/tests/data/exporter_cylinder_128_2_h0.5.stl");
  ASSERT_TRUE(read.ok()) << read.status();
  const Mesh& front = *read;
  VolumeParams params;
  params.size = mean_edge_length(front);
  params.local_refinements = 0;  // the first run fails; no reruns to wait for
  const absl::StatusOr<VolumeResult> result = generate_volume_mesh(front, params, no_progress());
  ASSERT_TRUE(result.ok()) << result.status();
  ASSERT_EQ(result->warnings.size(), 1u);
  EXPECT_NE(result->warnings[0].find(kDelaunayFillWords), std::string::npos)
      << result->warnings[0];
  const ValidationReport report = validate_volume_mesh(result->mesh, &front);
  EXPECT_TRUE(report.valid()) << report.to_string();
  for (std::size_t p = 0; p < front.points.size(); ++p)
    EXPECT_EQ(result->mesh.points[p], front.points[p]) << "point " << p;
  // Points the front placed inside are used, not only the front's own.
  EXPECT_GT(result->mesh.points.size(), front.points.size());
}

}  // namespace
}  // namespace afmesh
