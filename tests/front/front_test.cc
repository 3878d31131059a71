// Unit tests of the dimension-generic front (core/front/): the bins over front points and
// items, the item lookup by orientation, the per-point live lists and the priority queue, for
// faces (Arity 3, the volume front) and sides (Arity 2, the surface front).
#include <algorithm>
#include <cmath>
#include <random>
#include <utility>
#include <vector>

#include "core/front/advancing_front.h"
#include "core/front/front_bins.h"
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

TEST(FrontBins, ItemQueriesFindEveryOverlappingItem) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(0.0, 10.0), s(0.0, 1.5);
  std::vector<Box> boxes(1000);
  FrontBins bins(Box{{0, 0, 0}, {10, 10, 10}}, 1.0);
  for (Index i = 0; i < 1000; ++i) {
    const Point lo{u(rng), u(rng), u(rng)};
    boxes[i] = Box{lo, {lo[0] + s(rng), lo[1] + s(rng), lo[2] + s(rng)}};
    bins.insert_item(i, boxes[i]);
  }
  for (int q = 0; q < 50; ++q) {
    const Point lo{u(rng), u(rng), u(rng)};
    const Box box{lo, {lo[0] + 1, lo[1] + 1, lo[2] + 1}};
    std::vector<Index> found;
    bins.items_near(box, found);
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
TEST(FrontBins, ItemQueriesListEachItemOnceAlsoPastTheDomain) {
  std::mt19937 rng(13);
  std::uniform_real_distribution<double> u(-2.0, 6.0), s(0.0, 3.0);
  std::vector<Box> boxes(600);
  FrontBins bins(Box{{0, 0, 0}, {4, 4, 4}}, 0.5);
  for (Index i = 0; i < 600; ++i) {
    const Point lo{u(rng), u(rng), u(rng)};
    boxes[i] = Box{lo, {lo[0] + s(rng), lo[1] + s(rng), lo[2] + s(rng)}};
    bins.insert_item(i, boxes[i]);
  }
  for (Index i = 0; i < 600; i += 3) bins.erase_item(i, boxes[i]);
  for (int q = 0; q < 200; ++q) {
    const Point lo{u(rng), u(rng), u(rng)};
    const double e = q % 2 == 0 ? 0.1 : 2.5;
    const Box box{lo, {lo[0] + e, lo[1] + e, lo[2] + e}};
    std::vector<Index> found;
    bins.items_near(box, found);
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

TEST(AdvancingFront, LookupFindsFacesByOrientation) {
  std::vector<Point> pts = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  AdvancingFront<3> front(pts, Box{{0, 0, 0}, {1, 1, 1}}, 0.5);
  const Index f = front.add({0, 1, 2}, 1.0);
  EXPECT_EQ(front.find({0, 1, 2}), f);  // every rotation
  EXPECT_EQ(front.find({1, 2, 0}), f);
  EXPECT_EQ(front.find({2, 0, 1}), f);
  EXPECT_FALSE(front.find({1, 0, 2}).has_value());  // the other orientation is another face
  EXPECT_FALSE(front.find({0, 2, 1}).has_value());
  EXPECT_FALSE(front.find({0, 1, 3}).has_value());
  // Both orientations on the front at once (two layers where sides cross, paper §2).
  const Index g = front.add({2, 1, 0}, 1.0);
  EXPECT_EQ(front.find({0, 2, 1}), g);
  EXPECT_EQ(front.find({0, 1, 2}), f);
  front.remove(f);
  EXPECT_FALSE(front.find({0, 1, 2}).has_value());
  EXPECT_EQ(front.find({1, 0, 2}), g);
  front.remove(g);
  EXPECT_EQ(front.size(), 0);
}

// Faces sharing points (a fan around point 0 and faces off it), added and removed in a mixed
// order, in both orientations: find answers from the points' face lists exactly as a set of
// oriented triangles would.
TEST(AdvancingFront, LookupFollowsAddsAndRemovesOfFacesSharingPoints) {
  std::vector<Point> pts(12);
  for (int i = 0; i < 12; ++i) pts[i] = {std::cos(i * 0.5), std::sin(i * 0.5), 0.1 * i};
  AdvancingFront<3> front(pts, Box{{-1, -1, 0}, {1, 1, 1.2}}, 0.3);
  std::mt19937 rng(3);
  std::uniform_int_distribution<Index> vertex(0, 11);
  std::vector<std::pair<Triangle, Index>> live;
  for (int step = 0; step < 3000; ++step) {
    Triangle t{step % 3 == 0 ? 0 : vertex(rng), vertex(rng), vertex(rng)};
    if (t[0] == t[1] || t[1] == t[2] || t[0] == t[2]) continue;
    const auto found = front.find({t[2], t[0], t[1]});
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

TEST(AdvancingFront, QueuePopsSmallestFirstAndDeferredLast) {
  std::vector<Point> pts = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {1, 1, 1}};
  AdvancingFront<3> front(pts, Box{{0, 0, 0}, {1, 1, 1}}, 0.5);
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

// Adaptive bins (FrontBins::Adaptive, an octree): points and items whose sizes span six orders of
// magnitude (a cluster a millionth of the domain wide beside points spread over all of it, some
// past the domain), inserted, partly erased, queried with boxes of every scale. Every point inside
// a box and every item overlapping it is listed exactly once, and only those.
TEST(FrontBins, AdaptiveBinsAnswerExactlyAcrossScales) {
  std::mt19937 rng(17);
  std::uniform_real_distribution<double> u(-1.0, 11.0), unit(0.0, 1.0);
  const Point cluster{3.0, 4.0, 5.0};
  const auto point_at = [&](int i) -> Point {
    if (i % 2 == 0) return {u(rng), u(rng), u(rng)};
    const double r = std::pow(10.0, -6.0 * unit(rng));  // 1e-6 .. 1 from the cluster
    return {cluster[0] + r * (unit(rng) - 0.5), cluster[1] + r * (unit(rng) - 0.5),
            cluster[2] + r * (unit(rng) - 0.5)};
  };
  std::vector<Point> pts(3000);
  std::vector<Box> boxes(3000);
  FrontBins bins(Box{{0, 0, 0}, {10, 10, 10}}, 0.5, FrontBins::Adaptive{});
  EXPECT_TRUE(bins.adaptive());
  for (Index i = 0; i < 3000; ++i) {
    pts[i] = point_at(i);
    const double e = std::pow(10.0, -6.0 * unit(rng));
    boxes[i] = Box{pts[i], {pts[i][0] + e, pts[i][1] + 2 * e, pts[i][2] + e}};
    bins.insert_point(i, pts[i]);
    bins.insert_item(i, boxes[i]);
  }
  for (Index i = 0; i < 3000; i += 4) {
    bins.erase_point(i, pts[i]);
    bins.erase_item(i, boxes[i]);
  }
  for (int q = 0; q < 300; ++q) {
    const double e = std::pow(10.0, 1.0 - 7.0 * unit(rng));
    const Point c = q % 2 == 0 ? Point{u(rng), u(rng), u(rng)} : point_at(1);
    const Box box{{c[0] - e, c[1] - e, c[2] - e}, {c[0] + e, c[1] + e, c[2] + e}};
    std::vector<Index> points, items;
    bins.points_near(box, points);
    bins.items_near(box, items);
    std::sort(points.begin(), points.end());
    std::sort(items.begin(), items.end());
    EXPECT_EQ(std::adjacent_find(points.begin(), points.end()), points.end());
    EXPECT_EQ(std::adjacent_find(items.begin(), items.end()), items.end());
    std::vector<Index> want_points, want_items;
    for (Index i = 0; i < 3000; ++i) {
      if (i % 4 == 0) continue;
      bool inside = true;
      for (int a = 0; a < 3; ++a) inside &= pts[i][a] >= box.lo[a] && pts[i][a] <= box.hi[a];
      if (inside) want_points.push_back(i);
      if (boxes_overlap(box, boxes[i])) want_items.push_back(i);
    }
    EXPECT_EQ(points, want_points) << "query " << q;
    EXPECT_EQ(items, want_items) << "query " << q;
  }
}

// A front whose bins turn adaptive midway keeps its points and items: the same sets before and
// after, and adds and removes after the switch are seen.
TEST(AdvancingFront, UseAdaptiveBinsKeepsWhatIsOnTheFront) {
  std::mt19937 rng(19);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<Point> pts(400);
  for (Point& p : pts) p = {u(rng), u(rng), u(rng)};
  AdvancingFront<2> front(pts, Box{{0, 0, 0}, {1, 1, 1}}, 0.1);
  std::vector<Index> ids;
  for (Index i = 0; i + 1 < 300; i += 2) ids.push_back(front.add({i, i + 1}, 1.0));
  for (std::size_t k = 0; k < ids.size(); k += 3) front.remove(ids[k]);
  const Box all{{-1, -1, -1}, {2, 2, 2}}, part{{0.2, 0.2, 0.2}, {0.6, 0.7, 0.8}};
  const auto listed = [&](const Box& box) {
    std::vector<Index> points, items;
    front.bins().points_near(box, points);
    front.bins().items_near(box, items);
    std::sort(points.begin(), points.end());
    std::sort(items.begin(), items.end());
    return std::make_pair(points, items);
  };
  const auto grid_all = listed(all);
  const auto grid_part = listed(part);
  EXPECT_FALSE(front.adaptive_bins());
  front.use_adaptive_bins();
  EXPECT_TRUE(front.adaptive_bins());
  EXPECT_EQ(listed(all), grid_all);
  // The grid lists every point of the cells the box meets and the items whose boxes miss it by
  // less than 1/255 of a cell; the tree lists exactly the points inside and the items that
  // overlap: a subset with every point inside.
  const auto tree_part = listed(part);
  for (const Index p : grid_part.first) {
    bool inside = true;
    for (int a = 0; a < 3; ++a) inside &= pts[p][a] >= part.lo[a] && pts[p][a] <= part.hi[a];
    EXPECT_EQ(std::binary_search(tree_part.first.begin(), tree_part.first.end(), p), inside);
  }
  for (const Index f : tree_part.second)
    EXPECT_TRUE(std::binary_search(grid_part.second.begin(), grid_part.second.end(), f));
  const Index added = front.add({300, 301}, 1.0);
  front.remove(ids[1]);
  const auto after = listed(all);
  EXPECT_TRUE(std::binary_search(after.second.begin(), after.second.end(), added));
  EXPECT_FALSE(std::binary_search(after.second.begin(), after.second.end(), ids[1]));
  EXPECT_TRUE(std::binary_search(after.first.begin(), after.first.end(), Index{300}));
  EXPECT_FALSE(std::binary_search(after.first.begin(), after.first.end(), Index{2}));
}

TEST(AdvancingFront, PointsLeaveTheBinsWithTheirLastItem) {
  std::vector<Point> pts = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  AdvancingFront<3> front(pts, Box{{0, 0, 0}, {1, 1, 1}}, 0.5);
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

// Sides (Arity 2, the surface front of paper §3): a side and its reverse are different items,
// each found only in its own orientation.
TEST(AdvancingFront, SidesAreFoundOnlyInTheirOwnOrientation) {
  std::vector<Point> pts = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}};
  AdvancingFront<2> front(pts, Box{{0, 0, 0}, {1, 1, 1}}, 0.5);
  const Index s = front.add({0, 1}, 1.0);
  EXPECT_EQ(front.find({0, 1}), s);
  EXPECT_FALSE(front.find({1, 0}).has_value());
  const Index r = front.add({1, 0}, 1.0);  // both orientations at once
  EXPECT_EQ(front.find({1, 0}), r);
  EXPECT_EQ(front.find({0, 1}), s);
  front.remove(s);
  EXPECT_FALSE(front.find({0, 1}).has_value());
  EXPECT_EQ(front.find({1, 0}), r);
  EXPECT_FALSE(front.on_front(2));
  front.add({1, 2}, 1.0);
  EXPECT_TRUE(front.on_front(2));
  EXPECT_EQ(front.size(), 2);
}

// Sides sharing points, added and removed in a mixed order: find answers as a set of oriented
// segments would, and a point is on the front exactly while a live side uses it; the bins list
// the live sides' boxes.
TEST(AdvancingFront, SideLookupFollowsAddsAndRemoves) {
  std::vector<Point> pts(10);
  for (int i = 0; i < 10; ++i) pts[i] = {std::cos(i * 0.6), std::sin(i * 0.6), 0.0};
  AdvancingFront<2> front(pts, Box{{-1, -1, -1}, {1, 1, 1}}, 0.25);
  std::mt19937 rng(5);
  std::uniform_int_distribution<Index> vertex(0, 9);
  std::vector<std::pair<std::array<Index, 2>, Index>> live;
  for (int step = 0; step < 2000; ++step) {
    const std::array<Index, 2> e{vertex(rng), vertex(rng)};
    if (e[0] == e[1]) continue;
    const auto found = front.find(e);
    auto it = std::find_if(live.begin(), live.end(), [&](const auto& x) { return x.first == e; });
    ASSERT_EQ(found.has_value(), it != live.end()) << "step " << step;
    if (found) {
      ASSERT_EQ(*found, it->second);
      front.remove(*found);
      live.erase(it);
    } else {
      live.push_back({e, front.add(e, 1.0)});
    }
    for (Index p = 0; p < 10; ++p) {
      const bool used = std::any_of(live.begin(), live.end(), [&](const auto& x) {
        return x.first[0] == p || x.first[1] == p;
      });
      ASSERT_EQ(front.on_front(p), used) << "step " << step << " point " << p;
    }
  }
  std::vector<Index> near;
  front.bins().items_near(Box{{-2, -2, -2}, {2, 2, 2}}, near);
  std::sort(near.begin(), near.end());
  std::vector<Index> ids;
  for (const auto& x : live) ids.push_back(x.second);
  std::sort(ids.begin(), ids.end());
  EXPECT_EQ(near, ids);
}

// The queue of S1 orders sides as F6 orders faces: crossing-environment items first within a
// class, then smallest size.
TEST(AdvancingFront, QueuePutsCrossingEnvironmentItemsFirst) {
  std::vector<Point> pts = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}};
  AdvancingFront<2> front(pts, Box{{0, 0, 0}, {1, 1, 1}}, 0.5);
  const Index plain = front.add({0, 1}, 0.5);
  const Index marked = front.add({1, 2}, 2.0, 4);
  const Index small = front.add({2, 3}, 0.1);
  EXPECT_EQ(front.pop(), marked);
  EXPECT_EQ(front.pop(), small);
  front.requeue(small, 0.1);
  EXPECT_EQ(front.pop(), small);
  EXPECT_EQ(front.pop(), plain);
  EXPECT_FALSE(front.pop().has_value());
}

}  // namespace
}  // namespace afmesh
