// Tests of validate_volume_mesh: good meshes pass every check, and each deliberately broken
// mesh fails the right check with the right elements named.
#include <gtest/gtest.h>

#include <algorithm>
#include <limits>
#include <utility>

#include "core/quality/mesh_topology.h"
#include "core/quality/validate.h"
#include "tests/quality/report_helpers.h"
#include "tests/quality/test_meshes.h"

namespace afmesh {
namespace {

using testing::check_of;
using testing::contains;
using testing::expect_all_passed;
using testing::findings_mentioning;
using testing::has_finding_with_tets;
using testing::has_finding_with_triangles;
using testing::outcome_of;

TEST(ValidateVolume, FiveTetCubeWithItsBoundaryIsValid) {
  const Mesh boundary = testing::five_tet_cube_boundary();
  const ValidationReport report = validate_volume_mesh(testing::five_tet_cube(), &boundary);
  expect_all_passed(report);
  EXPECT_NE(check_of(report, check::kBoundaryMatch).summary.find("matched by index"),
            std::string::npos);
}

TEST(ValidateVolume, SixTetCubeWithItsBoundaryIsValid) {
  const Mesh boundary = testing::six_tet_cube_boundary();
  expect_all_passed(validate_volume_mesh(testing::six_tet_cube(), &boundary));
}

TEST(ValidateVolume, TwoTetMeshIsValidWithoutBoundary) {
  const ValidationReport report = validate_volume_mesh(testing::two_tet_mesh());
  expect_all_passed(report, {check::kBoundaryMatch});
}

TEST(ValidateVolume, EmptyMeshIsValid) {
  expect_all_passed(validate_volume_mesh(Mesh{}), {check::kBoundaryMatch});
}

TEST(ValidateVolume, BoundaryWithOtherPointNumberingMatchesByCoordinates) {
  // Boundary points in reverse order (point i of the boundary is cube point 7 - i).
  Mesh boundary = testing::five_tet_cube_boundary();
  const std::vector<Point> cube = boundary.points;
  for (Index i = 0; i < 8; ++i) boundary.points[i] = cube[7 - i];
  for (Triangle& t : boundary.triangles) {
    for (Index& v : t) v = 7 - v;
  }
  const ValidationReport report = validate_volume_mesh(testing::five_tet_cube(), &boundary);
  expect_all_passed(report);
  EXPECT_NE(check_of(report, check::kBoundaryMatch).summary.find("exact coordinates"),
            std::string::npos);
}

TEST(ValidateVolume, NegativeZeroCoordinatesMatchPositiveZero) {
  Mesh boundary = testing::five_tet_cube_boundary();
  boundary.points.push_back({-0.0, -0.0, -0.0});  // forces coordinate matching
  for (Triangle& t : boundary.triangles) {
    for (Index& v : t) v = v == 0 ? 8 : v;
  }
  const ValidationReport report = validate_volume_mesh(testing::five_tet_cube(), &boundary);
  EXPECT_EQ(outcome_of(report, check::kBoundaryMatch), CheckOutcome::kPassed)
      << report.to_string();
}

TEST(ValidateVolume, InvertedTetIsNamed) {
  Mesh mesh = testing::five_tet_cube();
  std::swap(mesh.tets[2][0], mesh.tets[2][1]);
  const ValidationReport report = validate_volume_mesh(mesh);
  EXPECT_FALSE(report.valid());
  const Check volumes = check_of(report, check::kPositiveVolumes);
  EXPECT_EQ(volumes.outcome, CheckOutcome::kFailed);
  ASSERT_EQ(volumes.finding_count, 1);
  EXPECT_EQ(volumes.findings[0].tets, std::vector<Index>{2});
  EXPECT_EQ(volumes.findings[0].message, "tet 2 has non-positive volume (orient3d = -1)");
}

TEST(ValidateVolume, FlatTetIsNamedWithZeroOrientation) {
  const Mesh mesh = testing::tet_mesh({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}},
                                      {{0, 1, 2, 3}});
  const Check volumes = check_of(validate_volume_mesh(mesh), check::kPositiveVolumes);
  ASSERT_EQ(volumes.finding_count, 1);
  EXPECT_EQ(volumes.findings[0].message, "tet 0 has non-positive volume (orient3d = 0)");
}

TEST(ValidateVolume, TetWithRepeatedPointIsNamed) {
  Mesh mesh = testing::five_tet_cube();
  mesh.tets.push_back({0, 1, 1, 2});
  mesh.tet_tags.push_back(0);
  const Check volumes = check_of(validate_volume_mesh(mesh), check::kPositiveVolumes);
  ASSERT_EQ(volumes.finding_count, 1);
  EXPECT_EQ(volumes.findings[0].tets, std::vector<Index>{5});
  EXPECT_EQ(findings_mentioning(volumes, "repeats a point"), 1);
}

// Removing corner tet 0 of the five-tet cube exposes the central tet's face (1,4,2) and leaves
// the corner's three boundary triangles (0, 2 and 4) without a tet.
TEST(ValidateVolume, MissingTetGivesBoundaryAndVolumeMismatch) {
  Mesh mesh = testing::five_tet_cube();
  mesh.tets.erase(mesh.tets.begin());
  mesh.tet_tags.pop_back();
  const Mesh boundary = testing::five_tet_cube_boundary();
  const ValidationReport report = validate_volume_mesh(mesh, &boundary);
  EXPECT_FALSE(report.valid());

  const Check match = check_of(report, check::kBoundaryMatch);
  EXPECT_EQ(match.outcome, CheckOutcome::kFailed);
  ASSERT_EQ(match.finding_count, 4);
  EXPECT_TRUE(has_finding_with_triangles(match, {0}));
  EXPECT_TRUE(has_finding_with_triangles(match, {2}));
  EXPECT_TRUE(has_finding_with_triangles(match, {4}));
  EXPECT_EQ(findings_mentioning(match, "is not a boundary face of the tets"), 3);
  EXPECT_EQ(match.findings[3].message,
            "face (1,4,2) of tet 3 is on the tets' boundary but not in the boundary mesh");

  const Check volume = check_of(report, check::kVolumeBalance);
  EXPECT_EQ(volume.outcome, CheckOutcome::kFailed);
  EXPECT_EQ(volume.finding_count, 1);
  // The remaining tets still form a closed, well-shared complex.
  EXPECT_EQ(outcome_of(report, check::kFaceSharing), CheckOutcome::kPassed);
  EXPECT_EQ(outcome_of(report, check::kBoundarySurface), CheckOutcome::kPassed);
}

TEST(ValidateVolume, DuplicatedTetIsNamed) {
  Mesh mesh = testing::five_tet_cube();
  mesh.tets.push_back(mesh.tets[1]);
  mesh.tet_tags.push_back(0);
  const ValidationReport report = validate_volume_mesh(mesh);
  EXPECT_FALSE(report.valid());
  const Check sharing = check_of(report, check::kFaceSharing);
  // Corner tet 1 has three boundary faces, now in tets 1 and 5 alike, and one face shared with
  // the central tet 4, now in three tets.
  ASSERT_EQ(sharing.finding_count, 4);
  EXPECT_EQ(findings_mentioning(sharing, "of tets 1 and 5 with the same orientation"), 3);
  EXPECT_TRUE(has_finding_with_tets(sharing, {1, 4, 5}));
  EXPECT_EQ(findings_mentioning(sharing, "shared by tets 1, 4 and 5"), 1);
}

TEST(ValidateVolume, FaceOfTwoTetsOnTheSameSideIsNamed) {
  const Mesh mesh = testing::tet_mesh({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {0.2, 0.2, 2}},
                                      {{0, 1, 2, 3}, {0, 1, 2, 4}});
  const Check sharing = check_of(validate_volume_mesh(mesh), check::kFaceSharing);
  ASSERT_EQ(sharing.finding_count, 1);
  EXPECT_EQ(sharing.findings[0].message, "face (0,1,2) of tets 0 and 1 with the same orientation");
  EXPECT_EQ(sharing.findings[0].points, (std::vector<Index>{0, 1, 2}));
}

// The six-tet cube cuts faces z=0, y=0 and x=0 along the other diagonal than the five-tet cube:
// six boundary triangles are missing and six tet faces extra; the volumes still agree.
TEST(ValidateVolume, NonMatchingBoundaryListsMissingAndExtraFaces) {
  const Mesh boundary = testing::five_tet_cube_boundary();
  const ValidationReport report = validate_volume_mesh(testing::six_tet_cube(), &boundary);
  EXPECT_FALSE(report.valid());
  const Check match = check_of(report, check::kBoundaryMatch);
  ASSERT_EQ(match.finding_count, 12);
  for (Index t = 0; t < 6; ++t) EXPECT_TRUE(has_finding_with_triangles(match, {t})) << t;
  EXPECT_EQ(findings_mentioning(match, "is not a boundary face of the tets"), 6);
  EXPECT_EQ(findings_mentioning(match, "is on the tets' boundary but not in the boundary mesh"),
            6);
  EXPECT_EQ(findings_mentioning(match, "opposite orientation"), 0);
  EXPECT_EQ(outcome_of(report, check::kVolumeBalance), CheckOutcome::kPassed);
}

TEST(ValidateVolume, FlippedBoundaryTriangleIsNamedWithItsTet) {
  Mesh boundary = testing::five_tet_cube_boundary();
  std::swap(boundary.triangles[7][1], boundary.triangles[7][2]);  // (4,7,6) -> (4,6,7)
  const ValidationReport report = validate_volume_mesh(testing::five_tet_cube(), &boundary);
  const Check match = check_of(report, check::kBoundaryMatch);
  ASSERT_EQ(match.finding_count, 1);
  EXPECT_EQ(match.findings[0].triangles, std::vector<Index>{7});
  EXPECT_EQ(match.findings[0].tets, std::vector<Index>{3});  // corner tet at 6
  EXPECT_EQ(findings_mentioning(match, "only with the opposite orientation"), 1);
}

TEST(ValidateVolume, BoundaryPointWithoutVolumeCounterpartIsNamed) {
  Mesh boundary = testing::five_tet_cube_boundary();
  boundary.points[3] = {1, 1, 0.5};
  const Check match =
      check_of(validate_volume_mesh(testing::five_tet_cube(), &boundary), check::kBoundaryMatch);
  // Triangles 1, 9 and 10 use point 3; the tets' three faces at point 3 are then extra.
  ASSERT_EQ(match.finding_count, 6);
  EXPECT_EQ(findings_mentioning(match, "boundary point 3 (1, 1, 0.5) is not a point"), 3);
  for (Index t : {1, 9, 10}) EXPECT_TRUE(has_finding_with_triangles(match, {t})) << t;
}

TEST(ValidateVolume, BrokenBoundaryMeshFailsTheMatch) {
  Mesh boundary = testing::five_tet_cube_boundary();
  boundary.triangles[4][1] = 99;
  const ValidationReport report = validate_volume_mesh(testing::five_tet_cube(), &boundary);
  EXPECT_FALSE(report.valid());
  const Check match = check_of(report, check::kBoundaryMatch);
  EXPECT_EQ(match.outcome, CheckOutcome::kFailed);
  EXPECT_TRUE(has_finding_with_triangles(match, {4}));
  EXPECT_EQ(outcome_of(report, check::kVolumeBalance), CheckOutcome::kNotRun);
}

TEST(ValidateVolume, TetsTouchingAtOneVertexGiveNonManifoldBoundaryVertex) {
  const Mesh mesh = testing::tet_mesh(
      {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {2, 0, 0}, {1, 1, 0}, {1, 0, 1}},
      {{0, 1, 2, 3}, {1, 4, 5, 6}});
  const ValidationReport report = validate_volume_mesh(mesh);
  const Check surface = check_of(report, check::kBoundarySurface);
  EXPECT_EQ(surface.outcome, CheckOutcome::kFailed);
  ASSERT_EQ(surface.finding_count, 1);
  EXPECT_EQ(surface.findings[0].points, std::vector<Index>{1});
  EXPECT_EQ(surface.findings[0].tets, (std::vector<Index>{0, 1}));
  EXPECT_EQ(outcome_of(report, check::kFaceSharing), CheckOutcome::kPassed);
}

TEST(ValidateVolume, TetsSharingOnlyAnEdgeGiveNonManifoldBoundaryEdge) {
  const Mesh mesh = testing::tet_mesh(
      {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {0, -1, 0}, {0, 0, -1}},
      {{0, 1, 2, 3}, {0, 1, 4, 5}});
  const Check surface = check_of(validate_volume_mesh(mesh), check::kBoundarySurface);
  EXPECT_EQ(surface.outcome, CheckOutcome::kFailed);
  EXPECT_EQ(findings_mentioning(surface, "boundary edge (0,1) is used by 4 boundary faces"), 1);
}

TEST(ValidateVolume, OutOfRangeIndexIsNamedAndStopsTheOtherChecks) {
  Mesh mesh = testing::five_tet_cube();
  mesh.tets[2][3] = 99;
  const ValidationReport report = validate_volume_mesh(mesh);
  EXPECT_FALSE(report.valid());
  const Check indices = check_of(report, check::kIndices);
  ASSERT_EQ(indices.finding_count, 1);
  EXPECT_EQ(indices.findings[0].message, "tet 2 has point index 99 outside [0, 8)");
  for (const Check& c : report.checks) {
    if (c.name != check::kIndices) {
      EXPECT_EQ(c.outcome, CheckOutcome::kNotRun) << c.name;
    }
  }
}

TEST(ValidateVolume, TagCountMismatchFailsIndicesButOtherChecksRun) {
  Mesh mesh = testing::five_tet_cube();
  mesh.tet_tags.pop_back();
  const ValidationReport report = validate_volume_mesh(mesh);
  EXPECT_FALSE(report.valid());
  EXPECT_EQ(check_of(report, check::kIndices).findings[0].message,
            "tet_tags has 4 entries for 5 tets");
  EXPECT_EQ(outcome_of(report, check::kPositiveVolumes), CheckOutcome::kPassed);
}

TEST(ValidateVolume, NonFiniteCoordinateIsNamedAndSkipsGeometricChecks) {
  Mesh mesh = testing::five_tet_cube();
  mesh.points[5][1] = std::numeric_limits<double>::quiet_NaN();
  const ValidationReport report = validate_volume_mesh(mesh);
  EXPECT_FALSE(report.valid());
  const Check finite = check_of(report, check::kFiniteCoordinates);
  ASSERT_EQ(finite.finding_count, 1);
  EXPECT_EQ(finite.findings[0].points, std::vector<Index>{5});
  EXPECT_EQ(outcome_of(report, check::kPositiveVolumes), CheckOutcome::kNotRun);
  EXPECT_EQ(outcome_of(report, check::kVolumeBalance), CheckOutcome::kNotRun);
  EXPECT_EQ(outcome_of(report, check::kFaceSharing), CheckOutcome::kPassed);
}

TEST(ValidateVolume, UnusedPointIsAWarningOnly) {
  Mesh mesh = testing::five_tet_cube();
  mesh.points.push_back({5, 5, 5});
  const ValidationReport report = validate_volume_mesh(mesh);
  EXPECT_TRUE(report.valid()) << report.to_string();
  const Check unused = check_of(report, check::kUnusedPoints);
  EXPECT_EQ(unused.outcome, CheckOutcome::kWarning);
  ASSERT_EQ(unused.finding_count, 1);
  EXPECT_EQ(unused.findings[0].message, "point 8 is not used by any tet");
}

TEST(ValidateVolume, FindingsBeyondTheLimitAreCountedAndAnnounced) {
  Mesh mesh;
  for (int i = 0; i < 30; ++i) {
    const double x = 2.0 * i;
    const Index base = static_cast<Index>(mesh.points.size());
    mesh.points.insert(mesh.points.end(), {{x, 0, 0}, {x + 1, 0, 0}, {x, 1, 0}, {x, 0, 1}});
    mesh.tets.push_back({base, base + 2, base + 1, base + 3});  // inverted
    mesh.tet_tags.push_back(0);
  }
  const ValidationReport report = validate_volume_mesh(mesh);
  const Check volumes = check_of(report, check::kPositiveVolumes);
  EXPECT_EQ(volumes.finding_count, 30);
  ASSERT_EQ(volumes.findings.size(), 20u);
  EXPECT_EQ(volumes.findings.front().tets, std::vector<Index>{0});
  EXPECT_EQ(volumes.findings.back().tets, std::vector<Index>{19});
  EXPECT_NE(volumes.summary.find("and 10 more"), std::string::npos) << volumes.summary;
  EXPECT_NE(report.to_string().find("... and 10 more"), std::string::npos);
}

// A grid of 4^3 cubes with scrambled point and tet numbers: many tets per vertex, neighbours far
// apart in the arrays.
TEST(ValidateVolume, ScrambledCubeGridWithItsBoundaryIsValid) {
  const Mesh grid = testing::cube_grid(4);
  const Mesh boundary = testing::boundary_by_brute_force(grid);
  ASSERT_EQ(boundary.triangles.size(), 6u * 4 * 4 * 2);
  const ValidationReport report = validate_volume_mesh(grid, &boundary);
  expect_all_passed(report);
  EXPECT_EQ(check_of(report, check::kFaceSharing).summary,
            "672 interior faces each shared by two tets with opposite orientations, 192 boundary "
            "faces");
  EXPECT_NE(check_of(report, check::kBoundaryMatch).summary.find("matched by index"),
            std::string::npos);
}

TEST(ValidateVolume, TriangleMissingFromTheBoundaryMeshLeavesAnExtraTetFace) {
  const Mesh grid = testing::cube_grid(3);
  Mesh boundary = testing::boundary_by_brute_force(grid);
  const Triangle dropped = boundary.triangles[40];
  boundary.triangles.erase(boundary.triangles.begin() + 40);
  boundary.triangle_tags.pop_back();
  const ValidationReport report = validate_volume_mesh(grid, &boundary);
  EXPECT_FALSE(report.valid());
  const Check match = check_of(report, check::kBoundaryMatch);
  ASSERT_EQ(match.finding_count, 1);
  EXPECT_EQ(findings_mentioning(match, "is on the tets' boundary but not in the boundary mesh"),
            1);
  const Triangle named = canonical_rotation(dropped);
  EXPECT_EQ(match.findings[0].points, std::vector<Index>(named.begin(), named.end()));
  ASSERT_EQ(match.findings[0].tets.size(), 1u);
  const Tet& owner = grid.tets[match.findings[0].tets[0]];
  for (Index v : dropped) EXPECT_NE(std::find(owner.begin(), owner.end(), v), owner.end());
}

TEST(ValidateVolume, DuplicatedBoundaryTriangleIsCountedWithMultiplicity) {
  const Mesh grid = testing::cube_grid(3);
  Mesh boundary = testing::boundary_by_brute_force(grid);
  boundary.triangles.push_back(boundary.triangles[17]);
  boundary.triangle_tags.push_back(0);
  const ValidationReport report = validate_volume_mesh(grid, &boundary);
  EXPECT_FALSE(report.valid());
  const Check match = check_of(report, check::kBoundaryMatch);
  ASSERT_EQ(match.finding_count, 1);
  EXPECT_EQ(findings_mentioning(match, "is not a boundary face of the tets"), 1);
  // Either copy may be the one left over; both are the same triangle.
  ASSERT_EQ(match.findings[0].triangles.size(), 1u);
  const Index left = match.findings[0].triangles[0];
  EXPECT_TRUE(left == 17 || left == static_cast<Index>(boundary.triangles.size()) - 1) << left;
  EXPECT_EQ(outcome_of(report, check::kVolumeBalance), CheckOutcome::kFailed);
}

// The centre cube of a 3^3 grid left out: the tets' boundary has a second, inner component that
// the outer boundary mesh does not have.
TEST(ValidateVolume, CavityIsAnExtraInnerBoundary) {
  const Mesh outer = testing::boundary_by_brute_force(testing::cube_grid(3));
  const Mesh holed = testing::cube_grid(3, {1, 1, 1});
  ASSERT_EQ(holed.points, outer.points);
  const ValidationReport report = validate_volume_mesh(holed, &outer);
  EXPECT_FALSE(report.valid());
  EXPECT_EQ(outcome_of(report, check::kFaceSharing), CheckOutcome::kPassed);
  EXPECT_EQ(outcome_of(report, check::kBoundarySurface), CheckOutcome::kPassed);
  const Check match = check_of(report, check::kBoundaryMatch);
  EXPECT_EQ(match.finding_count, 12);
  EXPECT_EQ(findings_mentioning(match, "is on the tets' boundary but not in the boundary mesh"),
            12);
  for (const Finding& f : match.findings) {
    for (Index v : f.points) {
      for (int k = 0; k < 3; ++k) {
        EXPECT_TRUE(holed.points[v][k] == 1.0 || holed.points[v][k] == 2.0) << f.message;
      }
    }
  }
  const Check volume = check_of(report, check::kVolumeBalance);
  EXPECT_EQ(volume.outcome, CheckOutcome::kFailed);
  EXPECT_EQ(volume.finding_count, 1);
}

TEST(ValidateVolume, DuplicatedTetInAScrambledGridIsNamed) {
  Mesh grid = testing::cube_grid(3);
  grid.tets.push_back(grid.tets[100]);
  grid.tet_tags.push_back(0);
  const Check sharing = check_of(validate_volume_mesh(grid), check::kFaceSharing);
  EXPECT_EQ(sharing.finding_count, 4);  // each face of tet 100 now has one use too many
  for (const Finding& f : sharing.findings) {
    EXPECT_NE(std::find(f.tets.begin(), f.tets.end(), 100), f.tets.end()) << f.message;
    EXPECT_EQ(f.tets.back(), static_cast<Index>(grid.tets.size()) - 1) << f.message;
  }
}

TEST(ValidateVolume, ReportIsDeterministic) {
  const Mesh boundary = testing::five_tet_cube_boundary();
  const Mesh mesh = testing::six_tet_cube();
  EXPECT_EQ(validate_volume_mesh(mesh, &boundary).to_string(),
            validate_volume_mesh(mesh, &boundary).to_string());
}

}  // namespace
}  // namespace afmesh
