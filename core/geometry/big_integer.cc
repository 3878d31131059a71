#include "core/geometry/big_integer.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstddef>
#include <utility>

namespace afmesh {
namespace {

using Limbs = std::vector<std::uint32_t>;

void trim(Limbs& limbs) {
  while (!limbs.empty() && limbs.back() == 0) limbs.pop_back();
}

// -1, 0, +1 as |a| <, ==, > |b| (both trimmed).
int compare_magnitudes(const Limbs& a, const Limbs& b) {
  if (a.size() != b.size()) return a.size() < b.size() ? -1 : 1;
  for (std::size_t i = a.size(); i-- > 0;) {
    if (a[i] != b[i]) return a[i] < b[i] ? -1 : 1;
  }
  return 0;
}

Limbs add_magnitudes(const Limbs& a, const Limbs& b) {
  const Limbs& longer = a.size() >= b.size() ? a : b;
  const Limbs& shorter = a.size() >= b.size() ? b : a;
  Limbs result(longer.size() + 1);
  std::uint64_t carry = 0;
  for (std::size_t i = 0; i < longer.size(); ++i) {
    const std::uint64_t t =
        std::uint64_t(longer[i]) + (i < shorter.size() ? shorter[i] : 0) + carry;
    result[i] = std::uint32_t(t);
    carry = t >> 32;
  }
  result[longer.size()] = std::uint32_t(carry);
  trim(result);
  return result;
}

// |a| - |b|, requires |a| >= |b|.
Limbs subtract_magnitudes(const Limbs& a, const Limbs& b) {
  Limbs result(a.size());
  std::int64_t borrow = 0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    std::int64_t t = std::int64_t(a[i]) - (i < b.size() ? std::int64_t(b[i]) : 0) - borrow;
    borrow = t < 0 ? 1 : 0;
    if (t < 0) t += std::int64_t(1) << 32;
    result[i] = std::uint32_t(t);
  }
  trim(result);
  return result;
}

// Schoolbook product; each step's sum fits in 64 bits: (2^32-1)^2 + 2 (2^32-1) = 2^64 - 1.
Limbs multiply_magnitudes(const Limbs& a, const Limbs& b) {
  if (a.empty() || b.empty()) return {};
  Limbs result(a.size() + b.size(), 0);
  for (std::size_t i = 0; i < a.size(); ++i) {
    std::uint64_t carry = 0;
    for (std::size_t j = 0; j < b.size(); ++j) {
      const std::uint64_t t = std::uint64_t(a[i]) * b[j] + result[i + j] + carry;
      result[i + j] = std::uint32_t(t);
      carry = t >> 32;
    }
    result[i + b.size()] = std::uint32_t(carry);
  }
  trim(result);
  return result;
}

// |x| = significand · 2^exponent with an odd integer significand below 2^53 (x nonzero).
std::pair<std::uint64_t, int> odd_significand(double x) {
  int exponent = 0;
  const double fraction = std::frexp(std::fabs(x), &exponent);  // in [0.5, 1)
  const auto significand = std::uint64_t(std::ldexp(fraction, 53));
  const int trailing_zeros = std::countr_zero(significand);
  return {significand >> trailing_zeros, exponent - 53 + trailing_zeros};
}

}  // namespace

int BigInteger::lowest_bit_exponent(double x) { return odd_significand(x).second; }

BigInteger BigInteger::from_scaled_double(double x, int exponent_base) {
  if (x == 0.0) return {};
  const auto [significand, exponent] = odd_significand(x);
  const int shift = exponent - exponent_base;
  const int whole_limbs = shift / 32;
  const int bits = shift % 32;
  // significand << bits spans at most three limbs (53 + 31 bits).
  const std::uint64_t low = significand & 0xffffffffu;
  const std::uint64_t high = significand >> 32;
  Limbs magnitude(std::size_t(whole_limbs) + 3, 0);
  magnitude[whole_limbs] = std::uint32_t(low << bits);
  magnitude[whole_limbs + 1] = std::uint32_t((high << bits) | (bits > 0 ? low >> (32 - bits) : 0));
  magnitude[whole_limbs + 2] = std::uint32_t(bits > 0 ? high >> (32 - bits) : 0);
  trim(magnitude);
  return from_magnitude(x < 0.0 ? -1 : 1, std::move(magnitude));
}

BigInteger BigInteger::from_int64(std::int64_t value) {
  if (value == 0) return {};
  // Negate in unsigned arithmetic so INT64_MIN is handled.
  const std::uint64_t magnitude = value < 0 ? ~std::uint64_t(value) + 1 : std::uint64_t(value);
  Limbs limbs = {std::uint32_t(magnitude), std::uint32_t(magnitude >> 32)};
  trim(limbs);
  return from_magnitude(value < 0 ? -1 : 1, std::move(limbs));
}

BigInteger BigInteger::from_magnitude(int sign, Limbs magnitude) {
  BigInteger result;
  if (!magnitude.empty()) {
    result.sign_ = sign;
    result.magnitude_ = std::move(magnitude);
  }
  return result;
}

int BigInteger::bit_length() const {
  if (magnitude_.empty()) return 0;
  return 32 * int(magnitude_.size() - 1) + std::bit_width(magnitude_.back());
}

BigInteger BigInteger::operator-() const {
  BigInteger negated = *this;
  negated.sign_ = -sign_;
  return negated;
}

BigInteger operator+(const BigInteger& a, const BigInteger& b) {
  if (a.sign_ == 0) return b;
  if (b.sign_ == 0) return a;
  if (a.sign_ == b.sign_) {
    return BigInteger::from_magnitude(a.sign_, add_magnitudes(a.magnitude_, b.magnitude_));
  }
  const int order = compare_magnitudes(a.magnitude_, b.magnitude_);
  if (order == 0) return {};
  if (order > 0) {
    return BigInteger::from_magnitude(a.sign_, subtract_magnitudes(a.magnitude_, b.magnitude_));
  }
  return BigInteger::from_magnitude(b.sign_, subtract_magnitudes(b.magnitude_, a.magnitude_));
}

BigInteger operator-(const BigInteger& a, const BigInteger& b) { return a + (-b); }

BigInteger operator*(const BigInteger& a, const BigInteger& b) {
  return BigInteger::from_magnitude(a.sign_ * b.sign_,
                                    multiply_magnitudes(a.magnitude_, b.magnitude_));
}

}  // namespace afmesh
