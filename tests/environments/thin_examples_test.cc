// The thin examples (core/shapes/thin_shapes.h, examples/dome, examples/sails): the shipped
// files are the generator's output; they are valid fronts under the relaxed self-intersection
// rule and only under it; automatic detection finds the environments their tags carry.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <set>
#include <string>

#include "core/environments/detect_environments.h"
#include "core/environments/environments.h"
#include "core/geometry/closest_points.h"
#include "core/geometry/intersect.h"
#include "core/io/mesh_io.h"
#include "core/quality/validate.h"
#include "core/shapes/thin_shapes.h"
#include "core/spatial/aabb_tree.h"
#include "core/spatial/box.h"

namespace afmesh {
namespace {

std::string example_path(const std::string& relative) {
  return std::string(AFMESH_SOURCE_DIR) + "/examples/" + relative;
}

Mesh read_example(const std::string& relative) {
  absl::StatusOr<Mesh> mesh = read_mesh(example_path(relative));
  EXPECT_TRUE(mesh.ok()) << mesh.status();
  return mesh.ok() ? *std::move(mesh) : Mesh{};
}

void expect_same_front(const Mesh& shipped, const Mesh& generated) {
  ASSERT_EQ(shipped.points.size(), generated.points.size());
  ASSERT_EQ(shipped.triangles, generated.triangles);
  ASSERT_EQ(shipped.triangle_tags, generated.triangle_tags);
  for (std::size_t p = 0; p < shipped.points.size(); ++p) {
    for (int k = 0; k < 3; ++k) {
      // Bit-identical on the machine that wrote them; a libm elsewhere may differ in the last
      // bits of a sine.
      ASSERT_NEAR(shipped.points[p][k], generated.points[p][k], 1e-12) << "point " << p;
    }
  }
}

TEST(ThinExamples, ShippedDomeIsTheGeneratorsOutput) {
  expect_same_front(read_example("dome/dome.mesh"), quarter_dome_surface());
}

TEST(ThinExamples, ShippedSailsAreTheGeneratorsOutput) {
  expect_same_front(read_example("sails/sails.mesh"), sails_surface());
}

// Valid with the environments of the tags, and invalid without them only through crossings.
void expect_valid_only_with_environments(const Mesh& front) {
  ValidationParams relaxed;
  relaxed.face_environments = front.triangle_tags;
  const ValidationReport with = validate_surface(front, relaxed);
  EXPECT_TRUE(with.valid()) << with.to_string();
  for (const Check& c : with.checks) EXPECT_EQ(c.outcome, CheckOutcome::kPassed) << c.name;

  const ValidationReport without = validate_surface(front);
  EXPECT_FALSE(without.valid());
  for (const Check& c : without.checks) {
    if (c.name == check::kNoSelfIntersections) {
      EXPECT_EQ(c.outcome, CheckOutcome::kFailed);
      EXPECT_GT(c.finding_count, 100);  // the sides cross in many places
    } else {
      EXPECT_EQ(c.outcome, CheckOutcome::kPassed) << c.name;
    }
  }
}

TEST(ThinExamples, DomeIsAClosedOrientedFrontWhoseSidesCross) {
  const Mesh dome = quarter_dome_surface();
  EXPECT_EQ(dome.triangles.size(), 1264u);
  expect_valid_only_with_environments(dome);
}

TEST(ThinExamples, SailsAreAClosedOrientedFrontWhoseSidesCross) {
  const Mesh sails = sails_surface();
  EXPECT_EQ(sails.triangles.size(), 1396u);
  expect_valid_only_with_environments(sails);
}

// Issue 10, part 6: the issue's sails, about 15k sail triangles in a box about 20 chords wide,
// are a front of the same kind: closed, oriented, its sides crossing, the box three times as
// wide about the same middle.
TEST(ThinExamples, TheIssuesLargeSailsAreAClosedOrientedFrontWhoseSidesCross) {
  SailsParams params;
  params.grid_scale = 4;
  params.box_scale = 3.0;
  params.box_size = 30.0;
  const Mesh sails = sails_surface(params);
  std::int64_t on_sails = 0;
  for (const std::int32_t tag : sails.triangle_tags) on_sails += tag != 0;
  EXPECT_EQ(on_sails, 16 * 864);  // four times the cells along the chord and the height
  Box box = empty_box();
  for (const Point& x : sails.points) enclose(box, x);
  EXPECT_EQ(box.lo[0], -100.0);
  EXPECT_EQ(box.hi[0], 110.0);
  EXPECT_EQ(box.hi[2], 115.0);
  expect_valid_only_with_environments(sails);
}

// Issue 10, part 6: the whole hemispherical shell, 1/1000 of its radius thick, in a box of 4
// radii with squares of half a radius, its sides in rings of 20 and 22 steps per quarter circle
// (0.08 of the radius) with different phases: closed, oriented, its sides crossing. Both
// environments are found automatically (the box is left out).
TEST(ThinExamples, TheIssuesHemisphericalShellIsAClosedOrientedFrontWhoseSidesCross) {
  const Mesh shell = hemispherical_shell_surface();
  EXPECT_EQ(shell.triangles.size(), 7010u);
  Box box = empty_box();
  for (const Point& x : shell.points) enclose(box, x);
  EXPECT_EQ(box.lo, (Point{-2.0, -2.0, 0.0}));
  EXPECT_EQ(box.hi, (Point{2.0, 2.0, 4.0}));
  std::int64_t inside = 0, outside = 0;
  for (const std::int32_t tag : shell.triangle_tags) {
    inside += tag == kDomeInsideEnvironment;
    outside += tag == kDomeOutsideEnvironment;
  }
  EXPECT_GT(inside, 2000);  // the hemisphere and the ground disk
  EXPECT_GT(outside, inside);  // the hemisphere, finer, and the ground out to the walls
  expect_valid_only_with_environments(shell);
  absl::StatusOr<DetectedEnvironments> found = detect_environments(shell, {}, no_progress());
  ASSERT_TRUE(found.ok()) << found.status();
  EXPECT_EQ(found->stats.environment_count, 2);
}

// The sail (0 = jib, 1 = main, -1 = the box) of a tag.
int sail_of(Index tag) {
  if (tag == kJibSideA || tag == kJibSideB) return 0;
  if (tag == kMainSideA || tag == kMainSideB) return 1;
  return -1;
}

TEST(ThinExamples, TheSlotBetweenTheSailsIsOpen) {
  // Faces of different bodies neither touch nor come closer than 0.25 of their size: the slot
  // is a gap of the domain, not a thin structure.
  const Mesh sails = sails_surface();
  const AabbTree tree(triangle_boxes(sails.points, sails.triangles));
  double closest = 1e300;
  for (Index t = 0; t < static_cast<Index>(sails.triangles.size()); ++t) {
    if (sail_of(sails.triangle_tags[t]) != 0) continue;
    Box box = triangle_box(sails.points, sails.triangles[t]);
    for (int k = 0; k < 3; ++k) box.lo[k] -= 3.0, box.hi[k] += 3.0;
    for (const Index u : tree.overlapping(box)) {
      if (sail_of(sails.triangle_tags[u]) == 0) continue;
      const Triangle& a = sails.triangles[t];
      const Triangle& b = sails.triangles[u];
      EXPECT_FALSE(triangles_intersect_improperly(sails.points, a, b)) << t << " " << u;
      const ClosestPair pair = closest_points_triangles(
          sails.points[a[0]], sails.points[a[1]], sails.points[a[2]], sails.points[b[0]],
          sails.points[b[1]], sails.points[b[2]]);
      closest = std::min(closest, std::sqrt(pair.squared_distance));
    }
  }
  std::printf("closest jib face to a main or box face: %.3f m\n", closest);
  EXPECT_GT(closest, 0.5);
}

// Auto environments restricted to the faces they mark equal the tags' partition there, up to
// renumbering; every tag environment is found.
void expect_auto_matches_tags(const Mesh& front, const char* name) {
  absl::StatusOr<DetectedEnvironments> found = detect_environments(front, {}, no_progress());
  ASSERT_TRUE(found.ok()) << found.status();
  const std::vector<std::int32_t>& automatic = found->environments.face;
  std::map<std::int32_t, std::int32_t> auto_to_tag, tag_to_auto;
  std::int64_t marked = 0;
  for (std::size_t t = 0; t < automatic.size(); ++t) {
    if (automatic[t] == 0) continue;
    ++marked;
    const std::int32_t tag = front.triangle_tags[t];
    ASSERT_GT(tag, 0) << "triangle " << t << " marked " << automatic[t] << " but untagged";
    const auto [a, inserted_a] = auto_to_tag.try_emplace(automatic[t], tag);
    const auto [b, inserted_b] = tag_to_auto.try_emplace(tag, automatic[t]);
    ASSERT_EQ(a->second, tag) << "triangle " << t;
    ASSERT_EQ(b->second, automatic[t]) << "triangle " << t;
  }
  EXPECT_EQ(found->stats.environment_count, count_environments(front.triangle_tags));
  EXPECT_EQ(auto_to_tag.size(), tag_to_auto.size());
  std::printf("%s: auto %d environments (%lld of %zu faces marked; %lld crossing, %lld close "
              "pairs), tags %d environments (%lld faces tagged)\n",
              name, found->stats.environment_count, static_cast<long long>(marked),
              front.triangles.size(), static_cast<long long>(found->stats.crossing_pairs),
              static_cast<long long>(found->stats.close_pairs),
              count_environments(front.triangle_tags),
              static_cast<long long>(std::count_if(front.triangle_tags.begin(),
                                                   front.triangle_tags.end(),
                                                   [](Index t) { return t > 0; })));
}

TEST(ThinExamples, AutoFindsTheDomeTags) {
  expect_auto_matches_tags(read_example("dome/dome.mesh"), "dome");
}

TEST(ThinExamples, AutoFindsTheSailsTags) {
  expect_auto_matches_tags(read_example("sails/sails.mesh"), "sails");
}

TEST(ThinExamples, SailRimsAreRidgePoints) {
  // Each sail's rim (2 (chord + height divisions) points: 44 for the jib, 52 for the main) lies
  // on both sides: LPOCR -1, from the tags and from the automatic detection alike.
  const Mesh sails = sails_surface();
  absl::StatusOr<FrontEnvironments> tagged = environments_from_tags(sails);
  ASSERT_TRUE(tagged.ok()) << tagged.status();
  absl::StatusOr<DetectedEnvironments> automatic = detect_environments(sails, {}, no_progress());
  ASSERT_TRUE(automatic.ok()) << automatic.status();
  EXPECT_EQ(std::count(tagged->point.begin(), tagged->point.end(), -1), 96);
  EXPECT_EQ(automatic->environments.point, tagged->point);
}

TEST(ThinExamples, CrossingPlatesAreAValidFrontWithEnvironmentsAndAutoFindsThem) {
  const Mesh plates = crossing_plates_surface();
  ValidationParams relaxed;
  relaxed.face_environments = plates.triangle_tags;
  const ValidationReport report = validate_surface(plates, relaxed);
  EXPECT_TRUE(report.valid()) << report.to_string();
  EXPECT_FALSE(validate_surface(plates).valid());  // the sides of each half plate cross
  expect_auto_matches_tags(plates, "crossing plates");
  // Flat plates: the sides are 1/1000 apart but do not cross, so that front is valid without
  // environments too, and detection finds the quadrants from nearly touching faces alone.
  CrossingPlatesParams flat;
  flat.camber = 0.0;
  const Mesh flat_plates = crossing_plates_surface(flat);
  EXPECT_TRUE(validate_surface(flat_plates).valid());
  expect_auto_matches_tags(flat_plates, "crossing plates, flat");
}

// Issue 10, part 6: plates crossing at ±30° (60° between them), of one thickness with their
// rims closed by narrow strips of no environment, as a user would leave them: a valid front with
// the quadrants' environments, and detection finds them (before, a strip at 90° to a side was
// paired with the side's faces, joining the two sides through it, and auto refused).
TEST(ThinExamples, PlatesCrossingAt60DegreesWithRimStripsAreFoundByAuto) {
  for (const double camber : {0.0, 0.02}) {
    CrossingPlatesParams params;
    params.angle_deg = 60.0;
    params.rim_strips = true;
    params.camber = camber;
    const Mesh plates = crossing_plates_surface(params);
    SCOPED_TRACE(camber);
    // 4 quadrants × 2n × 2n quads; per half plate its end (2n quads) and two edges (n quads
    // each); the two caps; the box.
    const std::size_t n = 4;
    EXPECT_EQ(plates.triangles.size(), 2 * (16 * n * n + 16 * n + 2) + 6 * 2 * 36);
    ValidationParams relaxed;
    relaxed.face_environments = plates.triangle_tags;
    const ValidationReport report = validate_surface(plates, relaxed);
    EXPECT_TRUE(report.valid()) << report.to_string();
    expect_auto_matches_tags(plates, "plates at 60 degrees with rim strips");
  }
}

TEST(ThinExamples, ShippedCrossingPlatesAreTheGeneratorsOutput) {
  expect_same_front(read_example("crossing/crossing.mesh"), crossing_plates_surface());
}

TEST(ThinExamples, AutoPartitionDoesNotDependOnTriangleOrder) {
  // Reversed triangle order: the same faces group together; only the numbering follows the new
  // smallest indices (the main's side B now comes first).
  const Mesh sails = sails_surface();
  Mesh reversed = sails;
  std::reverse(reversed.triangles.begin(), reversed.triangles.end());
  std::reverse(reversed.triangle_tags.begin(), reversed.triangle_tags.end());
  absl::StatusOr<DetectedEnvironments> forward = detect_environments(sails, {}, no_progress());
  absl::StatusOr<DetectedEnvironments> backward = detect_environments(reversed, {}, no_progress());
  ASSERT_TRUE(forward.ok() && backward.ok());
  const std::size_t m = sails.triangles.size();
  std::map<std::int32_t, std::int32_t> renumber;
  for (std::size_t t = 0; t < m; ++t) {
    const std::int32_t a = forward->environments.face[t];
    const std::int32_t b = backward->environments.face[m - 1 - t];
    ASSERT_EQ(a == 0, b == 0) << "triangle " << t;
    if (a == 0) continue;
    const auto [it, inserted] = renumber.try_emplace(a, b);
    ASSERT_EQ(it->second, b) << "triangle " << t;
  }
  EXPECT_EQ(renumber.size(), 4u);
  EXPECT_EQ(renumber.at(kMainSideB), 1);  // the first environment of the reversed order
}

TEST(ThinExamples, GrowthMarksTheSailRimFaces) {
  // Faces on a sail's rim row have no thin partner of their own (their close faces on the other
  // side share their rim points); growth (step 3) adds them to their side.
  const Mesh sails = sails_surface();
  AutoEnvironmentParams no_growth;
  no_growth.grow_rings = 0;
  absl::StatusOr<DetectedEnvironments> seeds = detect_environments(sails, no_growth, no_progress());
  absl::StatusOr<DetectedEnvironments> grown = detect_environments(sails, {}, no_progress());
  ASSERT_TRUE(seeds.ok() && grown.ok());
  EXPECT_LT(seeds->stats.marked_faces, 864);
  EXPECT_EQ(grown->stats.marked_faces, 864);  // every sail face, no box face
  EXPECT_EQ(seeds->stats.crossing_pairs, grown->stats.crossing_pairs);
}

TEST(ThinExamples, DomeComponentsShareNoPoint) {
  const Mesh dome = quarter_dome_surface();
  absl::StatusOr<FrontEnvironments> tagged = environments_from_tags(dome);
  ASSERT_TRUE(tagged.ok()) << tagged.status();
  EXPECT_EQ(std::count(tagged->point.begin(), tagged->point.end(), -1), 0);
  EXPECT_GT(std::count(tagged->point.begin(), tagged->point.end(), kDomeInsideEnvironment), 0);
  EXPECT_GT(std::count(tagged->point.begin(), tagged->point.end(), kDomeOutsideEnvironment), 0);
}

}  // namespace
}  // namespace afmesh
