// repair_front: fronts with flipped facets, cavities oriented like the outer wall, inward
// surfaces and repeated-point triangles are repaired; what needs guessing is left alone.
#include "core/volume/repair_front.h"

#include <algorithm>
#include <array>
#include <random>

#include "core/quality/mesh_topology.h"
#include "core/quality/validate.h"
#include "core/quality/validate_common.h"
#include "core/shapes/shapes.h"
#include "gtest/gtest.h"

namespace afmesh {
namespace {

void flip(Triangle& t) { std::swap(t[1], t[2]); }

// The two surfaces as one front: `inner`'s points follow `outer`'s.
Mesh joined(const Mesh& outer, const Mesh& inner) {
  Mesh out = outer;
  const Index offset = static_cast<Index>(outer.points.size());
  out.points.insert(out.points.end(), inner.points.begin(), inner.points.end());
  for (std::size_t t = 0; t < inner.triangles.size(); ++t) {
    Triangle v = inner.triangles[t];
    for (Index& p : v) p += offset;
    out.triangles.push_back(v);
    out.triangle_tags.push_back(inner.triangle_tags.empty() ? 0 : inner.triangle_tags[t]);
  }
  out.triangle_tags.resize(out.triangles.size(), 0);
  return out;
}

// A sphere of radius 1 with a box cavity, both oriented outward as a closed front must be: the
// cavity's triangles face into the cavity.
Mesh sphere_with_cavity() {
  Mesh cavity = box_surface({-0.3, -0.3, -0.3}, {0.3, 0.3, 0.3}, 0.15);
  for (Triangle& t : cavity.triangles) flip(t);
  return joined(sphere_surface({0, 0, 0}, 1.0, 0.25), cavity);
}

bool valid_front(const Mesh& m) { return validate_surface(m).valid(); }

TEST(RepairFront, ValidFrontIsLeftUnchanged) {
  const Mesh front = sphere_with_cavity();
  ASSERT_TRUE(valid_front(front));
  Mesh repaired = front;
  const FrontRepairReport report = repair_front(repaired);
  EXPECT_FALSE(report.changed());
  EXPECT_TRUE(report.notes().empty());
  EXPECT_EQ(report.components, 2);
  EXPECT_EQ(report.cavities, 1);
  EXPECT_EQ(repaired.triangles, front.triangles);
}

TEST(RepairFront, FlippedFacetsAreTurnedBackAndCounted) {
  const Mesh good = sphere_with_cavity();
  Mesh front = good;
  const std::vector<std::size_t> flipped = {0, 7, 8, 40, 41, 42, 100, front.triangles.size() - 1};
  for (std::size_t t : flipped) flip(front.triangles[t]);
  ASSERT_FALSE(valid_front(front));
  const FrontRepairReport report = repair_front(front);
  EXPECT_EQ(report.triangles_reoriented, static_cast<std::int64_t>(flipped.size()));
  EXPECT_EQ(report.components_turned, 0);
  EXPECT_EQ(front.triangles, good.triangles);
  ASSERT_EQ(report.notes().size(), 1u);
  EXPECT_NE(report.notes()[0].find("re-oriented 8 triangle(s)"), std::string::npos)
      << report.notes()[0];
}

TEST(RepairFront, CavityOrientedLikeTheOuterWallIsTurnedInward) {
  const Mesh good = sphere_with_cavity();
  const Mesh cavity_outward =
      joined(sphere_surface({0, 0, 0}, 1.0, 0.25),
             box_surface({-0.3, -0.3, -0.3}, {0.3, 0.3, 0.3}, 0.15));
  // The validator alone does not see it: the enclosed volume is still positive.
  Mesh front = cavity_outward;
  const FrontRepairReport report = repair_front(front);
  EXPECT_EQ(report.cavities, 1);
  EXPECT_EQ(report.components_turned, 1);
  EXPECT_EQ(report.triangles_reoriented,
            static_cast<std::int64_t>(good.triangles.size() -
                                      sphere_surface({0, 0, 0}, 1.0, 0.25).triangles.size()));
  EXPECT_EQ(front.triangles, good.triangles);
  EXPECT_TRUE(valid_front(front));
}

TEST(RepairFront, InwardSurfaceIsTurnedOutward) {
  const Mesh good = sphere_with_cavity();
  Mesh front = good;
  for (Triangle& t : front.triangles) flip(t);  // both walls face into the solid
  ASSERT_FALSE(valid_front(front));
  const FrontRepairReport report = repair_front(front);
  EXPECT_EQ(report.components_turned, 2);
  EXPECT_EQ(front.triangles, good.triangles);
}

TEST(RepairFront, RandomWindingIsMadeConsistentAndOutward) {
  const Mesh good = sphere_with_cavity();
  Mesh front = good;
  std::mt19937 random(12345);
  std::int64_t flipped = 0;
  for (Triangle& t : front.triangles) {
    if (random() % 2) {
      flip(t);
      ++flipped;
    }
  }
  const FrontRepairReport report = repair_front(front);
  EXPECT_EQ(report.triangles_reoriented, flipped);
  EXPECT_EQ(front.triangles, good.triangles);
  EXPECT_TRUE(valid_front(front));
}

// The edge neighbours repair_front gives back are those of the triangles it leaves: the slots of
// each triangle it turned swapped, and the same_way flags of the edges between a turned triangle
// and one left as it was changed (the surface mesher uses them in lieu of grouping the edges
// again). With random winding and a cavity the whole sphere: not a flag changes the other way.
TEST(RepairFront, EdgeNeighboursAreThoseOfTheRepairedTriangles) {
  Mesh front = sphere_with_cavity();
  std::mt19937 random(777);
  for (Triangle& t : front.triangles)
    if (random() % 3 == 0) flip(t);
  EdgeNeighbours neighbours;
  const FrontRepairReport report = repair_front(front, &neighbours);
  ASSERT_GT(report.triangles_reoriented, 0);
  const EdgeNeighbours expected = triangle_edge_neighbours(front.triangles);
  EXPECT_EQ(neighbours.across, expected.across);
  EXPECT_EQ(neighbours.same_way, expected.same_way);
  // A consistent front: no two neighbours traverse an edge the same way.
  for (const auto& flags : neighbours.same_way)
    EXPECT_EQ(flags, (std::array<bool, 3>{false, false, false}));

  // Skipped (an open surface): none given back.
  Mesh open = box_surface({0, 0, 0}, {1, 1, 1}, 0.5);
  open.triangles.pop_back();
  EdgeNeighbours none;
  repair_front(open, &none);
  EXPECT_TRUE(none.across.empty());
}

TEST(RepairFront, RepeatedPointTrianglesAreDroppedWithTheirTags) {
  Mesh front = box_surface({0, 0, 0}, {1, 1, 1}, 0.5);
  front.triangle_tags.assign(front.triangles.size(), 3);
  const Mesh good = front;
  front.triangles.insert(front.triangles.begin() + 2, Triangle{4, 4, 5});
  front.triangle_tags.insert(front.triangle_tags.begin() + 2, 9);
  front.triangles.push_back({1, 2, 1});
  front.triangle_tags.push_back(9);
  const FrontRepairReport report = repair_front(front);
  EXPECT_EQ(report.triangles_dropped, 2);
  EXPECT_EQ(report.triangles_reoriented, 0);
  EXPECT_EQ(front.triangles, good.triangles);
  EXPECT_EQ(front.triangle_tags, good.triangle_tags);
  EXPECT_NE(report.notes()[0].find("dropped 2 triangle(s)"), std::string::npos);
}

// occt-misc's bearing.stl has 16 triangles that repeat a point and, without them, 134 open edges:
// the triangles stay, for the validator to refuse, and the report says why they stayed.
TEST(RepairFront, RepeatedPointTrianglesStayWhenTheRestIsOpenAndTheReportSaysWhy) {
  Mesh front = box_surface({0, 0, 0}, {1, 1, 1}, 0.5);
  front.triangles.pop_back();  // three sides of it lose their neighbour
  front.triangles.push_back({4, 4, 5});
  front.triangles.push_back({1, 2, 1});
  const Mesh before = front;
  const FrontRepairReport report = repair_front(front);
  EXPECT_FALSE(report.changed());
  EXPECT_EQ(front.triangles, before.triangles);
  EXPECT_EQ(report.repeated_points_kept, 2);
  EXPECT_EQ(report.triangle_sides_unpaired, 3);
  EXPECT_EQ(report.why_repeated_points_kept(),
            "the 2 triangle(s) that repeat a point were not dropped: without them 3 triangle "
            "side(s) still have no single neighbour across them (the surface is open or "
            "non-manifold there, which a volume cannot be meshed from)");

  Mesh clean = box_surface({0, 0, 0}, {1, 1, 1}, 0.5);
  clean.triangles.pop_back();
  const FrontRepairReport open = repair_front(clean);
  EXPECT_EQ(open.repeated_points_kept, 0);
  EXPECT_EQ(open.why_repeated_points_kept(), "");
}

TEST(RepairFront, OpenSurfaceIsLeftForTheValidatorToRefuse) {
  Mesh front = box_surface({0, 0, 0}, {1, 1, 1}, 0.5);
  front.triangles.pop_back();
  flip(front.triangles[0]);
  const Mesh before = front;
  const FrontRepairReport report = repair_front(front);
  EXPECT_FALSE(report.changed());
  EXPECT_NE(report.skipped_because.find("open or non-manifold"), std::string::npos);
  EXPECT_EQ(front.triangles, before.triangles);
}

TEST(RepairFront, NestedShellsAlternate) {
  // A ball in a cavity of a ball: the outer wall faces out, the cavity in, the inner ball out.
  const Mesh outer = sphere_surface({0, 0, 0}, 2.0, 0.4);
  const Mesh cavity = sphere_surface({0, 0, 0}, 1.2, 0.3);
  const Mesh ball = box_surface({-0.4, -0.4, -0.4}, {0.4, 0.4, 0.4}, 0.2);
  Mesh front = joined(joined(outer, cavity), ball);  // all three facing out
  const FrontRepairReport report = repair_front(front);
  EXPECT_EQ(report.components, 3);
  EXPECT_EQ(report.cavities, 1);
  EXPECT_EQ(report.components_turned, 1);
  EXPECT_EQ(report.triangles_reoriented, static_cast<std::int64_t>(cavity.triangles.size()));
  EXPECT_TRUE(valid_front(front));
  const double expected = enclosed_volume(outer.points, outer.triangles, nullptr) -
                          enclosed_volume(cavity.points, cavity.triangles, nullptr) +
                          enclosed_volume(ball.points, ball.triangles, nullptr);
  EXPECT_NEAR(enclosed_volume(front.points, front.triangles, nullptr), expected, 1e-9);
}

}  // namespace
}  // namespace afmesh
