// Decay laws (eq. 10–13) against hand-computed values at points inside r0, on it and beyond, for
// point, line and triangle sources.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

#include "core/sizing/decay_law.h"
#include "core/sizing/source_set.h"
#include "tests/sizing/sizing_test_util.h"

namespace afmesh {
namespace {

using sizing_test::point_source;
using sizing_test::source_of;

// Relative tolerance of the hand values (the laws are a few roundings deep).
void expect_rel(double actual, double expected) {
  EXPECT_NEAR(actual, expected, 1e-14 * std::fabs(expected)) << "expected " << expected;
}

double size_of(const SizeSource& source, const Point& x) {
  const std::vector<SizeSource> sources{source};
  return SourceSet(sources).size(0, x);
}

TEST(DecayLaw, ScaledDistanceIsZeroWithinR0AndLinearBeyond) {
  EXPECT_EQ(scaled_distance(0.5, 1.0, 0.2), 0.0);
  EXPECT_EQ(scaled_distance(1.0, 1.0, 0.2), 0.0);
  expect_rel(scaled_distance(1.5, 1.0, 0.2), 2.5);
  EXPECT_EQ(scaled_distance(1e300, 0.0, 1e-300), std::numeric_limits<double>::max());
}

TEST(DecayLaw, PowerLawOfAPointSource) {
  // delta0 0.1, r0 1, r1 0.5, gamma 1.5: 0.1 inside and on r0; at r = 2, rho = 2 and
  // 0.1 (1 + 2^1.5) = 0.38284271247461904.
  const SizeSource s = point_source({1, 1, 1}, 0.1, 1.0, 0.5, PowerLaw{1.5});
  expect_rel(size_of(s, {1, 1, 1}), 0.1);
  expect_rel(size_of(s, {1.6, 1, 1}), 0.1);
  expect_rel(size_of(s, {1, 1, 2}), 0.1);
  expect_rel(size_of(s, {1, 3, 1}), 0.38284271247461904);
}

TEST(DecayLaw, ExponentialLawOfALineSource) {
  // delta0 0.2, r0 0, r1 2, gamma 0.7 on the segment (0,0,0)-(2,0,0).
  const SizeSource s = source_of({{0, 0, 0}, {2, 0, 0}}, 0.2, 0.0, 2.0, ExponentialLaw{0.7});
  expect_rel(size_of(s, {1, 0, 0}), 0.2);                   // on the segment
  expect_rel(size_of(s, {1, 3, 0}), 0.5715302236126328);    // beside: r 3, 0.2 e^1.05
  expect_rel(size_of(s, {-3, 0, 0}), 0.5715302236126328);   // beyond x1: r 3
  expect_rel(size_of(s, {2, 0, 4}), 0.811039993368935);     // above x2: r 4, 0.2 e^1.4
  expect_rel(size_of(s, {5, 4, 0}), 1.1509205352011462);    // beyond x2: r 5, 0.2 e^1.75
}

TEST(DecayLaw, PolynomialLawOfTheDomeExample) {
  // The paper's dome: delta0 0.15, r0 1, r1 0.2, a1 1, a2 0 at the origin.
  const SizeSource s = point_source({0, 0, 0}, 0.15, 1.0, 0.2, PolynomialLaw{{1.0, 0.0}});
  expect_rel(size_of(s, {0.3, 0.4, 0}), 0.15);
  expect_rel(size_of(s, {0.6, 0.8, 0}), 0.15);
  expect_rel(size_of(s, {0, 1.5, 0}), 0.525);   // rho 2.5: 0.15 (1 + 2.5)
  expect_rel(size_of(s, {0, 0, -3}), 1.65);     // rho 10
}

TEST(DecayLaw, QuadraticLawOfATriangleSourceInsideOnAndBeyondItsEdges) {
  // a = [0.5, 0.25]: 1 + rho/2 + rho^2/4; r0 = 1, r1 = 1 on the triangle (0,0,0),(4,0,0),(0,4,0).
  const SizeSource s = source_of({{0, 0, 0}, {4, 0, 0}, {0, 4, 0}}, 0.1, 1.0, 1.0,
                                 PolynomialLaw{{0.5, 0.25}});
  expect_rel(size_of(s, {1, 1, 0}), 0.1);         // on the triangle
  expect_rel(size_of(s, {1, 1, 1}), 0.1);         // r = r0 above it
  expect_rel(size_of(s, {1, 1, 3}), 0.3);         // rho 2: 0.1 (1 + 1 + 1)
  expect_rel(size_of(s, {2, -3, 4}), 0.7);        // beyond an edge: r 5, rho 4: 0.1 (1 + 2 + 4)
  expect_rel(size_of(s, {-3, -4, 0}), 0.7);       // beyond a corner: r 5
  expect_rel(size_of(s, {2.5, 2.5, 0}), 0.1);     // beyond the long edge, within r0
  expect_rel(size_of(s, {3.5, 3.5, 0}),           // r = 3/sqrt(2), rho = r - 1
             0.1 * (1 + 0.5 * (3 / std::sqrt(2.0) - 1) +
                    0.25 * (3 / std::sqrt(2.0) - 1) * (3 / std::sqrt(2.0) - 1)));
}

TEST(DecayLaw, DecaySizeOfTheSpecEqualsTheStoredSourceBitForBit) {
  const std::vector<SizeSource> sources{
      point_source({0, 0, 0}, 0.1, 0.5, 0.3, PowerLaw{1.3}),
      source_of({{0, 0, 0}, {1, 2, 0}}, 0.2, 0.0, 0.7, ExponentialLaw{0.4}),
      source_of({{0, 0, 1}, {1, 0, 1}, {0, 1, 1}}, 0.05, 0.1, 1.0, PolynomialLaw{{1, 2, 3}})};
  const SourceSet set(sources);
  for (const Point& x : {Point{3, 1, 2}, Point{0.1, 0.2, 0.3}, Point{-2, 5, 1}}) {
    for (Index s = 0; s < 3; ++s) {
      EXPECT_EQ(set.size(s, x), decay_size(sources[s], set.distance(s, x)));
    }
  }
}

TEST(DecayLaw, EveryLawGrowsWithDistance) {
  const Point o{0, 0, 0};
  const std::vector<SizeSource> sources{point_source(o, 0.1, 0.5, 0.3, PowerLaw{0.5}),
                                        point_source(o, 0.1, 0.5, 0.3, PowerLaw{2.0}),
                                        point_source(o, 0.1, 0.0, 0.3, ExponentialLaw{0}),
                                        point_source(o, 0.1, 0.0, 0.3, ExponentialLaw{2}),
                                        point_source(o, 0.1, 0.2, 1, PolynomialLaw{}),
                                        point_source(o, 0.1, 0.2, 1, PolynomialLaw{{0, 1}})};
  for (const SizeSource& s : sources) {
    double previous = 0.0;
    for (double r = 0.0; r < 20.0; r += 0.01) {
      const double size = decay_size(s, r);
      EXPECT_GE(size, previous);
      EXPECT_GE(size, s.delta0);
      previous = size;
    }
  }
}

TEST(DecayLaw, HugeDistancesGiveInfinityOrANumberNeverNaN) {
  const SizeSource poly = point_source({0, 0, 0}, 0.1, 0.0, 1e-300, PolynomialLaw{{1.0, 0.0}});
  const SizeSource power = point_source({0, 0, 0}, 0.1, 0.0, 1e-300, PowerLaw{2});
  const SizeSource exponential = point_source({0, 0, 0}, 0.1, 0.0, 1e-300, ExponentialLaw{1});
  for (const SizeSource& s : {poly, power, exponential}) {
    const double size = decay_size(s, 1e10);
    EXPECT_FALSE(std::isnan(size));
    EXPECT_GT(size, 1e300);
  }
}

}  // namespace
}  // namespace afmesh
