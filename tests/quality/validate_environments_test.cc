// Validation with crossing environments (paper §2): the relaxed self-intersection rule of
// validate_surface and the environment_gap check of validate_volume_mesh.
#include <gtest/gtest.h>

#include <vector>

#include "core/quality/validate.h"
#include "tests/quality/report_helpers.h"
#include "tests/quality/test_meshes.h"

namespace afmesh {
namespace {

using testing::check_of;
using testing::findings_mentioning;
using testing::has_finding_with_tets;
using testing::outcome_of;

// Two unit cubes (12 outward triangles each), the second moved by (0.5, 0.5, 0.5): their
// surfaces cross. Triangles 0-11 are the first cube's, 12-23 the second's.
Mesh crossing_cubes() {
  return testing::merge(testing::five_tet_cube_boundary(),
                        testing::translated(testing::five_tet_cube_boundary(), {0.5, 0.5, 0.5}));
}

std::vector<std::int32_t> per_cube(std::int32_t first, std::int32_t second) {
  std::vector<std::int32_t> env(12, first);
  env.resize(24, second);
  return env;
}

ValidationReport validate_with(const Mesh& m, const std::vector<std::int32_t>& env) {
  ValidationParams params;
  params.face_environments = env;
  return validate_surface(m, params);
}

TEST(RelaxedSelfIntersection, StrictRuleRejectsCrossingSurfaces) {
  const ValidationReport report = validate_surface(crossing_cubes());
  EXPECT_EQ(outcome_of(report, check::kNoSelfIntersections), CheckOutcome::kFailed);
  EXPECT_EQ(report.find(check::kEnvironments), nullptr);  // no environments given
}

TEST(RelaxedSelfIntersection, DifferentPositiveEnvironmentsMayCross) {
  const std::vector<std::int32_t> env = per_cube(1, 2);
  const ValidationReport report = validate_with(crossing_cubes(), env);
  EXPECT_TRUE(report.valid()) << report.to_string();
  const Check c = check_of(report, check::kNoSelfIntersections);
  EXPECT_EQ(c.outcome, CheckOutcome::kPassed);
  EXPECT_NE(c.summary.find("of two different environments allowed"), std::string::npos)
      << c.summary;
  EXPECT_EQ(outcome_of(report, check::kEnvironments), CheckOutcome::kPassed);
  EXPECT_NE(check_of(report, check::kEnvironments).summary.find("2 crossing environments"),
            std::string::npos);
}

TEST(RelaxedSelfIntersection, CrossingWithinOneEnvironmentIsStillRejected) {
  const std::vector<std::int32_t> env = per_cube(3, 3);
  const ValidationReport report = validate_with(crossing_cubes(), env);
  const Check c = check_of(report, check::kNoSelfIntersections);
  EXPECT_EQ(c.outcome, CheckOutcome::kFailed);
  EXPECT_GT(findings_mentioning(c, "within environment 3"), 0) << report.to_string();
}

TEST(RelaxedSelfIntersection, CrossingAnUnmarkedFaceIsStillRejected) {
  for (const auto& env : {per_cube(0, 2), per_cube(1, 0), per_cube(0, 0)}) {
    const ValidationReport report = validate_with(crossing_cubes(), env);
    EXPECT_EQ(outcome_of(report, check::kNoSelfIntersections), CheckOutcome::kFailed);
  }
}

TEST(RelaxedSelfIntersection, OnlyTheCrossingPairsDecide) {
  // One face of the second cube moved to environment 1: its crossings with the first cube are
  // forbidden again, the others stay allowed.
  std::vector<std::int32_t> env = per_cube(1, 2);
  const Mesh m = crossing_cubes();
  const ValidationReport all_allowed = validate_with(m, env);
  ASSERT_TRUE(all_allowed.valid());
  int rejected_faces = 0;
  for (Index t = 12; t < 24; ++t) {
    env = per_cube(1, 2);
    env[t] = 1;
    const Check c = check_of(validate_with(m, env), check::kNoSelfIntersections);
    if (c.outcome == CheckOutcome::kFailed) {
      ++rejected_faces;
      for (const Finding& f : c.findings) {
        ASSERT_EQ(f.triangles.size(), 2u);
        EXPECT_EQ(f.triangles[1], t);  // pairs (first-cube face, t)
        EXPECT_LT(f.triangles[0], 12);
      }
    }
  }
  EXPECT_GT(rejected_faces, 0);
}

TEST(RelaxedSelfIntersection, MalformedEnvironmentsFailAndTheStrictRuleApplies) {
  std::vector<std::int32_t> short_env = per_cube(1, 2);
  short_env.pop_back();
  ValidationReport report = validate_with(crossing_cubes(), short_env);
  EXPECT_EQ(outcome_of(report, check::kEnvironments), CheckOutcome::kFailed);
  EXPECT_NE(check_of(report, check::kEnvironments).findings.at(0).message.find(
                "23 face environments given for 24 triangles"),
            std::string::npos);
  EXPECT_EQ(outcome_of(report, check::kNoSelfIntersections), CheckOutcome::kFailed);

  std::vector<std::int32_t> negative = per_cube(1, 2);
  negative[5] = -1;
  report = validate_with(crossing_cubes(), negative);
  const Check c = check_of(report, check::kEnvironments);
  EXPECT_EQ(c.outcome, CheckOutcome::kFailed);
  EXPECT_EQ(c.findings.at(0).triangles, std::vector<Index>{5});
}

// ----- environment_gap ----------------------------------------------------------------------

// Points: 0-2 on environment 1, 3-5 on environment 2, 6 a ridge point (-1), 7 a point of no
// environment, 8 an interior point beyond the environment array. Tets (all positive):
//   0: (0, 1, 2, 7)  environment 1 and none: fine
//   1: (0, 1, 6, 8)  environment 1, ridge, interior: fine
//   2: (0, 1, 3, 7)  joins 1 and 2 across the gap (stored as (0, 1, 7, 3), positive)
//   3: (3, 4, 5, 6)  environment 2 and ridge: fine
//   4: (6, 4, 2, 8)  joins 2 and 1 again
Mesh gap_mesh() {
  return testing::tet_mesh({{0, 0, 0}, {1, 0, 0}, {0, 1, 0},        // environment 1
                            {0, 0, 1}, {1, 0, 1}, {0, 1, 1},        // environment 2
                            {1, 1, 0.5}, {2, 2, 2}, {-1, -1, -1}},  // ridge, none, interior
                           {{0, 1, 2, 7}, {0, 1, 6, 8}, {0, 1, 3, 7}, {3, 4, 5, 6}, {6, 4, 2, 8}});
}

const std::vector<std::int32_t> kGapEnvironments = {1, 1, 1, 2, 2, 2, -1, 0};  // point 8: none

ValidationReport validate_gap(const Mesh& m, const std::vector<std::int32_t>& env,
                              bool warns_only = false) {
  ValidationParams params;
  params.point_environments = env;
  params.environment_gap_warns_only = warns_only;
  return validate_volume_mesh(m, nullptr, params);
}

TEST(EnvironmentGap, TetsAcrossTheGapAreFound) {
  const ValidationReport report = validate_gap(gap_mesh(), kGapEnvironments);
  const Check c = check_of(report, check::kEnvironmentGap);
  EXPECT_EQ(c.outcome, CheckOutcome::kFailed);
  EXPECT_EQ(c.finding_count, 2);
  EXPECT_TRUE(has_finding_with_tets(c, {2}));
  EXPECT_TRUE(has_finding_with_tets(c, {4}));
  EXPECT_EQ(findings_mentioning(c, "tet 2 (0,1,7,3) joins environment 1 (point 0) and "
                                   "environment 2 (point 3) across a thin gap"),
            1)
      << report.to_string();
  EXPECT_FALSE(report.valid());
}

TEST(EnvironmentGap, RidgePointsAndUnmarkedPointsJoinAnything) {
  Mesh m = gap_mesh();
  m.tets.erase(m.tets.begin() + 4);
  m.tets.erase(m.tets.begin() + 2);
  m.tet_tags.resize(3);
  const Check c = check_of(validate_gap(m, kGapEnvironments), check::kEnvironmentGap);
  EXPECT_EQ(c.outcome, CheckOutcome::kPassed);
  EXPECT_NE(c.summary.find("3 of 3 tets touch one"), std::string::npos) << c.summary;
}

TEST(EnvironmentGap, WarnsOnlyWhenAsked) {
  const ValidationReport report = validate_gap(gap_mesh(), kGapEnvironments, true);
  EXPECT_EQ(outcome_of(report, check::kEnvironmentGap), CheckOutcome::kWarning);
  EXPECT_EQ(check_of(report, check::kEnvironmentGap).finding_count, 2);
}

TEST(EnvironmentGap, RunsOnlyWithEnvironments) {
  EXPECT_EQ(validate_volume_mesh(gap_mesh()).find(check::kEnvironmentGap), nullptr);
}

TEST(EnvironmentGap, MalformedArraysFail) {
  std::vector<std::int32_t> too_long(10, 0);
  Check c = check_of(validate_gap(gap_mesh(), too_long), check::kEnvironmentGap);
  EXPECT_EQ(c.outcome, CheckOutcome::kFailed);
  EXPECT_EQ(findings_mentioning(c, "10 point environments given for 9 points"), 1);
  std::vector<std::int32_t> below = kGapEnvironments;
  below[3] = -2;
  c = check_of(validate_gap(gap_mesh(), below, true), check::kEnvironmentGap);
  EXPECT_EQ(c.outcome, CheckOutcome::kFailed);  // a bad array is never just a warning
  EXPECT_EQ(findings_mentioning(c, "point 3 has environment -2"), 1);
}

}  // namespace
}  // namespace afmesh
