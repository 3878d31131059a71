#include "core/geometry/expansion.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <random>
#include <span>
#include <vector>

#include "core/geometry/big_integer.h"
#include "tests/geometry/test_support.h"

namespace afmesh::expansion {
namespace {

using afmesh::testing::Int128;

// The exact value of an expansion whose components are integers (|value| < 2^126).
Int128 integer_value(std::span<const double> e) {
  Int128 total = 0;
  for (const double x : e) total += Int128(x);
  return total;
}

// The documented invariants: no zeros, increasing magnitude, and nonoverlapping: each component's
// lowest set bit lies above the previous component's highest set bit.
void expect_valid_expansion(std::span<const double> e) {
  for (std::size_t i = 0; i < e.size(); ++i) {
    ASSERT_NE(e[i], 0.0) << "component " << i;
    if (i == 0) continue;
    ASSERT_GT(BigInteger::lowest_bit_exponent(e[i]), std::ilogb(e[i - 1])) << "component " << i;
  }
}

double random_integer_double(std::mt19937_64& rng, int bits) {
  std::uniform_int_distribution<std::int64_t> value(-(std::int64_t(1) << bits), std::int64_t(1)
                                                                                    << bits);
  return double(value(rng));
}

TEST(Expansion, TwoSumAndTwoProductAreErrorFree) {
  std::mt19937_64 rng(51);
  for (int trial = 0; trial < 20000; ++trial) {
    const double a = random_integer_double(rng, 62), b = random_integer_double(rng, 1 + trial % 40);
    const Pair s = two_sum(a, b);
    ASSERT_EQ(s.hi, a + b);
    ASSERT_EQ(Int128(s.hi) + Int128(s.lo), Int128(a) + Int128(b));
    ASSERT_EQ(two_difference(a, b).hi, a - b);
    ASSERT_EQ(Int128(two_difference(a, b).hi) + Int128(two_difference(a, b).lo),
              Int128(a) - Int128(b));
    const double c = random_integer_double(rng, 53), d = random_integer_double(rng, 53);
    const Pair p = two_product(c, d);
    ASSERT_EQ(p.hi, c * d);
    ASSERT_EQ(Int128(p.hi) + Int128(p.lo), Int128(c) * Int128(d));
    if (std::fabs(a) >= std::fabs(b)) {
      const Pair f = fast_two_sum(a, b);
      ASSERT_EQ(f.hi, s.hi);
      ASSERT_EQ(f.lo, s.lo);
    }
  }
}

// Expansions grown by summing many integers of mixed sizes: sums, differences and products stay
// exact and keep the invariants.
TEST(Expansion, SumScaleAndProductAreExact) {
  std::mt19937_64 rng(52);
  for (int trial = 0; trial < 3000; ++trial) {
    Expansion<16> e;
    Expansion<16> f;
    Int128 e_value = 0;
    Int128 f_value = 0;
    for (int k = 0; k < 8; ++k) {
      const double x = random_integer_double(rng, 1 + (k * 7 + trial) % 55);
      const double y = random_integer_double(rng, 1 + (k * 5 + trial) % 55);
      const Expansion<17> e_next = e + Expansion<1>(x);
      const Expansion<17> f_next = f - Expansion<1>(y);
      ASSERT_LE(e_next.size(), 16);
      ASSERT_LE(f_next.size(), 16);
      e = Expansion<16>();
      f = Expansion<16>();
      std::copy(e_next.components().begin(), e_next.components().end(), e.data());
      e.resize(e_next.size());
      std::copy(f_next.components().begin(), f_next.components().end(), f.data());
      f.resize(f_next.size());
      e_value += Int128(x);
      f_value -= Int128(y);
    }
    expect_valid_expansion(e.components());
    ASSERT_EQ(integer_value(e.components()), e_value);
    ASSERT_EQ(e.sign(), afmesh::testing::sign_of(e_value));

    const Expansion<32> total = e + f;
    expect_valid_expansion(total.components());
    ASSERT_EQ(integer_value(total.components()), e_value + f_value);

    const Expansion<32> difference = e - e;
    ASSERT_EQ(difference.size(), 0);
    ASSERT_EQ(difference.sign(), 0);

    const double factor = random_integer_double(rng, 40);
    Expansion<32> scaled;
    scaled.resize(scale(e.components(), factor, scaled.data()));
    expect_valid_expansion(scaled.components());
    ASSERT_EQ(integer_value(scaled.components()), e_value * Int128(factor));
  }
}

TEST(Expansion, ProductOfExactDifferencesIsExact) {
  std::mt19937_64 rng(53);
  for (int trial = 0; trial < 20000; ++trial) {
    const double a = random_integer_double(rng, 60), b = random_integer_double(rng, 1 + trial % 20);
    const double c = random_integer_double(rng, 60), d = random_integer_double(rng, 1 + trial % 20);
    const Expansion<2> ab = exact_difference(a, b);
    const Expansion<2> cd = exact_difference(c, d);
    const Expansion<8> product = ab * cd;
    expect_valid_expansion(product.components());
    ASSERT_EQ(integer_value(product.components()),
              (Int128(a) - Int128(b)) * (Int128(c) - Int128(d)));
  }
}

TEST(Expansion, EstimateIsTheRoundedValue) {
  const Expansion<2> e(two_sum(1.0, 0x1p-60));
  EXPECT_EQ(e.size(), 2);
  EXPECT_EQ(e.estimate(), 1.0);
  EXPECT_EQ(Expansion<1>(0.0).size(), 0);
  EXPECT_EQ(Expansion<1>(-3.0).sign(), -1);
}

}  // namespace
}  // namespace afmesh::expansion
