// --envs auto on small hand-built fronts: which pairs are thin, how sides group, the errors
// (core/environments/detect_environments.h, paper §2).
#include "core/environments/detect_environments.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <utility>
#include <vector>

#include "core/shapes/shapes.h"

namespace afmesh {
namespace {

using ::testing::ElementsAre;
using ::testing::HasSubstr;

Mesh triangles_mesh(std::vector<Point> points, std::vector<Triangle> triangles) {
  Mesh m;
  m.points = std::move(points);
  m.triangles = std::move(triangles);
  m.triangle_tags.assign(m.triangles.size(), 0);
  return m;
}

DetectedEnvironments detect(const Mesh& m, const AutoEnvironmentParams& params = {}) {
  absl::StatusOr<DetectedEnvironments> found = detect_environments(m, params, no_progress());
  EXPECT_TRUE(found.ok()) << found.status();
  return found.ok() ? *std::move(found) : DetectedEnvironments{};
}

// Two unit right triangles in the planes z = 0 and z = gap, over the same square corner.
// `facing`: the normals point towards each other's outside (a gap of the domain between two
// solids); otherwise back to back (a thin solid between them).
Mesh parallel_pair(double gap, bool facing) {
  const std::vector<Point> points = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0},
                                     {0, 0, gap}, {1, 0, gap}, {0, 1, gap}};
  // (0,1,2) has normal +z, (3,5,4) has normal -z.
  if (facing) return triangles_mesh(points, {{0, 2, 1}, {3, 4, 5}});  // -z and +z: apart
  return triangles_mesh(points, {{0, 1, 2}, {3, 5, 4}});              // +z and -z: together
}

TEST(DetectEnvironments, BackToBackCloseFacesAreTwoEnvironments) {
  const DetectedEnvironments found = detect(parallel_pair(0.01, false));
  EXPECT_THAT(found.environments.face, ElementsAre(1, 2));
  EXPECT_THAT(found.environments.point, ElementsAre(1, 1, 1, 2, 2, 2));
  EXPECT_EQ(found.stats.close_pairs, 1);
  EXPECT_EQ(found.stats.crossing_pairs, 0);
  EXPECT_EQ(found.stats.environment_count, 2);
}

TEST(DetectEnvironments, NarrowGapOfTheDomainIsNotMarked) {
  // Facing each other across air: the tets there must join both faces.
  const DetectedEnvironments found = detect(parallel_pair(0.01, true));
  EXPECT_THAT(found.environments.face, ElementsAre(0, 0));
  EXPECT_EQ(found.stats.close_pairs, 0);
}

TEST(DetectEnvironments, CloseMeansBelowTheFractionOfTheLocalSize) {
  // Mean edge length (1 + 1 + sqrt 2) / 3 = 1.138; 0.25 of it is 0.285.
  EXPECT_THAT(detect(parallel_pair(0.28, false)).environments.face, ElementsAre(1, 2));
  EXPECT_THAT(detect(parallel_pair(0.29, false)).environments.face, ElementsAre(0, 0));
  AutoEnvironmentParams tight;
  tight.closeness = 0.0;  // crossings only
  EXPECT_THAT(detect(parallel_pair(0.01, false), tight).environments.face, ElementsAre(0, 0));
}

// Regression (netgen_hinge with --envs auto): two faces near and facing each other, as in
// BackToBackCloseFacesAreTwoEnvironments, but side by side rather than over each other, seen from
// where they face: a step between two levels (the hinge's bore changing radius by 1 where
// facets 20 and 15 long end in one plane). No thin region lies between them. Moved over the
// lower face by `overlap` in x, they lie over each other and are a thin pair again.
Mesh side_by_side_pair(double gap, double overlap) {
  return triangles_mesh({{0, 0, 0}, {1, 0, 0}, {0, 1, 0},                                 // +z
                         {overlap, 0, gap}, {overlap, 1, gap}, {overlap - 1, 0, gap}},  // -z
                        {{0, 1, 2}, {3, 5, 4}});
}

TEST(DetectEnvironments, FacesThatMeetOnlyEdgeToEdgeSeenFromWhereTheyFaceAreNotThin) {
  const DetectedEnvironments apart = detect(side_by_side_pair(0.01, 0.0));
  EXPECT_THAT(apart.environments.face, ElementsAre(0, 0));
  EXPECT_EQ(apart.stats.close_pairs, 0);
  const DetectedEnvironments over = detect(side_by_side_pair(0.01, 0.1));
  EXPECT_THAT(over.environments.face, ElementsAre(1, 2));
  EXPECT_EQ(over.stats.close_pairs, 1);
}

TEST(DetectEnvironments, CrossingFacesAreMarkedWhateverTheirOrientation) {
  const Mesh m = triangles_mesh({{0, 0, 0}, {2, 0, 0}, {0, 2, 0},             // z = 0
                                 {0.5, 0.5, -1}, {0.5, 0.5, 1}, {1.5, -0.5, 0.2}},  // pierces it
                                {{0, 1, 2}, {3, 4, 5}});
  const DetectedEnvironments found = detect(m);
  EXPECT_THAT(found.environments.face, ElementsAre(1, 2));
  EXPECT_EQ(found.stats.crossing_pairs, 1);
}

// A thin body (a flat double pyramid over the regular hexagon with corners (1, 0, 0),
// (0.5, ±√3/2, 0), ...): six top faces around the apex (0.2, 0.1, t), six bottom faces around
// (-0.2, -0.1, -t), normals into the body. The two sides meet at the rim, a fold of nearly 180°.
// Every face touches the rim; a top and a bottom face that share no point lie over each other
// (seen from above) only where the apexes are off the centre: over a centred apex they would
// only touch there (the square pyramid these tests used first had no other pairs).
Mesh flat_double_pyramid(double t) {
  const double s = std::sqrt(3.0) / 2.0;
  Mesh m = triangles_mesh({{1, 0, 0}, {0.5, s, 0}, {-0.5, s, 0}, {-1, 0, 0}, {-0.5, -s, 0},
                           {0.5, -s, 0}, {0.2, 0.1, t}, {-0.2, -0.1, -t}},
                          {});
  for (Index i = 0; i < 6; ++i) m.triangles.push_back({i, 6, (i + 1) % 6});
  for (Index i = 0; i < 6; ++i) m.triangles.push_back({i, (i + 1) % 6, 7});
  m.triangle_tags.assign(12, 0);
  return m;
}

TEST(DetectEnvironments, SidesStopAtTheFoldAndTheRimIsARidge) {
  const DetectedEnvironments found = detect(flat_double_pyramid(0.01));
  EXPECT_THAT(found.environments.face, ElementsAre(1, 1, 1, 1, 1, 1, 2, 2, 2, 2, 2, 2));
  EXPECT_THAT(found.environments.point, ElementsAre(-1, -1, -1, -1, -1, -1, 1, 2));
  EXPECT_EQ(found.stats.marked_faces, 12);
}

TEST(DetectEnvironments, NumberingFollowsTheSmallestFaceIndex) {
  Mesh m = flat_double_pyramid(0.01);
  std::swap(m.triangles[0], m.triangles[11]);  // a bottom face comes first now
  const DetectedEnvironments found = detect(m);
  EXPECT_THAT(found.environments.face, ElementsAre(1, 2, 2, 2, 2, 2, 1, 1, 1, 1, 1, 2));
}

TEST(DetectEnvironments, AThickBodyHasNoEnvironments) {
  const DetectedEnvironments found = detect(flat_double_pyramid(0.8));
  EXPECT_THAT(found.environments.face, ElementsAre(0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0));
  EXPECT_EQ(found.stats.environment_count, 0);
}

TEST(DetectEnvironments, AFoldAngleAboveTheRimJoinsTheSidesAndIsReported) {
  AutoEnvironmentParams wide;
  // The rim no longer stops the grouping: its faces' normals are 178.58–178.66° apart, and
  // those of the thin pairs within 0.57° of opposite.
  wide.fold_angle_deg = 179.0;
  absl::StatusOr<DetectedEnvironments> found =
      detect_environments(flat_double_pyramid(0.01), wide, no_progress());
  ASSERT_FALSE(found.ok());
  EXPECT_EQ(found.status().code(), absl::StatusCode::kInvalidArgument);
  EXPECT_THAT(found.status().message(), HasSubstr("cannot be told apart"));
  EXPECT_THAT(found.status().message(), HasSubstr("--envs tags"));
}

TEST(DetectEnvironments, OverlapWithinOneSideIsReported) {
  // Two coplanar triangles sharing an edge and overlapping: one side folded onto itself.
  const Mesh m = triangles_mesh({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0.5, 0.5, 0}},
                                {{0, 1, 2}, {0, 1, 3}});
  absl::StatusOr<DetectedEnvironments> found = detect_environments(m, {}, no_progress());
  ASSERT_FALSE(found.ok());
  EXPECT_THAT(found.status().message(), HasSubstr("triangles 0 and 1 cross"));
}

TEST(DetectEnvironments, SolidsPassingThroughEachOtherAreNamedAsSuch) {
  // The air in a box around two thin slabs given as two closed boxes crossing at 90° (normals
  // into the slabs), not as the boundary of their union: the end faces of the shorter slab cross
  // the other's sides, joining its two sides, and the sides cross at 90°. No environments can
  // tell these apart; the error says what it is.
  Mesh front = box_surface({-3, -3, -3}, {3, 3, 3}, 1.0);
  for (const auto& [lo, hi] : {std::pair<Point, Point>{{-1, -0.01, -1}, {1, 0.01, 1}},
                               std::pair<Point, Point>{{-0.01, -1, -0.8}, {0.01, 1, 0.8}}}) {
    const Mesh slab = box_surface(lo, hi, 0.25);
    const Index offset = static_cast<Index>(front.points.size());
    front.points.insert(front.points.end(), slab.points.begin(), slab.points.end());
    for (const Triangle& t : slab.triangles) {  // reversed: the slab is a solid in the air
      front.triangles.push_back({t[0] + offset, t[2] + offset, t[1] + offset});
    }
  }
  front.triangle_tags.assign(front.triangles.size(), 0);
  absl::StatusOr<DetectedEnvironments> found = detect_environments(front, {}, no_progress());
  ASSERT_FALSE(found.ok());
  EXPECT_EQ(found.status().code(), absl::StatusCode::kInvalidArgument);
  EXPECT_THAT(found.status().message(), HasSubstr("cross at 90 degrees"));
  EXPECT_THAT(found.status().message(), HasSubstr("pass through each other"));
}

TEST(DetectEnvironments, BadInputIsNamed) {
  Mesh m = parallel_pair(0.01, false);
  m.triangles[1] = {3, 5, 5};
  EXPECT_THAT(detect_environments(m, {}, no_progress()).status().message(),
              HasSubstr("triangle 1 (3,5,5) is degenerate"));
  m = parallel_pair(0.01, false);
  m.triangles[0][2] = 17;
  EXPECT_THAT(detect_environments(m, {}, no_progress()).status().message(),
              HasSubstr("triangle 0 refers to point 17"));
  AutoEnvironmentParams bad;
  bad.closeness = -1;
  EXPECT_EQ(detect_environments(parallel_pair(0.01, false), bad, no_progress()).status().code(),
            absl::StatusCode::kInvalidArgument);
}

class CancelAtOnce : public Progress {
 public:
  bool cancelled() const override { return true; }
};

TEST(DetectEnvironments, Cancels) {
  CancelAtOnce cancel;
  EXPECT_EQ(detect_environments(flat_double_pyramid(0.01), {}, cancel).status().code(),
            absl::StatusCode::kCancelled);
}

}  // namespace
}  // namespace afmesh
