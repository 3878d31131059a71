// r(x) of point, line and triangle sources (eq. 1–9): exact hand values inside, on and beyond
// each edge and end, degenerate triangles, and agreement with a dense sampling of the source.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <random>
#include <vector>

#include "core/geometry/vec.h"
#include "core/sizing/source_set.h"
#include "tests/sizing/sizing_test_util.h"

namespace afmesh {
namespace {

using sizing_test::source_of;

// r(x) of the single source with `points`.
double source_distance(const std::vector<Point>& points, const Point& x) {
  const std::vector<SizeSource> sources{source_of(points, 1.0, 0.0, 1.0, PolynomialLaw{})};
  return SourceSet(sources).distance(0, x);
}

constexpr double kTol = 1e-14;

TEST(SourceDistance, PointSourceIsDistanceToThePoint) {
  const Point p{1, 2, 3};
  EXPECT_NEAR(source_distance({p}, {4, 6, 3}), 5.0, kTol);
  EXPECT_NEAR(source_distance({p}, {1, 2, 3}), 0.0, kTol);
  EXPECT_NEAR(source_distance({p}, {1, 2, -9}), 12.0, kTol);
}

TEST(SourceDistance, LineSourceInsideOnAndBeyondBothEnds) {
  const std::vector<Point> line{{0, 0, 0}, {2, 0, 0}};
  EXPECT_NEAR(source_distance(line, {1, 3, 4}), 5.0, kTol);    // beside the segment
  EXPECT_NEAR(source_distance(line, {1.5, 0, 0}), 0.0, kTol);  // on it
  EXPECT_NEAR(source_distance(line, {0, 0, 0}), 0.0, kTol);    // on an end
  EXPECT_NEAR(source_distance(line, {-3, 4, 0}), 5.0, kTol);   // beyond x1: distance to x1
  EXPECT_NEAR(source_distance(line, {5, 0, 4}), 5.0, kTol);    // beyond x2: distance to x2
  EXPECT_NEAR(source_distance(line, {3, 0, 0}), 1.0, kTol);    // on the line, past the end
}

// Triangle (0,0,0), (4,0,0), (0,4,0) in the plane z = 0.
const std::vector<Point> kTriangle{{0, 0, 0}, {4, 0, 0}, {0, 4, 0}};

TEST(SourceDistance, TriangleSourceAboveInsideAndOnIt) {
  EXPECT_NEAR(source_distance(kTriangle, {1, 1, 3}), 3.0, kTol);
  EXPECT_NEAR(source_distance(kTriangle, {1, 1, -2.5}), 2.5, kTol);
  EXPECT_NEAR(source_distance(kTriangle, {1, 1, 0}), 0.0, kTol);
  EXPECT_NEAR(source_distance(kTriangle, {2, 2, 0}), 0.0, kTol);   // on the long edge
  EXPECT_NEAR(source_distance(kTriangle, {0, 4, 7}), 7.0, kTol);   // above a corner
}

TEST(SourceDistance, TriangleSourceBeyondEachEdgeAndCorner) {
  EXPECT_NEAR(source_distance(kTriangle, {2, -3, 4}), 5.0, kTol);             // beyond edge y = 0
  EXPECT_NEAR(source_distance(kTriangle, {-3, 2, 4}), 5.0, kTol);             // beyond edge x = 0
  EXPECT_NEAR(source_distance(kTriangle, {3, 3, 0}), std::sqrt(2.0), kTol);  // beyond x + y = 4
  EXPECT_NEAR(source_distance(kTriangle, {3, 3, 1}), std::sqrt(3.0), kTol);
  EXPECT_NEAR(source_distance(kTriangle, {-3, -4, 0}), 5.0, kTol);            // beyond (0,0,0)
  EXPECT_NEAR(source_distance(kTriangle, {7, -4, 0}), 5.0, kTol);             // beyond (4,0,0)
  EXPECT_NEAR(source_distance(kTriangle, {-4, 7, 0}), 5.0, kTol);             // beyond (0,4,0)
}

TEST(SourceDistance, TriangleVertexOrderDoesNotMatter) {
  std::array<int, 3> perm{0, 1, 2};
  const std::vector<Point> probes{{1, 1, 3}, {2, -3, 4}, {3, 3, 1}, {7, -4, 0}, {-1, 5, 2}};
  do {
    const std::vector<Point> t{kTriangle[perm[0]], kTriangle[perm[1]], kTriangle[perm[2]]};
    for (const Point& x : probes) {
      EXPECT_NEAR(source_distance(t, x), source_distance(kTriangle, x), kTol);
    }
  } while (std::next_permutation(perm.begin(), perm.end()));
}

TEST(SourceDistance, DegenerateTrianglesAreSegmentsOrPoints) {
  // Two coincident points: the segment between the distinct ones.
  const std::vector<Point> doubled{{0, 0, 0}, {0, 0, 0}, {2, 0, 0}};
  EXPECT_NEAR(source_distance(doubled, {1, 3, 4}), 5.0, kTol);
  EXPECT_NEAR(source_distance(doubled, {5, 0, 4}), 5.0, kTol);
  // Collinear points: the segment spanning them, whatever their order.
  using Points = std::vector<Point>;
  for (const Points& collinear : {Points{{0, 0, 0}, {1, 0, 0}, {3, 0, 0}},
                                  Points{{1, 0, 0}, {3, 0, 0}, {0, 0, 0}},
                                  Points{{3, 0, 0}, {0, 0, 0}, {1, 0, 0}}}) {
    EXPECT_NEAR(source_distance(collinear, {2, 1, 0}), 1.0, kTol);
    EXPECT_NEAR(source_distance(collinear, {4, 0, 0}), 1.0, kTol);
    EXPECT_NEAR(source_distance(collinear, {-1, 0, 0}), 1.0, kTol);
    EXPECT_NEAR(source_distance(collinear, {2.5, 0, 0}), 0.0, kTol);
  }
  // Three coincident points: a point.
  const std::vector<Point> point{{1, 1, 1}, {1, 1, 1}, {1, 1, 1}};
  EXPECT_NEAR(source_distance(point, {1, 4, 5}), 5.0, kTol);
}

TEST(SourceDistance, NearlyCollinearTriangleStaysAccurate) {
  // Height 1e-12 over a base of length 2: within 1e-11 of the segment's distance.
  const std::vector<Point> sliver{{0, 0, 0}, {2, 0, 0}, {1, 1e-12, 0}};
  EXPECT_NEAR(source_distance(sliver, {1, 0, 3}), 3.0, 1e-11);
  EXPECT_NEAR(source_distance(sliver, {-3, 0, 4}), 5.0, 1e-11);
  EXPECT_NEAR(source_distance(sliver, {1, 5e-13, 0}), 0.0, 1e-11);
  // Just above the flatness limit: the interior test decides, still accurate.
  const std::vector<Point> thin{{0, 0, 0}, {2, 0, 0}, {1, 1e-6, 0}};
  EXPECT_NEAR(source_distance(thin, {1, 5e-7, 3}), 3.0, 1e-12);
  EXPECT_NEAR(source_distance(thin, {1, -1, 0}), 1.0, 1e-12);
}

// Smallest distance from x to points sampled on the triangle with n + 1 points per edge.
double sampled_distance(const std::array<Point, 3>& t, const Point& x, int n) {
  double best = std::numeric_limits<double>::infinity();
  for (int i = 0; i <= n; ++i) {
    for (int j = 0; i + j <= n; ++j) {
      const double u = double(i) / n, v = double(j) / n;
      const Point p = add(t[0], add(scale(sub(t[1], t[0]), u), scale(sub(t[2], t[0]), v)));
      best = std::min(best, distance(p, x));
    }
  }
  return best;
}

TEST(SourceDistance, AgreesWithDenseSamplingOfRandomTriangles) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> coord(-1.0, 1.0);
  const auto random_point = [&] { return Point{coord(rng), coord(rng), coord(rng)}; };
  constexpr int kSamples = 150;
  for (int trial = 0; trial < 60; ++trial) {
    std::array<Point, 3> t{random_point(), random_point(), random_point()};
    if (trial % 3 == 1) t[2] = add(lerp(t[0], t[1], 0.3), scale(random_point(), 1e-9));  // thin
    if (trial % 3 == 2) t[2] = t[1];                                       // a segment
    const double longest = std::max({distance(t[0], t[1]), distance(t[1], t[2]),
                                     distance(t[2], t[0])});
    // Every point of the triangle is within `spacing` of a sample; a thin triangle counts as its
    // edges, off by at most kFlatSine times an edge.
    const double spacing = longest / kSamples;
    const double flat = trial % 3 == 1 ? SourceSet::kFlatSine * longest : 0.0;
    const std::vector<SizeSource> sources{source_of({t[0], t[1], t[2]}, 1, 0, 1, PolynomialLaw{})};
    const SourceSet set(sources);
    for (int probe = 0; probe < 20; ++probe) {
      const Point x = scale(random_point(), 1.5);
      const double exact = set.distance(0, x);
      const double sampled = sampled_distance(t, x, kSamples);
      EXPECT_LE(exact, sampled + flat + 1e-12) << "trial " << trial;
      EXPECT_GE(exact, sampled - spacing) << "trial " << trial;
    }
  }
}

}  // namespace
}  // namespace afmesh
