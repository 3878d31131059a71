// BigInteger: a signed integer of unbounded size, with just the operations the predicates'
// last-resort tier needs (construction from a scaled double, +, -, ×, sign).
//
// Why it exists: expansion arithmetic (expansion.h) is exact only while no product underflows or
// overflows, which holds for coordinates of moderate magnitude but not for every finite double
// (e.g. 1e-300 next to 1e+300). Every finite double is an integer multiple of 2^-1074, so after
// scaling all inputs of a predicate by a common power of two they become integers of at most
// ~2150 bits, and the determinant's sign is the sign of an integer polynomial in them. Such inputs
// are rare in meshing, so this tier favours simplicity over speed (schoolbook multiplication).
#pragma once

#include <cstdint>
#include <vector>

namespace afmesh {

class BigInteger {
 public:
  BigInteger() = default;  // zero

  // The integer x · 2^(-exponent_base). Requires a finite x whose lowest set bit has exponent
  // >= exponent_base (use lowest_bit_exponent below), so that the result is an integer.
  static BigInteger from_scaled_double(double x, int exponent_base);

  // Exponent of the lowest set bit of a finite nonzero x: x is an odd integer times 2^result.
  static int lowest_bit_exponent(double x);

  // The integer value of a (small) int64, for tests and constants.
  static BigInteger from_int64(std::int64_t value);

  int sign() const { return sign_; }  // -1, 0 or +1
  int bit_length() const;             // of the magnitude; 0 for zero

  BigInteger operator-() const;
  friend BigInteger operator+(const BigInteger& a, const BigInteger& b);
  friend BigInteger operator-(const BigInteger& a, const BigInteger& b);
  friend BigInteger operator*(const BigInteger& a, const BigInteger& b);
  friend bool operator==(const BigInteger& a, const BigInteger& b) = default;

 private:
  using Limbs = std::vector<std::uint32_t>;  // little-endian base 2^32, no high zero limbs

  static BigInteger from_magnitude(int sign, Limbs magnitude);

  int sign_ = 0;
  Limbs magnitude_;  // empty for zero
};

}  // namespace afmesh
