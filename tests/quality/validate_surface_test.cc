// Tests of validate_surface: closed surfaces pass, and each defect is found with the right
// elements named.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <limits>
#include <utility>

#include "absl/strings/str_format.h"
#include "core/common/progress.h"
#include "core/quality/validate.h"
#include "tests/quality/report_helpers.h"
#include "tests/quality/test_meshes.h"

namespace afmesh {
namespace {

using testing::check_of;
using testing::contains;
using testing::expect_all_passed;
using testing::findings_mentioning;
using testing::has_finding_with_triangles;
using testing::outcome_of;

// The surface of the corner tet (0,0,0), e_x, e_y, e_z, points 0..3, outward.
Mesh corner_tet_surface() {
  return testing::surface_mesh({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}},
                               {{1, 2, 3}, {0, 3, 2}, {0, 1, 3}, {0, 2, 1}});
}

// `m` with point `from` replaced by point `to` in every triangle and then removed.
Mesh weld(Mesh m, Index from, Index to) {
  for (Triangle& t : m.triangles) {
    for (Index& v : t) {
      if (v == from) v = to;
      if (v > from) --v;
    }
  }
  m.points.erase(m.points.begin() + from);
  return m;
}

TEST(ValidateSurface, OctahedronIsValid) { expect_all_passed(validate_surface(testing::octahedron())); }

TEST(ValidateSurface, CubeBoundariesAreValid) {
  expect_all_passed(validate_surface(testing::five_tet_cube_boundary()));
  expect_all_passed(validate_surface(testing::six_tet_cube_boundary()));
}

TEST(ValidateSurface, EnclosedVolumeIsReported) {
  const Check volume =
      check_of(validate_surface(testing::translated(testing::octahedron(), {1e3, -2e3, 5e2})),
               check::kPositiveEnclosedVolume);
  EXPECT_EQ(volume.outcome, CheckOutcome::kPassed);
  EXPECT_NE(volume.summary.find("1.333333333333"), std::string::npos) << volume.summary;
}

// Removing octahedron triangle 3 (3,0,4) leaves its three edges with one triangle each.
TEST(ValidateSurface, HoleIsNamedByEdgeAndTriangle) {
  Mesh surface = testing::octahedron();
  surface.triangles.erase(surface.triangles.begin() + 3);
  surface.triangle_tags.pop_back();
  const ValidationReport report = validate_surface(surface);
  EXPECT_FALSE(report.valid());
  const Check closed = check_of(report, check::kClosed);
  ASSERT_EQ(closed.finding_count, 3);
  EXPECT_EQ(closed.findings[0].message, "hole: edge (0,3) used by 1 triangle (triangle 6)");
  EXPECT_EQ(closed.findings[1].message, "hole: edge (0,4) used by 1 triangle (triangle 0)");
  EXPECT_EQ(closed.findings[2].message, "hole: edge (3,4) used by 1 triangle (triangle 2)");
  EXPECT_EQ(closed.findings[0].points, (std::vector<Index>{0, 3}));
  EXPECT_EQ(outcome_of(report, check::kManifoldVertices), CheckOutcome::kPassed);
  EXPECT_EQ(outcome_of(report, check::kPositiveEnclosedVolume), CheckOutcome::kNotRun);
}

TEST(ValidateSurface, FlippedTriangleIsNamedAtEachOfItsEdges) {
  Mesh surface = testing::octahedron();
  std::swap(surface.triangles[5][0], surface.triangles[5][1]);
  const ValidationReport report = validate_surface(surface);
  EXPECT_FALSE(report.valid());
  const Check orientation = check_of(report, check::kConsistentOrientation);
  ASSERT_EQ(orientation.finding_count, 3);
  for (const Finding& f : orientation.findings) {
    EXPECT_TRUE(contains(f.triangles, 5)) << f.message;
    EXPECT_EQ(f.triangles.size(), 2u);
  }
  EXPECT_EQ(orientation.findings[0].message,
            "triangles 1 and 5 traverse edge (1,2) in the same direction");
  EXPECT_EQ(outcome_of(report, check::kClosed), CheckOutcome::kPassed);
}

TEST(ValidateSurface, InwardOrientedSurfaceHasNonPositiveVolume) {
  Mesh surface = testing::octahedron();
  for (Triangle& t : surface.triangles) std::swap(t[1], t[2]);
  const ValidationReport report = validate_surface(surface);
  EXPECT_FALSE(report.valid());
  const Check volume = check_of(report, check::kPositiveEnclosedVolume);
  EXPECT_EQ(volume.outcome, CheckOutcome::kFailed);
  EXPECT_EQ(findings_mentioning(volume, "point inward"), 1);
  EXPECT_EQ(outcome_of(report, check::kConsistentOrientation), CheckOutcome::kPassed);
}

// Two tet surfaces sharing the edge (0,1): four triangles at one edge.
TEST(ValidateSurface, NonManifoldEdgeIsNamedWithAllItsTriangles) {
  const Mesh other = testing::surface_mesh(
      {{0, 0, 0}, {1, 0, 0}, {0, -1, 0}, {0, 0, -1}}, {{1, 2, 3}, {0, 3, 2}, {0, 1, 3}, {0, 2, 1}});
  Mesh surface = testing::merge(corner_tet_surface(), other);
  surface = weld(surface, 5, 1);
  surface = weld(surface, 4, 0);
  const ValidationReport report = validate_surface(surface);
  EXPECT_FALSE(report.valid());
  const Check edges = check_of(report, check::kManifoldEdges);
  ASSERT_EQ(edges.finding_count, 1);
  EXPECT_EQ(edges.findings[0].message,
            "non-manifold edge (0,1) used by 4 triangles (triangles 2, 3, 6 and 7)");
  EXPECT_EQ(outcome_of(report, check::kClosed), CheckOutcome::kPassed);
  EXPECT_EQ(outcome_of(report, check::kNoSelfIntersections), CheckOutcome::kPassed)
      << report.to_string();
}

// Two cubes [0,1]^3 and [1,2]^3 welded at the corner (1,1,1): point 7 has two fans.
TEST(ValidateSurface, SurfacesTouchingAtAVertexGiveNonManifoldVertex) {
  const Mesh a = testing::five_tet_cube_boundary();
  const Mesh b = testing::translated(testing::five_tet_cube_boundary(), {1, 1, 1});
  const Mesh surface = weld(testing::merge(a, b), 8, 7);
  const ValidationReport report = validate_surface(surface);
  EXPECT_FALSE(report.valid());
  const Check vertices = check_of(report, check::kManifoldVertices);
  ASSERT_EQ(vertices.finding_count, 1);
  EXPECT_EQ(vertices.findings[0].points, std::vector<Index>{7});
  EXPECT_EQ(vertices.findings[0].triangles,
            (std::vector<Index>{6, 7, 8, 9, 10, 11, 12, 14, 16}));
  EXPECT_EQ(findings_mentioning(vertices, "form 2 separate fans"), 1);
  for (std::string_view name : {check::kClosed, check::kManifoldEdges,
                                check::kConsistentOrientation, check::kNoSelfIntersections,
                                check::kPositiveEnclosedVolume}) {
    EXPECT_EQ(outcome_of(report, name), CheckOutcome::kPassed) << name << report.to_string();
  }
}

// The corner-tet surface with its face (0,2,1) split at the midpoint 4 of edge (0,1), closed by
// the zero-area triangle 5 (1,0,4).
TEST(ValidateSurface, CollinearTriangleIsNamed) {
  const Mesh surface = testing::surface_mesh(
      {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {0.5, 0, 0}},
      {{1, 2, 3}, {0, 3, 2}, {0, 1, 3}, {0, 2, 4}, {4, 2, 1}, {1, 0, 4}});
  const ValidationReport report = validate_surface(surface);
  EXPECT_FALSE(report.valid());
  const Check degenerate = check_of(report, check::kNonDegenerate);
  ASSERT_EQ(degenerate.finding_count, 1);
  EXPECT_EQ(degenerate.findings[0].message,
            "triangle 5 (1,0,4) is degenerate: it has collinear points");
  EXPECT_EQ(outcome_of(report, check::kClosed), CheckOutcome::kPassed) << report.to_string();
  EXPECT_EQ(outcome_of(report, check::kConsistentOrientation), CheckOutcome::kPassed);
}

TEST(ValidateSurface, TriangleRepeatingAPointIsNamed) {
  Mesh surface = testing::octahedron();
  surface.triangles.push_back({0, 0, 1});
  surface.triangle_tags.push_back(0);
  const ValidationReport report = validate_surface(surface);
  const Check degenerate = check_of(report, check::kNonDegenerate);
  ASSERT_EQ(degenerate.finding_count, 1);
  EXPECT_EQ(degenerate.findings[0].triangles, std::vector<Index>{8});
  EXPECT_EQ(findings_mentioning(degenerate, "repeats a point"), 1);
  EXPECT_EQ(outcome_of(report, check::kClosed), CheckOutcome::kPassed);
}

TEST(ValidateSurface, OverlappingCubesIntersectOnlyAcrossCubes) {
  const Mesh surface =
      testing::merge(testing::five_tet_cube_boundary(),
                     testing::translated(testing::five_tet_cube_boundary(), {0.5, 0.5, 0.5}));
  const ValidationReport report = validate_surface(surface);
  EXPECT_FALSE(report.valid());
  const Check intersections = check_of(report, check::kNoSelfIntersections);
  EXPECT_EQ(intersections.outcome, CheckOutcome::kFailed);
  EXPECT_GT(intersections.finding_count, 0);
  for (const Finding& f : intersections.findings) {
    ASSERT_EQ(f.triangles.size(), 2u);
    EXPECT_LT(f.triangles[0], 12) << f.message;
    EXPECT_GE(f.triangles[1], 12) << f.message;
  }
  EXPECT_EQ(outcome_of(report, check::kClosed), CheckOutcome::kPassed);
  EXPECT_EQ(outcome_of(report, check::kConsistentOrientation), CheckOutcome::kPassed);
}

// Cube corner 7 pulled through the bottom face to (0.5, 0.5, -0.5): the six triangles at point
// 7 (6..11) pierce the bottom triangles 0 and 1.
TEST(ValidateSurface, TrianglePokingThroughIsFound) {
  Mesh surface = testing::five_tet_cube_boundary();
  surface.points[7] = {0.5, 0.5, -0.5};
  const Check intersections = check_of(validate_surface(surface), check::kNoSelfIntersections);
  EXPECT_EQ(intersections.outcome, CheckOutcome::kFailed);
  bool pierces_bottom = false;
  for (const Finding& f : intersections.findings) {
    ASSERT_EQ(f.triangles.size(), 2u);
    const bool at_7 = std::any_of(f.triangles.begin(), f.triangles.end(),
                                  [](Index t) { return t >= 6; });
    EXPECT_TRUE(at_7) << f.message;
    pierces_bottom = pierces_bottom || f.triangles[0] <= 1;
  }
  EXPECT_TRUE(pierces_bottom);
}

// check_surface_self_intersections is validate_surface's check alone: the same findings on
// the pierced cube and on the overlapping cubes, passed on an octahedron, not run on bad input.
TEST(ValidateSurface, TheSelfIntersectionCheckAloneFindsWhatTheReportFinds) {
  Mesh pierced = testing::five_tet_cube_boundary();
  pierced.points[7] = {0.5, 0.5, -0.5};
  const Mesh overlapping =
      testing::merge(testing::five_tet_cube_boundary(),
                     testing::translated(testing::five_tet_cube_boundary(), {0.5, 0.5, 0.5}));
  for (const Mesh* surface : {static_cast<const Mesh*>(&pierced), &overlapping}) {
    const Check full = check_of(validate_surface(*surface), check::kNoSelfIntersections);
    const absl::StatusOr<Check> alone =
        check_surface_self_intersections(*surface, ValidationParams{}, no_progress());
    ASSERT_TRUE(alone.ok()) << alone.status();
    EXPECT_EQ(alone->outcome, CheckOutcome::kFailed);
    EXPECT_EQ(alone->finding_count, full.finding_count);
    ASSERT_EQ(alone->findings.size(), full.findings.size());
    for (std::size_t i = 0; i < full.findings.size(); ++i)
      EXPECT_EQ(alone->findings[i].triangles, full.findings[i].triangles);
  }
  const absl::StatusOr<Check> clean =
      check_surface_self_intersections(testing::octahedron(), ValidationParams{}, no_progress());
  ASSERT_TRUE(clean.ok());
  EXPECT_EQ(clean->outcome, CheckOutcome::kPassed);
  Mesh bad = testing::octahedron();
  bad.points[4][2] = std::numeric_limits<double>::infinity();
  EXPECT_EQ(check_surface_self_intersections(bad, ValidationParams{}, no_progress())->outcome,
            CheckOutcome::kNotRun);
  bad = testing::octahedron();
  bad.triangles[2][1] = -3;
  EXPECT_EQ(check_surface_self_intersections(bad, ValidationParams{}, no_progress())->outcome,
            CheckOutcome::kNotRun);
}

// With face_environments, the check alone allows what validate_surface allows: the two cubes
// overlap as two environments (MeshSurface's components of an assembly), not as one, and an
// environment array of the wrong length or with a negative id does not run.
TEST(ValidateSurface, TheSelfIntersectionCheckAloneReadsFaceEnvironments) {
  const Mesh cube = testing::five_tet_cube_boundary();
  const Mesh overlapping = testing::merge(cube, testing::translated(cube, {0.5, 0.5, 0.5}));
  std::vector<std::int32_t> env(overlapping.triangles.size(), 1);
  ValidationParams params;
  params.face_environments = env;
  absl::StatusOr<Check> one = check_surface_self_intersections(overlapping, params, no_progress());
  ASSERT_TRUE(one.ok()) << one.status();
  EXPECT_EQ(one->outcome, CheckOutcome::kFailed);
  std::fill(env.begin() + static_cast<std::ptrdiff_t>(cube.triangles.size()), env.end(), 2);
  const absl::StatusOr<Check> two =
      check_surface_self_intersections(overlapping, params, no_progress());
  ASSERT_TRUE(two.ok()) << two.status();
  EXPECT_EQ(two->outcome, CheckOutcome::kPassed) << two->summary;
  EXPECT_EQ(two->outcome, check_of(validate_surface(overlapping, params),
                                   check::kNoSelfIntersections).outcome);
  env[3] = -1;
  EXPECT_EQ(check_surface_self_intersections(overlapping, params, no_progress())->outcome,
            CheckOutcome::kNotRun);
  env.pop_back();
  env[3] = 1;
  params.face_environments = env;
  EXPECT_EQ(check_surface_self_intersections(overlapping, params, no_progress())->outcome,
            CheckOutcome::kNotRun);
}

// A forbidden crossing names what to tag: a face of no environment crossing one of environment
// 1 is to get its own side's environment; two faces of one environment share a side.
TEST(ValidateSurface, AForbiddenCrossingSaysWhichTriangleToTag) {
  const Mesh cube = testing::five_tet_cube_boundary();
  const Mesh overlapping = testing::merge(cube, testing::translated(cube, {0.5, 0.5, 0.5}));
  std::vector<std::int32_t> env(overlapping.triangles.size(), 1);
  std::fill(env.begin() + static_cast<std::ptrdiff_t>(cube.triangles.size()), env.end(), 0);
  ValidationParams params;
  params.face_environments = env;
  const Check crossing = check_of(validate_surface(overlapping, params),
                                  check::kNoSelfIntersections);
  ASSERT_FALSE(crossing.findings.empty());
  const Finding& first = crossing.findings.front();
  ASSERT_EQ(first.triangles.size(), 2u);
  const Index none = env[first.triangles[0]] == 0 ? first.triangles[0] : first.triangles[1];
  EXPECT_THAT(first.message,
              ::testing::HasSubstr(absl::StrFormat("triangle %d has no environment", none)));
  EXPECT_THAT(first.message, ::testing::HasSubstr(absl::StrFormat(
                                 "tag triangle %d with a positive environment other than 1",
                                 none)));
  std::fill(env.begin(), env.end(), 3);
  const Check within = check_of(validate_surface(overlapping, params),
                                check::kNoSelfIntersections);
  ASSERT_FALSE(within.findings.empty());
  EXPECT_THAT(within.findings.front().message, ::testing::HasSubstr("within environment 3"));
}

TEST(ValidateSurface, OutOfRangeIndexStopsTheOtherChecks) {
  Mesh surface = testing::octahedron();
  surface.triangles[2][1] = -3;
  const ValidationReport report = validate_surface(surface);
  EXPECT_FALSE(report.valid());
  const Check indices = check_of(report, check::kIndices);
  ASSERT_EQ(indices.finding_count, 1);
  EXPECT_EQ(indices.findings[0].message, "triangle 2 has point index -3 outside [0, 6)");
  EXPECT_EQ(indices.findings[0].triangles, std::vector<Index>{2});
  for (const Check& c : report.checks) {
    if (c.name != check::kIndices) {
      EXPECT_EQ(c.outcome, CheckOutcome::kNotRun) << c.name;
    }
  }
}

TEST(ValidateSurface, NonFiniteCoordinateSkipsGeometricChecksOnly) {
  Mesh surface = testing::octahedron();
  surface.points[4][2] = std::numeric_limits<double>::infinity();
  const ValidationReport report = validate_surface(surface);
  EXPECT_FALSE(report.valid());
  EXPECT_EQ(check_of(report, check::kFiniteCoordinates).findings[0].points,
            std::vector<Index>{4});
  EXPECT_EQ(outcome_of(report, check::kNoSelfIntersections), CheckOutcome::kNotRun);
  EXPECT_EQ(outcome_of(report, check::kPositiveEnclosedVolume), CheckOutcome::kNotRun);
  EXPECT_EQ(outcome_of(report, check::kClosed), CheckOutcome::kPassed);
}

TEST(ValidateSurface, UnusedPointIsAWarningOnly) {
  Mesh surface = testing::octahedron();
  surface.points.push_back({9, 9, 9});
  const ValidationReport report = validate_surface(surface);
  EXPECT_TRUE(report.valid()) << report.to_string();
  const Check unused = check_of(report, check::kUnusedPoints);
  EXPECT_EQ(unused.outcome, CheckOutcome::kWarning);
  ASSERT_EQ(unused.finding_count, 1);
  EXPECT_EQ(unused.findings[0].message, "point 6 is not used by any triangle");
}

TEST(ValidateSurface, FindingLimitIsAParameter) {
  Mesh surface = testing::octahedron();
  surface.triangles.resize(1);  // a single triangle: 3 open edges
  surface.triangle_tags.resize(1);
  ValidationParams params;
  params.max_findings_per_check = 2;
  const Check closed = check_of(validate_surface(surface, params), check::kClosed);
  EXPECT_EQ(closed.finding_count, 3);
  EXPECT_EQ(closed.findings.size(), 2u);
  EXPECT_NE(closed.summary.find("and 1 more"), std::string::npos) << closed.summary;
}

}  // namespace
}  // namespace afmesh
