// Unit tests of the front's data structures (bins, lookup table, priority queue) and of the
// end-game pocket fill.
#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>

#include "core/geometry/predicates.h"
#include "core/geometry/vec.h"
#include "core/shapes/shapes.h"
#include "core/sizing/size_field.h"
#include "core/volume/front.h"
#include "core/volume/front_bins.h"
#include "core/volume/front_steps.h"
#include "gtest/gtest.h"

namespace afmesh {
namespace {

TEST(FrontBins, PointQueriesFindEveryPointInTheBox) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(0.0, 10.0);
  std::vector<Point> pts(2000);
  for (Point& p : pts) p = {u(rng), u(rng), u(rng)};
  FrontBins bins(Box{{0, 0, 0}, {10, 10, 10}}, 0.7);
  for (Index i = 0; i < static_cast<Index>(pts.size()); ++i) bins.insert_point(i, pts[i]);
  for (Index i = 0; i < 500; ++i) bins.erase_point(i, pts[i]);  // leave the front
  for (int q = 0; q < 50; ++q) {
    const Point c{u(rng), u(rng), u(rng)};
    const Box box{{c[0] - 1, c[1] - 0.5, c[2] - 2}, {c[0] + 1, c[1] + 0.5, c[2] + 2}};
    std::vector<Index> found;
    bins.points_near(box, found);
    std::sort(found.begin(), found.end());
    EXPECT_EQ(std::adjacent_find(found.begin(), found.end()), found.end());
    for (Index i = 0; i < static_cast<Index>(pts.size()); ++i) {
      bool inside = true;
      for (int a = 0; a < 3; ++a) inside &= pts[i][a] >= box.lo[a] && pts[i][a] <= box.hi[a];
      const bool listed = std::binary_search(found.begin(), found.end(), i);
      if (i < 500) {
        EXPECT_FALSE(listed) << "erased point " << i;
      } else if (inside) {
        EXPECT_TRUE(listed) << "point " << i;
      }
    }
  }
}

TEST(FrontBins, FaceQueriesFindEveryOverlappingFace) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(0.0, 10.0), s(0.0, 1.5);
  std::vector<Box> boxes(1000);
  FrontBins bins(Box{{0, 0, 0}, {10, 10, 10}}, 1.0);
  for (Index i = 0; i < 1000; ++i) {
    const Point lo{u(rng), u(rng), u(rng)};
    boxes[i] = Box{lo, {lo[0] + s(rng), lo[1] + s(rng), lo[2] + s(rng)}};
    bins.insert_face(i, boxes[i]);
  }
  for (int q = 0; q < 50; ++q) {
    const Point lo{u(rng), u(rng), u(rng)};
    const Box box{lo, {lo[0] + 1, lo[1] + 1, lo[2] + 1}};
    std::vector<Index> found;
    bins.faces_near(box, found);
    std::sort(found.begin(), found.end());
    EXPECT_EQ(std::adjacent_find(found.begin(), found.end()), found.end());
    for (Index i = 0; i < 1000; ++i) {
      if (boxes_overlap(box, boxes[i])) {
        EXPECT_TRUE(std::binary_search(found.begin(), found.end(), i)) << "face " << i;
      }
    }
    // ... and only faces whose box meets the query box (up to 1/255 of a cell, rounded out).
    Box grown = box;
    for (int a = 0; a < 3; ++a) grown.lo[a] -= 0.01, grown.hi[a] += 0.01;
    for (Index f : found) EXPECT_TRUE(boxes_overlap(grown, boxes[f])) << "face " << f;
  }
}

// Faces and queries reaching past the bins' domain (clamped into the border cells), spanning
// many cells or lying in one: each overlapping face is listed exactly once.
TEST(FrontBins, FaceQueriesListEachFaceOnceAlsoPastTheDomain) {
  std::mt19937 rng(13);
  std::uniform_real_distribution<double> u(-2.0, 6.0), s(0.0, 3.0);
  std::vector<Box> boxes(600);
  FrontBins bins(Box{{0, 0, 0}, {4, 4, 4}}, 0.5);
  for (Index i = 0; i < 600; ++i) {
    const Point lo{u(rng), u(rng), u(rng)};
    boxes[i] = Box{lo, {lo[0] + s(rng), lo[1] + s(rng), lo[2] + s(rng)}};
    bins.insert_face(i, boxes[i]);
  }
  for (Index i = 0; i < 600; i += 3) bins.erase_face(i, boxes[i]);
  for (int q = 0; q < 200; ++q) {
    const Point lo{u(rng), u(rng), u(rng)};
    const double e = q % 2 == 0 ? 0.1 : 2.5;
    const Box box{lo, {lo[0] + e, lo[1] + e, lo[2] + e}};
    std::vector<Index> found;
    bins.faces_near(box, found);
    std::sort(found.begin(), found.end());
    EXPECT_EQ(std::adjacent_find(found.begin(), found.end()), found.end());
    for (Index i = 0; i < 600; ++i) {
      const bool listed = std::binary_search(found.begin(), found.end(), i);
      if (i % 3 == 0) {
        EXPECT_FALSE(listed) << "erased face " << i;
      } else if (boxes_overlap(box, boxes[i])) {
        EXPECT_TRUE(listed) << "face " << i;
      }
    }
  }
}

TEST(Front, LookupFindsFacesByOrientation) {
  std::vector<Point> pts = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  Front front(pts, Box{{0, 0, 0}, {1, 1, 1}}, 0.5);
  const Index f = front.add({0, 1, 2}, 1.0);
  EXPECT_EQ(front.find(0, 1, 2), f);  // every rotation
  EXPECT_EQ(front.find(1, 2, 0), f);
  EXPECT_EQ(front.find(2, 0, 1), f);
  EXPECT_FALSE(front.find(1, 0, 2).has_value());  // the other orientation is another face
  EXPECT_FALSE(front.find(0, 2, 1).has_value());
  EXPECT_FALSE(front.find(0, 1, 3).has_value());
  // Both orientations on the front at once (two layers where sides cross, paper §2).
  const Index g = front.add({2, 1, 0}, 1.0);
  EXPECT_EQ(front.find(0, 2, 1), g);
  EXPECT_EQ(front.find(0, 1, 2), f);
  front.remove(f);
  EXPECT_FALSE(front.find(0, 1, 2).has_value());
  EXPECT_EQ(front.find(1, 0, 2), g);
  front.remove(g);
  EXPECT_EQ(front.size(), 0);
}

// Faces sharing points (a fan around point 0 and faces off it), added and removed in a mixed
// order, in both orientations: find answers from the points' face lists exactly as a set of
// oriented triangles would.
TEST(Front, LookupFollowsAddsAndRemovesOfFacesSharingPoints) {
  std::vector<Point> pts(12);
  for (int i = 0; i < 12; ++i) pts[i] = {std::cos(i * 0.5), std::sin(i * 0.5), 0.1 * i};
  Front front(pts, Box{{-1, -1, 0}, {1, 1, 1.2}}, 0.3);
  std::mt19937 rng(3);
  std::uniform_int_distribution<Index> vertex(0, 11);
  std::vector<std::pair<Triangle, Index>> live;
  for (int step = 0; step < 3000; ++step) {
    Triangle t{step % 3 == 0 ? 0 : vertex(rng), vertex(rng), vertex(rng)};
    if (t[0] == t[1] || t[1] == t[2] || t[0] == t[2]) continue;
    const auto found = front.find(t[2], t[0], t[1]);
    auto it = std::find_if(live.begin(), live.end(), [&](const auto& e) {
      const Triangle& a = e.first;  // the same oriented triangle: a rotation of t
      for (int r = 0; r < 3; ++r) {
        if (a[r] == t[0] && a[(r + 1) % 3] == t[1] && a[(r + 2) % 3] == t[2]) return true;
      }
      return false;
    });
    ASSERT_EQ(found.has_value(), it != live.end()) << "step " << step;
    if (found) {
      ASSERT_EQ(*found, it->second);
      front.remove(*found);
      live.erase(it);
    } else {
      live.push_back({t, front.add(t, 1.0)});
    }
    for (Index p = 0; p < 12; ++p) {
      const bool used = std::any_of(live.begin(), live.end(), [&](const auto& e) {
        return e.first[0] == p || e.first[1] == p || e.first[2] == p;
      });
      ASSERT_EQ(front.on_front(p), used) << "step " << step << " point " << p;
    }
  }
  EXPECT_EQ(front.size(), static_cast<std::int64_t>(live.size()));
}

TEST(Front, QueuePopsSmallestFirstAndDeferredLast) {
  std::vector<Point> pts = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {1, 1, 1}};
  Front front(pts, Box{{0, 0, 0}, {1, 1, 1}}, 0.5);
  const Index big = front.add({0, 1, 2}, 3.0);
  const Index small = front.add({0, 1, 3}, 1.0);
  const Index mid = front.add({0, 2, 3}, 2.0);
  const Index gone = front.add({1, 2, 3}, 0.5);
  front.remove(gone);
  EXPECT_EQ(front.pop(), small);
  front.defer(small, 1.0);  // failed once: after every class-0 face
  EXPECT_EQ(front.pop(), mid);
  EXPECT_EQ(front.pop(), big);
  EXPECT_EQ(front.pop(), small);
  EXPECT_FALSE(front.pop().has_value());
}

TEST(Front, PointsLeaveTheBinsWithTheirLastFace) {
  std::vector<Point> pts = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  Front front(pts, Box{{0, 0, 0}, {1, 1, 1}}, 0.5);
  const Index a = front.add({0, 1, 2}, 1.0);
  const Index b = front.add({0, 1, 3}, 1.0);
  front.remove(a);
  EXPECT_TRUE(front.on_front(0));
  EXPECT_FALSE(front.on_front(2));
  std::vector<Index> near;
  front.bins().points_near(Box{{-1, -1, -1}, {2, 2, 2}}, near);
  std::sort(near.begin(), near.end());
  EXPECT_EQ(near, (std::vector<Index>{0, 1, 3}));
  front.remove(b);
  near.clear();
  front.bins().points_near(Box{{-1, -1, -1}, {2, 2, 2}}, near);
  EXPECT_TRUE(near.empty());
}

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

    const Triangle v = s.front.face(a).v;
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
      const Triangle& v = s.front.face(f).v;
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

}  // namespace
}  // namespace afmesh
