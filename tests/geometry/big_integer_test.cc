#include "core/geometry/big_integer.h"

#include <gtest/gtest.h>

#include <cfloat>
#include <cmath>
#include <cstdint>
#include <random>

#include "tests/geometry/test_support.h"

namespace afmesh {
namespace {

using testing::Int128;
using testing::UInt128;

// The BigInteger equal to an Int128, assembled from 32-bit pieces.
BigInteger from_int128(Int128 value) {
  const bool negative = value < 0;
  const UInt128 magnitude = negative ? -UInt128(value) : UInt128(value);
  const BigInteger limb_base = BigInteger::from_int64(std::int64_t(1) << 32);
  BigInteger result;
  for (int shift = 96; shift >= 0; shift -= 32) {
    result = result * limb_base +
             BigInteger::from_int64(std::int64_t((magnitude >> shift) & 0xffffffffu));
  }
  return negative ? -result : result;
}

TEST(BigInteger, ArithmeticMatchesInt128) {
  std::mt19937_64 rng(41);
  std::uniform_int_distribution<std::int64_t> value(INT64_MIN, INT64_MAX);
  for (int trial = 0; trial < 20000; ++trial) {
    const std::int64_t shift = trial % 63;
    const std::int64_t a = value(rng) >> shift, b = value(rng) >> (62 - shift);
    const std::int64_t c = value(rng) >> shift, d = value(rng) >> (62 - shift);
    const Int128 expected = Int128(a) * b - Int128(c) * d;
    const BigInteger got = BigInteger::from_int64(a) * BigInteger::from_int64(b) -
                           BigInteger::from_int64(c) * BigInteger::from_int64(d);
    ASSERT_EQ(got, from_int128(expected)) << "trial " << trial;
    ASSERT_EQ(got.sign(), testing::sign_of(expected));
    ASSERT_EQ((BigInteger::from_int64(a) + BigInteger::from_int64(c)), from_int128(Int128(a) + c));
  }
}

TEST(BigInteger, ScaledDoublesAreExactIntegers) {
  EXPECT_EQ(BigInteger::from_scaled_double(3.0, 0), BigInteger::from_int64(3));
  EXPECT_EQ(BigInteger::from_scaled_double(0.75, -2), BigInteger::from_int64(3));
  EXPECT_EQ(BigInteger::from_scaled_double(-0x1p-1074, -1074), BigInteger::from_int64(-1));
  EXPECT_EQ(BigInteger::from_scaled_double(96.0, 3), BigInteger::from_int64(12));
  EXPECT_EQ(BigInteger::from_scaled_double(0.0, -7).sign(), 0);
  EXPECT_EQ(BigInteger::from_scaled_double(DBL_MAX, -1074).bit_length(), 1024 + 1074);
  EXPECT_EQ(BigInteger::from_scaled_double(DBL_MAX, 971).bit_length(), 53);
}

TEST(BigInteger, LowestBitExponent) {
  EXPECT_EQ(BigInteger::lowest_bit_exponent(1.0), 0);
  EXPECT_EQ(BigInteger::lowest_bit_exponent(-0.5), -1);
  EXPECT_EQ(BigInteger::lowest_bit_exponent(3.0 * 1024), 10);
  EXPECT_EQ(BigInteger::lowest_bit_exponent(0x1p-1074), -1074);
  EXPECT_EQ(BigInteger::lowest_bit_exponent(DBL_MAX), 971);
  EXPECT_EQ(BigInteger::lowest_bit_exponent(0.1), -55);  // 0.1 = 0xccccccccccccd · 2^-55
}

// (x + y)(x - y) == x^2 - y^2 for integers of thousands of bits.
TEST(BigInteger, AlgebraicIdentityOnHugeValues) {
  std::mt19937_64 rng(42);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  std::uniform_int_distribution<int> exponent(-1000, 1000);
  for (int trial = 0; trial < 500; ++trial) {
    const double x = std::ldexp(unit(rng), exponent(rng));
    const double y = std::ldexp(unit(rng), exponent(rng));
    const int base =
        std::min(BigInteger::lowest_bit_exponent(x), BigInteger::lowest_bit_exponent(y));
    const BigInteger X = BigInteger::from_scaled_double(x, base);
    const BigInteger Y = BigInteger::from_scaled_double(y, base);
    ASSERT_EQ((X + Y) * (X - Y), X * X - Y * Y);
    ASSERT_EQ((X - Y) + Y, X);
    ASSERT_EQ((X * Y).sign(), (x > 0 ? 1 : -1) * (y > 0 ? 1 : -1));
  }
}

}  // namespace
}  // namespace afmesh
