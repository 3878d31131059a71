// Decay laws of the sources (paper eq. 10–13): the size as a function of the distance r to the
// source.
//
// One inline evaluation shared by every caller (single points, vector blocks, pruning bounds),
// so that a source's size at a point is the same double whichever path computes it.
// Each law is non-decreasing in rho for the parameters validate_size_spec accepts, and so is its
// floating-point evaluation up to the last bit of std::pow / std::exp.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <span>

#include "core/sizing/size_spec.h"

namespace afmesh {

enum class LawKind : std::uint8_t { kPower, kExponential, kPolynomial };

// rho = max(0, (r - r0) / r1) (eq. 10), capped at the largest finite double so that every law
// stays a number (0 · rho is then 0, not NaN) even for an enormous r / r1.
inline double scaled_distance(double r, double r0, double r1) {
  const double rho = std::max(0.0, (r - r0) / r1);
  return std::min(rho, std::numeric_limits<double>::max());
}

// The size at rho of one law: eq. 11 (kPower, exponent gamma), eq. 12 (kExponential, rate gamma)
// or eq. 13 (kPolynomial, coefficients [a_1, ..., a_n] by Horner's rule). May be +inf far away.
inline double law_size(LawKind kind, double delta0, double gamma,
                       std::span<const double> coefficients, double rho) {
  switch (kind) {
    case LawKind::kPower:
      return delta0 * (1.0 + std::pow(rho, gamma));
    case LawKind::kExponential:
      return delta0 * std::exp(gamma * rho);
    case LawKind::kPolynomial: {
      double sum = 0.0;  // a_1 + a_2 rho + ... + a_n rho^(n-1)
      for (std::size_t i = coefficients.size(); i-- > 0;) sum = sum * rho + coefficients[i];
      return delta0 * (1.0 + sum * rho);
    }
  }
  return std::numeric_limits<double>::quiet_NaN();
}

// The size of a (validated) source at distance r from it: law_size of its law at
// scaled_distance(r, r0, r1). Equal, bit for bit, to what SpecSizeField computes from r.
double decay_size(const SizeSource& source, double r);

}  // namespace afmesh
