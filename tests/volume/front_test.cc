// Unit tests of the volume front's steps on hand-built fronts: the crossing-environment filters
// (paper §2) and the end-game pocket fill (F11). The front's data structures are tested in
// tests/front/front_test.cc.
#include <filesystem>
#include <vector>

#include "core/geometry/predicates.h"
#include "core/geometry/vec.h"
#include "core/io/mesh_io.h"
#include "core/shapes/shapes.h"
#include "core/sizing/size_field.h"
#include "core/volume/front_steps.h"
#include "gtest/gtest.h"

namespace afmesh {
namespace {

// Crossing environments (paper §2): two crossing sheets, A (environment 1) and B (environment
// 2). For a face of A, B's faces and points do not exist: the element above A that B crosses is
// accepted, and B's points are no candidates. Without environments the same element crosses.
TEST(CrossingEnvironments, FacesAndPointsOfAnotherEnvironmentAreIgnored) {
  Mesh input;
  input.points = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0},            // A, in z = 0
                  {-1, -1, 0.3}, {2, -1, 0.3}, {-1, 2, 0.3},  // B, above A, crossing its element
                  {0.3, 0.3, 0.4}};                           // a point of B above A
  const UniformSize size(1.0);
  for (bool with_envs : {true, false}) {
    SCOPED_TRACE(with_envs);
    volume::MesherState s(input, 1.0, size, Box{{-2, -2, -2}, {3, 3, 3}}, 0.5);
    s.point_size.assign(input.points.size(), 1.0);
    if (with_envs) s.point_env = {1, 1, 1, 2, 2, 2, 2};
    const Index a = s.front.add({0, 1, 2}, 1.0, with_envs ? 1 : 0);  // looks up (+z)
    s.front.add({3, 4, 5}, 1.0, with_envs ? 2 : 0);
    s.front.add({6, 4, 5}, 1.0, with_envs ? 2 : 0);  // puts point 6 on the front
    s.points.push_back({0.3, 0.3, 0.8});  // a new point above A, beyond B
    const Index p = static_cast<Index>(s.points.size() - 1);
    EXPECT_EQ(volume::element_crosses_front(s, a, p), !with_envs);

    const Triangle v = s.front.item(a).v;
    const double d = volume::element_size_for_face(s, v);
    volume::gather_candidates(s, a, volume::ideal_point(s, v, d), d, volume::strictness_for(5));
    bool offers_b_point = false;
    for (const volume::Candidate& c : s.candidates) offers_b_point |= c.point >= 3;
    EXPECT_EQ(offers_b_point, !with_envs);
  }
}

// The end game (F11): a pocket whose corners admit no element (Schönhardt's twisted prism, all
// three side diagonals reflex) is filled from a kernel point inside it, every element positive,
// and the front is empty after.
TEST(FillPocket, SchoenhardtPrismIsFilledFromAKernelPoint) {
  const Mesh input = schoenhardt_prism_surface();
  // No tet on the six corners fits: each candidate crosses a side or a reflex edge.
  const UniformSize size(1.0);
  volume::MesherState s(input, 1.0, size, Box{{-2, -2, -1}, {2, 2, 2}}, 0.5);
  s.point_size.assign(input.points.size(), 1.0);
  for (const Triangle& t : input.triangles) s.front.add({t[0], t[2], t[1]}, 1.0);
  for (Index f = 0; f < 8; ++f)
    for (Index p = 0; p < 6; ++p) {
      const Triangle& v = s.front.item(f).v;
      if (p == v[0] || p == v[1] || p == v[2]) continue;
      if (orient3d(s.points[v[0]], s.points[v[1]], s.points[v[2]], s.points[p]) <= 0) continue;
      EXPECT_TRUE(volume::element_crosses_front(s, f, p)) << "face " << f << " point " << p;
    }

  std::vector<Index> pocket;
  ASSERT_TRUE(volume::collect_pocket(s, 0, 256, pocket));
  EXPECT_EQ(pocket.size(), 8u);
  EXPECT_FALSE(volume::collect_pocket(s, 0, 5, pocket));  // larger than allowed

  EXPECT_EQ(volume::fill_pocket(s, 0, 256), 8);
  EXPECT_EQ(s.front.size(), 0);
  EXPECT_EQ(s.points.size(), 7u);
  double volume = 0;
  for (const Tet& t : s.tets) {
    ASSERT_GT(orient3d(s.points[t[0]], s.points[t[1]], s.points[t[2]], s.points[t[3]]), 0);
    volume += orient3d_fast(s.points[t[0]], s.points[t[1]], s.points[t[2]], s.points[t[3]]) / 6;
  }
  double enclosed = 0;
  for (const Triangle& t : input.triangles)
    enclosed += dot(input.points[t[0]], cross(input.points[t[1]], input.points[t[2]])) / 6;
  EXPECT_NEAR(volume, enclosed, 1e-12);
}

// Regression for issue 10 (the robustness sweep): OCCT's shape.stl (494 triangles) stopped
// "stuck at face (244, 232, 60) ... after re-opening its surroundings 4 times" at its mean edge.
// tests/data/shape_bent_pocket.mesh is the pocket its front left there (126 faces, reversed to
// face out; triangle 0 is that face): a slab between two coaxial cylinders, 90 long and 10-17
// thick, whose outer side is strips of one sliver pair each, so that no corner closes face 0.
// The pocket bends: no point sees it all (fill_pocket), and shrinking it by the faces its
// deepest point is lowest above (fill_part_of_pocket) leaves face 0 alone, with no point whose
// element does not cross the front. The part grown from face 0 by the faces its element crosses
// (fill_grown_part_of_pocket) has one.
TEST(Regression, Issue10BentPocketClosesTheFaceItWasStuckAt) {
  absl::StatusOr<Mesh> input = read_mesh(
      (std::filesystem::path(AFMESH_SOURCE_DIR) / "tests" / "data" / "shape_bent_pocket.mesh")
          .string());
  ASSERT_TRUE(input.ok()) << input.status();
  ASSERT_EQ(input->triangles.size(), 126u);
  const double h = 26.108;  // the mean edge of shape.stl: the size of the failed run
  const UniformSize size(h);
  Box box = empty_box();
  for (const Point& p : input->points) enclose(box, p);
  volume::MesherState s(*input, 1.0, size, box, h);
  s.point_size.assign(input->points.size(), h);
  for (const Triangle& t : input->triangles) s.front.add({t[0], t[2], t[1]}, 1.0);
  const Triangle stuck = s.front.item(0).v;
  for (Index p = 0; p < static_cast<Index>(input->points.size()); ++p) {
    if (p == stuck[0] || p == stuck[1] || p == stuck[2]) continue;
    if (orient3d(s.points[stuck[0]], s.points[stuck[1]], s.points[stuck[2]], s.points[p]) <= 0)
      continue;
    EXPECT_TRUE(volume::element_crosses_front(s, 0, p)) << "point " << p;
  }
  EXPECT_EQ(volume::fill_pocket(s, 0, 256), 0);          // no kernel point
  EXPECT_EQ(volume::fill_part_of_pocket(s, 0, 256), 0);  // the shrinking leaves face 0 alone
  ASSERT_EQ(s.points.size(), input->points.size());      // and adds nothing

  EXPECT_GT(volume::fill_grown_part_of_pocket(s, 0, 256), 0);
  EXPECT_FALSE(s.front.find(stuck).has_value());  // closed
  EXPECT_EQ(s.points.size(), input->points.size() + 1);
  EXPECT_EQ(s.point_size.size(), s.points.size());
  for (const Tet& t : s.tets)
    EXPECT_GT(orient3d(s.points[t[0]], s.points[t[1]], s.points[t[2]], s.points[t[3]]), 0);
}

// F7.3 tests the face that met the last crossing element first (element_crosses_front): the
// answer must not depend on which face that is. On the bent pocket of shape.stl (many elements
// cross, by many faces), every element (face 0, point p) gets the same answer whatever face,
// live or deleted, is remembered.
TEST(CrossingCheck, RememberedCrossingFaceChangesNoAnswer) {
  absl::StatusOr<Mesh> input = read_mesh(
      (std::filesystem::path(AFMESH_SOURCE_DIR) / "tests" / "data" / "shape_bent_pocket.mesh")
          .string());
  ASSERT_TRUE(input.ok()) << input.status();
  const UniformSize size(26.108);
  Box box = empty_box();
  for (const Point& p : input->points) enclose(box, p);
  volume::MesherState s(*input, 1.0, size, box, 26.108);
  s.point_size.assign(input->points.size(), 26.108);
  for (const Triangle& t : input->triangles) s.front.add({t[0], t[2], t[1]}, 1.0);
  const Index dead = s.front.add({0, 1, 2}, 1.0);
  s.front.remove(dead);
  const auto faces = static_cast<Index>(input->triangles.size());
  int crossing = 0;
  for (Index f = 0; f < faces; f += 5) {
    const Triangle v = s.front.item(f).v;
    for (Index p = 0; p < static_cast<Index>(input->points.size()); p += 3) {
      if (p == v[0] || p == v[1] || p == v[2]) continue;
      s.last_crossed_face = kInvalidIndex;
      const bool expected = volume::element_crosses_front(s, f, p);
      crossing += expected;
      for (Index last : {Index{0}, Index{7}, faces - 1, dead}) {
        s.last_crossed_face = last;
        EXPECT_EQ(volume::element_crosses_front(s, f, p), expected)
            << "face " << f << " point " << p << " remembered " << last;
      }
    }
  }
  EXPECT_GT(crossing, 100);
}

// The bins turn adaptive after a window of kBinsWindow face deletions in which the crossing check
// looked at more than kCrowdedPointsPerSearch points per deletion, not before the window ends
// and not at fewer; the crossing check answers the same before and after.
TEST(VolumeFront, BinsTurnAdaptiveWhenTheCrossingCheckLooksAtManyPointsPerDeletion) {
  const Mesh input = box_surface({0, 0, 0}, {1, 1, 1}, 0.25);
  const UniformSize size(0.25);
  volume::MesherState s(input, 1.0, size, Box{{-1, -1, -1}, {2, 2, 2}}, 0.25);
  s.point_size.assign(input.points.size(), 0.25);
  for (const Triangle& t : input.triangles) s.front.add({t[0], t[2], t[1]}, 1.0);
  // Elements on every face towards a few interior points and every front point.
  for (const Point& x : {Point{0.5, 0.5, 0.5}, Point{0.1, 0.2, 0.3}, Point{0.9, 0.1, 0.5}})
    s.points.push_back(x);
  const auto answers = [&] {
    std::vector<bool> out;
    for (Index f = 0; f < static_cast<Index>(input.triangles.size()); ++f)
      for (Index p = 0; p < static_cast<Index>(s.points.size()); p += 7)
        if (!has_corner(s.front.item(f).v, p))
          out.push_back(volume::element_crosses_front(s, f, p));
    return out;
  };
  const std::vector<bool> uniform = answers();
  ASSERT_GT(s.bins_watch.points, 0);

  s.bins_watch = {};
  // A window of deletions at exactly the bound: uniform bins stay, and a new window starts.
  s.bins_watch.queries = volume::kBinsWindow - 1;  // the call counts the last one
  s.bins_watch.points = volume::kCrowdedPointsPerSearch * volume::kBinsWindow;
  volume::adapt_bins_when_crowded(s);
  EXPECT_FALSE(s.front.adaptive_bins());
  EXPECT_EQ(s.bins_watch.queries, 0);
  // Over it, but the window not full yet.
  s.bins_watch.queries = volume::kBinsWindow - 2;
  s.bins_watch.points = volume::kCrowdedPointsPerSearch * volume::kBinsWindow * 10;
  volume::adapt_bins_when_crowded(s);
  EXPECT_FALSE(s.front.adaptive_bins());
  volume::adapt_bins_when_crowded(s);
  EXPECT_TRUE(s.front.adaptive_bins());
  EXPECT_EQ(answers(), uniform);
}

}  // namespace
}  // namespace afmesh
