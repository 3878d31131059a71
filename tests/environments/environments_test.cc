// LPOCR from LFACR and LFACR from triangle tags (core/environments/environments.h, paper §2).
#include "core/environments/environments.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <vector>

namespace afmesh {
namespace {

using ::testing::ElementsAre;
using ::testing::HasSubstr;

// A flat "pillow": the square's rim points 0-3, a top apex 4 and a bottom apex 5; the four top
// faces (tags `top`) and the four bottom faces (tags `bottom`) share the rim.
Mesh pillow(Index top, Index bottom) {
  Mesh m;
  m.points = {{1, 0, 0}, {0, 1, 0}, {-1, 0, 0}, {0, -1, 0}, {0, 0, 0.01}, {0, 0, -0.01}};
  for (Index i = 0; i < 4; ++i) {
    const Index j = (i + 1) % 4;
    m.triangles.push_back({i, 4, j});  // normal -z: into the thin body
    m.triangle_tags.push_back(top);
  }
  for (Index i = 0; i < 4; ++i) {
    const Index j = (i + 1) % 4;
    m.triangles.push_back({i, j, 5});
    m.triangle_tags.push_back(bottom);
  }
  return m;
}

TEST(PointEnvironments, RidgePointsOfTwoEnvironmentsGetMinusOne) {
  const Mesh m = pillow(1, 2);
  const std::vector<std::int32_t> lpocr =
      point_environments(m.points.size(), m.triangles, m.triangle_tags);
  EXPECT_THAT(lpocr, ElementsAre(-1, -1, -1, -1, 1, 2));
}

TEST(PointEnvironments, EnvironmentZeroFacesDoNotUnmarkAPoint) {
  // Top faces in environment 3, bottom faces in none: the rim belongs to environment 3.
  const Mesh m = pillow(3, 0);
  EXPECT_THAT(point_environments(m.points.size(), m.triangles, m.triangle_tags),
              ElementsAre(3, 3, 3, 3, 3, 0));
}

TEST(PointEnvironments, SameEnvironmentOnBothSidesIsNotARidge) {
  const Mesh m = pillow(5, 5);
  EXPECT_THAT(point_environments(m.points.size(), m.triangles, m.triangle_tags),
              ElementsAre(5, 5, 5, 5, 5, 5));
}

TEST(PointEnvironments, UnusedPointsAndUnmarkedFrontsAreZero) {
  Mesh m = pillow(0, 0);
  m.points.push_back({9, 9, 9});
  EXPECT_THAT(point_environments(m.points.size(), m.triangles, m.triangle_tags),
              ElementsAre(0, 0, 0, 0, 0, 0, 0));
}

TEST(PointEnvironments, ThreeEnvironmentsAtOnePointGiveMinusOne) {
  Mesh m = pillow(1, 2);
  m.triangle_tags[0] = 7;  // face (0, 4, 1): points 0 and 1 now see 7, 1 and 2
  const std::vector<std::int32_t> lpocr =
      point_environments(m.points.size(), m.triangles, m.triangle_tags);
  EXPECT_EQ(lpocr[0], -1);
  EXPECT_EQ(lpocr[4], -1);  // the top apex sees 7 and 1
  EXPECT_EQ(lpocr[5], 2);
}

// A thin triangular prism: bottom (points 0-2) and top (3-5) in environments `bottom` and
// `top`, its three rim quads in none (the strips closing a plate's rim).
Mesh thin_prism(std::int32_t bottom, std::int32_t top) {
  Mesh m;
  m.points = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 0.001}, {1, 0, 0.001}, {0, 1, 0.001}};
  m.triangles = {{0, 2, 1}, {3, 4, 5}};
  m.triangle_tags = {bottom, top};
  for (Index i = 0; i < 3; ++i) {
    const Index j = (i + 1) % 3;
    m.triangles.push_back({i, j, j + 3});
    m.triangles.push_back({i, j + 3, i + 3});
    m.triangle_tags.insert(m.triangle_tags.end(), {0, 0});
  }
  return m;
}

TEST(PointEnvironments, FacesOfNoEnvironmentBetweenTwoEnvironmentsHaveRidgePoints) {
  // Each rim face has points of environments 1 and 2: it is where the two sides meet.
  const Mesh two = thin_prism(1, 2);
  EXPECT_THAT(point_environments(two.points.size(), two.triangles, two.triangle_tags),
              ElementsAre(-1, -1, -1, -1, -1, -1));
  // One environment on both: the rim faces touch only it.
  const Mesh one = thin_prism(4, 4);
  EXPECT_THAT(point_environments(one.points.size(), one.triangles, one.triangle_tags),
              ElementsAre(4, 4, 4, 4, 4, 4));
  // Only the bottom marked: nothing to join.
  const Mesh bottom = thin_prism(1, 0);
  EXPECT_THAT(point_environments(bottom.points.size(), bottom.triangles, bottom.triangle_tags),
              ElementsAre(1, 1, 1, 0, 0, 0));
}

TEST(EnvironmentsFromTags, FaceEnvironmentIsTheTag) {
  const Mesh m = pillow(4, 9);
  absl::StatusOr<FrontEnvironments> env = environments_from_tags(m);
  ASSERT_TRUE(env.ok()) << env.status();
  EXPECT_THAT(env->face, ElementsAre(4, 4, 4, 4, 9, 9, 9, 9));
  EXPECT_THAT(env->point, ElementsAre(-1, -1, -1, -1, 4, 9));
  EXPECT_EQ(count_environments(env->face), 2);
}

TEST(EnvironmentsFromTags, NegativeTagIsAnErrorNamingTheTriangle) {
  Mesh m = pillow(1, 2);
  m.triangle_tags[6] = -3;
  absl::StatusOr<FrontEnvironments> env = environments_from_tags(m);
  ASSERT_FALSE(env.ok());
  EXPECT_EQ(env.status().code(), absl::StatusCode::kInvalidArgument);
  EXPECT_THAT(env.status().message(), HasSubstr("triangle 6 has tag -3"));
}

TEST(EnvironmentsFromTags, NoPositiveTagIsAnError) {
  const Mesh m = pillow(0, 0);
  absl::StatusOr<FrontEnvironments> env = environments_from_tags(m);
  ASSERT_FALSE(env.ok());
  EXPECT_EQ(env.status().code(), absl::StatusCode::kInvalidArgument);
  EXPECT_THAT(env.status().message(), HasSubstr("positive tag"));
  EXPECT_FALSE(has_positive_tags(m));
  EXPECT_TRUE(has_positive_tags(pillow(0, 1)));
}

TEST(EnvironmentsFromTags, TagCountAndIndicesAreChecked) {
  Mesh m = pillow(1, 2);
  m.triangle_tags.pop_back();
  EXPECT_THAT(environments_from_tags(m).status().message(), HasSubstr("7 triangle tags for 8"));
  m = pillow(1, 2);
  m.triangles[2][1] = 6;
  EXPECT_THAT(environments_from_tags(m).status().message(), HasSubstr("triangle 2 refers to"));
}

// The filters of paper §2 as both fronts apply them.
TEST(EnvironmentFilters, PointsOfOtherPositiveEnvironmentsAreHidden) {
  const std::vector<std::int32_t> lpocr = {0, 1, 2, kSharedEnvironment};
  EXPECT_TRUE(point_visible(lpocr, 1, 0));   // a point of no environment
  EXPECT_TRUE(point_visible(lpocr, 1, 1));   // of the item's own
  EXPECT_FALSE(point_visible(lpocr, 1, 2));  // of another: §2 (a)
  EXPECT_TRUE(point_visible(lpocr, 1, 3));   // a ridge point of several
  EXPECT_FALSE(point_visible(lpocr, 0, 2));  // items of no environment do not see it either
  EXPECT_TRUE(point_visible(lpocr, 2, 7));   // new points (past the input's) are of none
}

TEST(EnvironmentFilters, ItemsSeeTheirOwnEnvironmentAndNone) {
  EXPECT_TRUE(item_visible(1, 0));
  EXPECT_TRUE(item_visible(1, 1));
  EXPECT_FALSE(item_visible(1, 2));  // §2 (b)
  EXPECT_TRUE(item_visible(0, 2));   // an item of no environment checks against all
}

TEST(EnvironmentFilters, NewItemsTakeTheLargestEnvironmentOfTheirPoints) {
  const std::vector<std::int32_t> lpocr = {0, 3, kSharedEnvironment, 1};
  EXPECT_EQ(item_environment(lpocr, Triangle{0, 1, 2}), 3);
  EXPECT_EQ(item_environment(lpocr, Triangle{0, 2, 9}), 0);
  EXPECT_EQ(item_environment(lpocr, std::array<Index, 2>{3, 9}), 1);  // a side
  EXPECT_EQ(item_environment({}, Triangle{0, 1, 2}), 0);              // no environments
}

}  // namespace
}  // namespace afmesh
