#include "core/geometry/predicates.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

#include "core/geometry/exact_predicates.h"
#include "tests/geometry/test_support.h"

namespace afmesh {
namespace {

using testing::Int128;
using testing::IntPoint;
using testing::near_plane_point;
using testing::orient2d_reference;
using testing::orient3d_reference;
using testing::random_int_point;
using testing::random_point;
using testing::to_point;

constexpr double kUnit = 0x1p-53;  // the perturbation step of the near-degenerate grids

// det[b-a, c-a] in plain doubles: what a naive implementation computes.
int naive_orient2d(const double a[2], const double b[2], const double c[2]) {
  const double det = (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
  return (det > 0) - (det < 0);
}

int naive_orient3d(const Point& a, const Point& b, const Point& c, const Point& d) {
  const double det = orient3d_fast(a, b, c, d);
  return (det > 0) - (det < 0);
}

// Sign of a permutation of {0, 1, 2, 3}.
int permutation_sign(const std::array<int, 4>& p) {
  int inversions = 0;
  for (int i = 0; i < 4; ++i) {
    for (int j = i + 1; j < 4; ++j) inversions += p[i] > p[j];
  }
  return inversions % 2 == 0 ? 1 : -1;
}

// ----- orient3d ----------------------------------------------------------------------------------

TEST(Orient3d, UnitTetIsPositiveAndSwapNegates) {
  const Point a{0, 0, 0}, b{1, 0, 0}, c{0, 1, 0}, d{0, 0, 1};
  EXPECT_EQ(orient3d(a, b, c, d), 1);
  EXPECT_EQ(orient3d(b, a, c, d), -1);
  EXPECT_EQ(orient3d(a, b, c, Point{0.3, 0.3, 0}), 0);
  EXPECT_EQ(orient3d(a, b, c, Point{5, -7, -1e-300}), -1);
  EXPECT_DOUBLE_EQ(orient3d_fast(a, b, c, d), 1.0);  // 6 × volume 1/6
}

TEST(Orient3d, MatchesInt128ReferenceOnRandomIntegerPoints) {
  std::mt19937_64 rng(11);
  for (int trial = 0; trial < 20000; ++trial) {
    const std::int64_t bound = std::int64_t(1) << (trial % 41);
    const IntPoint a = random_int_point(rng, bound), b = random_int_point(rng, bound);
    const IntPoint c = random_int_point(rng, bound), d = random_int_point(rng, bound);
    ASSERT_EQ(orient3d(to_point(a), to_point(b), to_point(c), to_point(d)),
              orient3d_reference(a, b, c, d))
        << "trial " << trial;
  }
}

// d = a + alpha (b - a) + beta (c - a) + (0 or a unit step): exactly coplanar or off the plane by
// the smallest integer amount, with products far beyond 53 bits so the filter cannot decide.
TEST(Orient3d, MatchesInt128ReferenceOnNearCoplanarIntegerPoints) {
  std::mt19937_64 rng(12);
  std::uniform_int_distribution<std::int64_t> weight(-2, 2);
  std::uniform_int_distribution<int> offset(-1, 1);
  std::uniform_int_distribution<int> axis(0, 2);
  int zeros = 0;
  for (int trial = 0; trial < 20000; ++trial) {
    const std::int64_t bound = std::int64_t(1) << 36;
    const IntPoint a = random_int_point(rng, bound), b = random_int_point(rng, bound);
    const IntPoint c = random_int_point(rng, bound);
    const std::int64_t alpha = weight(rng), beta = weight(rng);
    IntPoint d;
    for (int k = 0; k < 3; ++k) d[k] = a[k] + alpha * (b[k] - a[k]) + beta * (c[k] - a[k]);
    d[axis(rng)] += offset(rng);
    const int expected = orient3d_reference(a, b, c, d);
    zeros += expected == 0;
    ASSERT_EQ(orient3d(to_point(a), to_point(b), to_point(c), to_point(d)), expected)
        << "trial " << trial;
  }
  EXPECT_GT(zeros, 1000);  // the generator does produce exactly coplanar cases
}

// a, b, c on the plane y = 0 through (0.25, 0.25, 0.25) + span{(3, 5, 7), (9, 11, 13)}; d on a
// grid of steps of 2^-53 around (0.5, 0.5, 0.5). All differences from a are exact, so the exact
// determinant is 2^-53 · n · k for the small integer normal n = (-12, 24, -12). The naive double
// determinant rounds its products and gets some signs wrong; orient3d gets all of them right.
TEST(Orient3d, NaiveDeterminantFailsOnUlpGridWhereExactIsRight) {
  const Point a{0.25, 0.25, 0.25}, b{3.25, 5.25, 7.25}, c{9.25, 11.25, 13.25};
  int naive_wrong = 0;
  for (int i = 0; i < 16; ++i) {
    for (int j = 0; j < 16; ++j) {
      for (int k = 0; k < 16; ++k) {
        const Point d{0.5 + i * kUnit, 0.5 + j * kUnit, 0.5 + k * kUnit};
        const int expected = testing::sign_of(Int128(-12 * i + 24 * j - 12 * k));
        ASSERT_EQ(orient3d(a, b, c, d), expected) << i << " " << j << " " << k;
        naive_wrong += naive_orient3d(a, b, c, d) != expected;
      }
    }
  }
  EXPECT_GT(naive_wrong, 100);
}

// Points exactly on the plane z = x + y: x, y are multiples of 2^-52 in [0.5, 1), so their sum
// in [1, 2) is exact. Then the last point's z moved by one ulp: the determinant becomes
// ulp · n_z, with n_z the sign of orient2d of a, b, c in the (x, y) plane.
TEST(Orient3d, PlanePointsPerturbedByOneUlp) {
  std::mt19937_64 rng(13);
  std::uniform_int_distribution<std::int64_t> steps(0, (std::int64_t(1) << 51) - 1);
  const auto on_plane = [&]() {
    const double x = 0.5 + double(steps(rng)) * 0x1p-52;
    const double y = 0.5 + double(steps(rng)) * 0x1p-52;
    return Point{x, y, x + y};
  };
  int naive_nonzero = 0;
  for (int trial = 0; trial < 20000; ++trial) {
    const Point a = on_plane(), b = on_plane(), c = on_plane();
    Point d = on_plane();
    ASSERT_EQ(orient3d(a, b, c, d), 0) << "trial " << trial;
    naive_nonzero += naive_orient3d(a, b, c, d) != 0;
    const int n_z = orient2d_projected(a, b, c, 2);
    const bool up = trial % 2 == 0;
    d[2] = std::nextafter(d[2], up ? 100.0 : -100.0);
    ASSERT_EQ(orient3d(a, b, c, d), (up ? 1 : -1) * n_z) << "trial " << trial;
  }
  EXPECT_GT(naive_nonzero, 1000);
}

// Exactly coplanar points (on z = x + y, with x and y of 26 bits at a common random exponent so
// that the sum is exact) whose coordinates differ in magnitude by up to 2^40: the differences
// b - a are inexact, so the exact tiers must account for their rounding errors to find the
// exact 0, and the sign after moving d by one ulp.
TEST(Orient3d, ExactlyCoplanarPointsWithInexactDifferences) {
  std::mt19937_64 rng(17);
  std::uniform_int_distribution<std::int64_t> significand(-(std::int64_t(1) << 26), std::int64_t(1)
                                                                                        << 26);
  std::uniform_int_distribution<int> exponent(-30, 10);
  const auto on_plane = [&]() {
    const int e = exponent(rng);
    const double x = std::ldexp(double(significand(rng)), e);
    const double y = std::ldexp(double(significand(rng)), e);
    return Point{x, y, x + y};
  };
  int naive_nonzero = 0;
  for (int trial = 0; trial < 20000; ++trial) {
    const Point a = on_plane(), b = on_plane(), c = on_plane();
    Point d = on_plane();
    ASSERT_EQ(orient3d(a, b, c, d), 0) << "trial " << trial;
    naive_nonzero += naive_orient3d(a, b, c, d) != 0;
    const int n_z = orient2d_projected(a, b, c, 2);
    const bool up = trial % 2 == 0;
    d[2] = std::nextafter(d[2], up ? 1e300 : -1e300);
    ASSERT_EQ(orient3d(a, b, c, d), (up ? 1 : -1) * n_z) << "trial " << trial;
    ASSERT_EQ(orient3d(d, a, b, c), -(up ? 1 : -1) * n_z) << "trial " << trial;
  }
  EXPECT_GT(naive_nonzero, 1000);
}

// Every permutation of the four points multiplies the result by the permutation's sign, on
// configurations where the naive determinant is unreliable.
TEST(Orient3d, AntisymmetricUnderAllPermutationsOfNearDegenerateInputs) {
  std::mt19937_64 rng(14);
  std::uniform_real_distribution<double> weight(-2.0, 2.0);
  for (int trial = 0; trial < 3000; ++trial) {
    const std::array<Point, 4> points = [&] {
      const Point a = random_point(rng), b = random_point(rng), c = random_point(rng);
      return std::array<Point, 4>{a, b, c, near_plane_point(a, b, c, weight(rng), weight(rng))};
    }();
    const int base = orient3d(points[0], points[1], points[2], points[3]);
    std::array<int, 4> p = {0, 1, 2, 3};
    do {
      ASSERT_EQ(orient3d(points[p[0]], points[p[1]], points[p[2]], points[p[3]]),
                permutation_sign(p) * base)
          << "trial " << trial;
    } while (std::next_permutation(p.begin(), p.end()));
  }
}

// The expansion tier and the integer tier are independent exact evaluations of the same
// determinant; on near-degenerate inputs of many scales they must agree with each other and with
// the filtered entry point.
TEST(Orient3d, ExpansionAndIntegerTiersAgree) {
  std::mt19937_64 rng(15);
  std::uniform_real_distribution<double> weight(-3.0, 3.0);
  std::uniform_int_distribution<int> exponent(-200, 200);
  for (int trial = 0; trial < 30000; ++trial) {
    const double scale = std::ldexp(1.0, exponent(rng));
    const Point a = random_point(rng, -scale, scale), b = random_point(rng, -scale, scale);
    const Point c = random_point(rng, -scale, scale);
    Point d = near_plane_point(a, b, c, weight(rng), weight(rng));
    if (trial % 3 == 0) d[trial % 2] = std::nextafter(d[trial % 2], 0.0);
    const int expansion = predicates_internal::orient3d_expansion(a, b, c, d);
    ASSERT_EQ(expansion, predicates_internal::orient3d_integer(a, b, c, d)) << "trial " << trial;
    ASSERT_EQ(orient3d(a, b, c, d), expansion) << "trial " << trial;
  }
}

// Tiny (subnormal), huge and mixed-magnitude coordinates, where a naive evaluation underflows or
// overflows: the sign must equal that of the same integer configuration unscaled.
TEST(Orient3d, ExactForTinyHugeAndMixedMagnitudes) {
  std::mt19937_64 rng(16);
  for (int trial = 0; trial < 2000; ++trial) {
    const IntPoint a = random_int_point(rng, 600), b = random_int_point(rng, 600);
    const IntPoint c = random_int_point(rng, 600);
    IntPoint d;
    for (int k = 0; k < 3; ++k) d[k] = a[k] + (b[k] - a[k]) - (c[k] - a[k]) + (trial % 3 - 1);
    const int expected = orient3d_reference(a, b, c, d);
    for (const double scale : {0x1p-1064, 0x1p-600, 0x1p600, 0x1p1010}) {
      ASSERT_EQ(
          orient3d(to_point(a, scale), to_point(b, scale), to_point(c, scale), to_point(d, scale)),
          expected)
          << "trial " << trial << " scale " << scale;
    }
  }
  const Point origin{0, 0, 0};
  const Point huge_x{0x1p1000, 0, 0}, tiny_y{0, 0x1p-1000, 0};
  EXPECT_EQ(orient3d(origin, huge_x, tiny_y, Point{0, 0, 0x1p-1074}), 1);
  EXPECT_EQ(orient3d(origin, huge_x, tiny_y, Point{0x1p1000, 0x1p-1000, 0}), 0);
  EXPECT_EQ(naive_orient3d(origin, huge_x, tiny_y, Point{0, 0, 0x1p-1074}), 0);  // underflows
  // a = (F, -F, F) with F = 2^900, b = a + (0, 0, ulp), c = (1, 0, 0), d = (0, 1, 0):
  // det = ulp · ((1 - F)(1 + F) + F^2) = ulp > 0, while the naive products overflow.
  const double F = 0x1p900;
  const Point far{F, -F, F};
  const Point far_b{F, -F, std::nextafter(F, 0x1p1000)};
  EXPECT_EQ(orient3d(far, far_b, Point{1, 0, 0}, Point{0, 1, 0}), 1);
  EXPECT_EQ(naive_orient3d(far, far_b, Point{1, 0, 0}, Point{0, 1, 0}), 0);  // NaN
  EXPECT_EQ(predicates_internal::orient3d_integer(Point{0x1p-1074, 0, 0}, Point{0, 0x1p-1074, 0},
                                                  Point{0, 0, 0x1p-1074}, Point{0, 0, 0}),
            -1);
}

// Orient3dPlane must be orient3d itself, only cheaper: same sign on random, exactly coplanar,
// one-ulp-off and tiny/huge configurations (where its own filter cannot decide).
TEST(Orient3dPlane, EqualsOrient3dOnNearDegenerateInputsOfAllScales) {
  std::mt19937_64 rng(18);
  std::uniform_real_distribution<double> weight(-3.0, 3.0);
  std::uniform_int_distribution<int> exponent(-200, 200);
  int naive_wrong = 0;  // cases the double determinant gets wrong: the exact path decides
  for (int trial = 0; trial < 30000; ++trial) {
    const double scale = std::ldexp(1.0, exponent(rng));
    const Point a = random_point(rng, -scale, scale), b = random_point(rng, -scale, scale);
    const Point c = random_point(rng, -scale, scale);
    const Orient3dPlane plane(a, b, c);
    for (int k = 0; k < 4; ++k) {
      Point d = k == 0 ? random_point(rng, -scale, scale)
                       : near_plane_point(a, b, c, weight(rng), weight(rng));
      if (k == 2) d[trial % 3] = std::nextafter(d[trial % 3], 0.0);
      const int expected = orient3d(a, b, c, d);
      naive_wrong += naive_orient3d(a, b, c, d) != expected;
      ASSERT_EQ(plane.side(d), expected) << "trial " << trial << " point " << k;
    }
  }
  EXPECT_GT(naive_wrong, 100);
}

TEST(Orient3dPlane, MatchesInt128ReferenceOnNearCoplanarAndScaledIntegerPoints) {
  std::mt19937_64 rng(19);
  std::uniform_int_distribution<std::int64_t> weight(-2, 2);
  std::uniform_int_distribution<int> offset(-1, 1);
  for (int trial = 0; trial < 20000; ++trial) {
    const std::int64_t bound = std::int64_t(1) << (trial % 2 == 0 ? 36 : 9);
    const IntPoint a = random_int_point(rng, bound), b = random_int_point(rng, bound);
    const IntPoint c = random_int_point(rng, bound);
    const std::int64_t alpha = weight(rng), beta = weight(rng);
    IntPoint d;
    for (int k = 0; k < 3; ++k) d[k] = a[k] + alpha * (b[k] - a[k]) + beta * (c[k] - a[k]);
    d[trial % 3] += offset(rng);
    const int expected = orient3d_reference(a, b, c, d);
    const double scale = trial % 2 == 0 ? 1.0 : (trial % 4 == 1 ? 0x1p-1064 : 0x1p1000);
    const Orient3dPlane plane(to_point(a, scale), to_point(b, scale), to_point(c, scale));
    ASSERT_EQ(plane.side(to_point(d, scale)), expected) << "trial " << trial;
  }
  // The ulp grid of NaiveDeterminantFailsOnUlpGridWhereExactIsRight.
  const Orient3dPlane plane(Point{0.25, 0.25, 0.25}, Point{3.25, 5.25, 7.25},
                            Point{9.25, 11.25, 13.25});
  for (int i = 0; i < 16; ++i)
    for (int j = 0; j < 16; ++j)
      for (int k = 0; k < 16; ++k)
        ASSERT_EQ(plane.side(Point{0.5 + i * kUnit, 0.5 + j * kUnit, 0.5 + k * kUnit}),
                  testing::sign_of(Int128(-12 * i + 24 * j - 12 * k)));
}

// ----- orient2d and relatives ------------------------------------------------------------------

TEST(Orient2d, CounterClockwiseIsPositive) {
  const double a[2] = {0, 0}, b[2] = {1, 0}, c[2] = {0, 1}, d[2] = {2, 0};
  EXPECT_EQ(orient2d(a, b, c), 1);
  EXPECT_EQ(orient2d(a, c, b), -1);
  EXPECT_EQ(orient2d(a, b, d), 0);
}

TEST(Orient2d, MatchesInt128ReferenceOnRandomIntegerPoints) {
  std::mt19937_64 rng(21);
  for (int trial = 0; trial < 20000; ++trial) {
    const std::int64_t bound = std::int64_t(1) << (trial % 60);
    std::uniform_int_distribution<std::int64_t> coordinate(-bound, bound);
    std::int64_t v[6];
    for (std::int64_t& x : v) x = coordinate(rng);
    if (trial % 2 == 0) {  // c = a + 2 (b - a), moved by at most one unit: (nearly) collinear
      v[4] = v[0] + 2 * (v[2] - v[0]) + (trial % 3 - 1);
      v[5] = v[1] + 2 * (v[3] - v[1]);
    }
    // Integers up to 2^53 are exact doubles; larger ones are rounded, so compare against the
    // rounded values.
    double d[6];
    for (int k = 0; k < 6; ++k) {
      d[k] = double(v[k]);
      v[k] = std::int64_t(d[k]);
    }
    ASSERT_EQ(orient2d(d, d + 2, d + 4), orient2d_reference(v[0], v[1], v[2], v[3], v[4], v[5]))
        << "trial " << trial;
  }
}

// Shewchuk's classic example: a = (0.5 + i u, 0.5 + j u) with u = 2^-53, b = (12, 12),
// c = (24, 24). In units of u every coordinate is an integer below 2^58, so Int128 gives the
// exact sign; the naive determinant gets many of them wrong.
TEST(Orient2d, NaiveDeterminantFailsOnShewchukGridWhereExactIsRight) {
  const double b[2] = {12, 12}, c[2] = {24, 24};
  const std::int64_t b_units = std::int64_t(12) << 53, c_units = std::int64_t(24) << 53;
  int naive_wrong = 0;
  for (int i = 0; i < 256; ++i) {
    for (int j = 0; j < 256; ++j) {
      const double a[2] = {0.5 + i * kUnit, 0.5 + j * kUnit};
      const std::int64_t half = std::int64_t(1) << 52;
      const int expected =
          orient2d_reference(half + i, half + j, b_units, b_units, c_units, c_units);
      ASSERT_EQ(orient2d(a, b, c), expected) << i << " " << j;
      naive_wrong += naive_orient2d(a, b, c) != expected;
    }
  }
  EXPECT_GT(naive_wrong, 1000);
}

TEST(Orient2d, ExpansionAndIntegerTiersAgreeAndCyclicSymmetry) {
  std::mt19937_64 rng(22);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  std::uniform_int_distribution<int> exponent(-400, 400);
  for (int trial = 0; trial < 30000; ++trial) {
    const double scale = std::ldexp(1.0, exponent(rng));
    const double a[2] = {unit(rng) * scale, unit(rng) * scale};
    const double b[2] = {unit(rng) * scale, unit(rng) * scale};
    const double t = unit(rng) * 3.0;
    const double c[2] = {a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1])};
    const int expansion = predicates_internal::orient2d_expansion(a, b, c);
    ASSERT_EQ(expansion, predicates_internal::orient2d_integer(a, b, c)) << "trial " << trial;
    ASSERT_EQ(orient2d(a, b, c), expansion);
    ASSERT_EQ(orient2d(b, c, a), expansion);
    ASSERT_EQ(orient2d(b, a, c), -expansion);
  }
}

TEST(Orient2d, ExactForSubnormalAndHugeCoordinates) {
  const double a[2] = {0, 0}, b[2] = {0x1p-1074, 0}, c[2] = {0, 0x1p-1074};
  EXPECT_EQ(orient2d(a, b, c), 1);
  EXPECT_EQ(naive_orient2d(a, b, c), 0);  // the product underflows
  const double d[2] = {-0x1p1023, -0x1p1023}, e[2] = {0x1p1023, 0x1p1023};
  const double f[2] = {0x1p1023, std::nextafter(0x1p1023, 0.0)};
  EXPECT_EQ(orient2d(d, e, f), -1);
  EXPECT_EQ(orient2d(d, e, Point{0, 0}.data()), 0);
}

TEST(Orient2dProjected, HasTheSignOfTheNormalComponent) {
  const Point a{0, 0, 0}, b{1, 0, 0}, c{0, 1, 0};  // normal +z
  EXPECT_EQ(orient2d_projected(a, b, c, 2), 1);
  EXPECT_EQ(orient2d_projected(a, b, c, 0), 0);
  EXPECT_EQ(orient2d_projected(a, b, c, 1), 0);
  const Point p{0, 0, 0}, q{0, 1, 0}, r{0, 0, 1};  // normal +x
  EXPECT_EQ(orient2d_projected(p, q, r, 0), 1);
  const Point s{0, 0, 0}, t{0, 0, 1}, u{1, 0, 0};  // normal +y
  EXPECT_EQ(orient2d_projected(s, t, u, 1), 1);
  EXPECT_EQ(orient2d_projected(s, u, t, 1), -1);
}

TEST(Collinear, DetectsExactCollinearityOnly) {
  const Point a{0.1, 0.2, 0.3};
  const Point twice_a{0.2, 0.4, 0.6};  // 2a exactly: doubling is exact
  EXPECT_TRUE(collinear(Point{0, 0, 0}, a, twice_a));
  EXPECT_TRUE(collinear(Point{0, 0, 0}, Point{1, 2, 3}, Point{2, 4, 6}));
  EXPECT_TRUE(collinear(a, a, Point{5, 5, 5}));
  EXPECT_TRUE(collinear(a, a, a));
  EXPECT_FALSE(collinear(Point{0, 0, 0}, Point{1, 2, 3}, Point{2, 4, std::nextafter(6.0, 7.0)}));
  EXPECT_FALSE(collinear(Point{0, 0, 0}, a, Point{0.2, 0.4, std::nextafter(0.6, 1.0)}));
}

// ----- insphere ----------------------------------------------------------------------------------

TEST(Insphere, InsideIsPositiveForPositiveTet) {
  const Point a{0, 0, 0}, b{1, 0, 0}, c{0, 1, 0}, d{0, 0, 1};
  EXPECT_EQ(insphere(a, b, c, d, Point{0.25, 0.25, 0.25}), 1);
  EXPECT_EQ(insphere(a, b, c, d, Point{1, 1, 1}), 0);  // on the sphere, center (.5, .5, .5)
  EXPECT_EQ(insphere(a, b, c, d, Point{2, 2, 2}), -1);
  EXPECT_EQ(insphere(b, a, c, d, Point{0.25, 0.25, 0.25}), -1);  // negative tet flips the sign
}

TEST(Insphere, MatchesInt128ReferenceOnRandomIntegerPoints) {
  std::mt19937_64 rng(31);
  for (int trial = 0; trial < 20000; ++trial) {
    const std::int64_t bound = std::int64_t(1) << (1 + trial % 19);
    IntPoint p[5];
    for (IntPoint& x : p) x = random_int_point(rng, bound);
    ASSERT_EQ(
        insphere(to_point(p[0]), to_point(p[1]), to_point(p[2]), to_point(p[3]), to_point(p[4])),
        testing::insphere_reference(p[0], p[1], p[2], p[3], p[4]))
        << "trial " << trial;
  }
}

// Lattice points on the sphere x^2 + y^2 + z^2 = 15^2.
std::vector<IntPoint> sphere_lattice_points() {
  std::vector<IntPoint> points;
  for (int x = -15; x <= 15; ++x) {
    for (int y = -15; y <= 15; ++y) {
      for (int z = -15; z <= 15; ++z) {
        if (x * x + y * y + z * z == 225) points.push_back({x, y, z});
      }
    }
  }
  return points;
}

// Cospherical points, scaled by a power of two and translated by a dyadic offset (both exact),
// give exactly 0; moving the fifth point by one ulp along x gives the sign that the motion
// towards or away from the center implies, times the tet's orientation.
TEST(Insphere, CosphericalIsZeroAndOneUlpPerturbationDecides) {
  const std::vector<IntPoint> lattice = sphere_lattice_points();
  ASSERT_GT(lattice.size(), 50u);
  std::mt19937_64 rng(32);
  std::uniform_int_distribution<std::size_t> pick(0, lattice.size() - 1);
  const Point center{0.375, -1.5, 1024.125};
  int checked = 0;
  for (const double scale : {1.0, 0x1p-20, 0x1p-1040, 0x1p900}) {
    const auto place = [&](const IntPoint& p) {
      const Point shift = scale < 0x1p-100 || scale > 0x1p100 ? Point{0, 0, 0} : center;
      return Point{p[0] * scale + shift[0], p[1] * scale + shift[1], p[2] * scale + shift[2]};
    };
    for (int trial = 0; trial < 500; ++trial) {
      const IntPoint ia = lattice[pick(rng)], ib = lattice[pick(rng)], ic = lattice[pick(rng)];
      const IntPoint id = lattice[pick(rng)], ie = lattice[pick(rng)];
      const Point a = place(ia), b = place(ib), c = place(ic), d = place(id);
      Point e = place(ie);
      ASSERT_EQ(insphere(a, b, c, d, e), 0) << "scale " << scale << " trial " << trial;
      const int orientation = orient3d(a, b, c, d);
      if (orientation == 0 || ie[0] == 0) continue;
      e[0] = std::nextafter(e[0], 1e308);  // towards +x: inside iff the point is on the -x side
      const int expected = orientation * (ie[0] < 0 ? 1 : -1);
      ASSERT_EQ(insphere(a, b, c, d, e), expected) << "scale " << scale << " trial " << trial;
      ++checked;
    }
  }
  EXPECT_GT(checked, 1000);
}

TEST(Insphere, SwappingTwoTetVerticesNegates) {
  std::mt19937_64 rng(33);
  for (int trial = 0; trial < 3000; ++trial) {
    const Point a = random_point(rng), b = random_point(rng), c = random_point(rng);
    const Point d = random_point(rng), e = random_point(rng);
    const int base = insphere(a, b, c, d, e);
    ASSERT_EQ(insphere(b, a, c, d, e), -base);
    ASSERT_EQ(insphere(a, c, b, d, e), -base);
    ASSERT_EQ(insphere(a, b, d, c, e), -base);
    ASSERT_EQ(insphere(d, b, c, a, e), -base);
  }
}

// Points on the unit sphere (normalized, so off it by rounding): all three tiers must agree.
TEST(Insphere, FilterExpansionAndIntegerTiersAgreeOnNearCosphericalPoints) {
  std::mt19937_64 rng(34);
  std::normal_distribution<double> gaussian;
  const auto on_unit_sphere = [&]() {
    Point p{gaussian(rng), gaussian(rng), gaussian(rng)};
    const double length = std::sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]);
    for (double& x : p) x /= length;
    return p;
  };
  int undecided_by_filter = 0;
  for (int trial = 0; trial < 5000; ++trial) {
    const Point a = on_unit_sphere(), b = on_unit_sphere(), c = on_unit_sphere();
    const Point d = on_unit_sphere(), e = on_unit_sphere();
    const int expansion = predicates_internal::insphere_expansion(a, b, c, d, e);
    ASSERT_EQ(expansion, predicates_internal::insphere_integer(a, b, c, d, e)) << "trial " << trial;
    ASSERT_EQ(insphere(a, b, c, d, e), expansion) << "trial " << trial;
    const auto filtered = predicates_internal::insphere_filtered(a, b, c, d, e);
    if (filtered) {
      ASSERT_EQ(*filtered, expansion);
    } else {
      ++undecided_by_filter;
    }
  }
  EXPECT_GT(undecided_by_filter, 0);  // the exact tiers were exercised
}

}  // namespace
}  // namespace afmesh
