// The exact tiers behind predicates.h, exposed for the filters' out-of-line fallbacks and for
// tests that check the tiers against each other. Mesh code calls predicates.h instead.
//
// Tier 1 (filter, predicates.h / insphere in predicates.cc): double evaluation plus a forward
//   error bound; returns when the bound proves the sign.
// Tier 2 (expansion): the same determinant in floating-point expansion arithmetic
//   (expansion.h), starting from the exact coordinate differences. Exact when every input
//   coordinate is 0 or has magnitude within the tier's range below, which rules out overflow and
//   underflow of every product the formula forms.
// Tier 3 (integer): every coordinate scaled by one power of two into an integer (BigInteger),
//   then the same polynomial in integer arithmetic. Exact for all finite doubles; used only for
//   inputs outside tier 2's range.
//
// Each function returns the same sign as its public counterpart in predicates.h.
#pragma once

#include <optional>

#include "core/geometry/predicates.h"

namespace afmesh::predicates_internal {

// Magnitude range [min, max] within which tier 2 is exact. The determinant of degree k in the
// coordinate differences is evaluated exactly when (a) the lowest set bit of every coordinate,
// at least min * 2^-52, raised to the k-th power stays >= 2^-1074 (no product error underflows),
// and (b) k-fold products of differences (<= 2 max) stay far below 2^1024 (nothing overflows).
struct ExpansionRange {
  double min;
  double max;
};
inline constexpr ExpansionRange kOrient2dRange = {0x1p-480, 0x1p480};  // degree 2
inline constexpr ExpansionRange kOrient3dRange = {0x1p-300, 0x1p300};  // degree 3
inline constexpr ExpansionRange kInsphereRange = {0x1p-160, 0x1p200};  // degree 5

int orient2d_expansion(const double a[2], const double b[2], const double c[2]);
int orient2d_integer(const double a[2], const double b[2], const double c[2]);

int orient3d_expansion(const Point& a, const Point& b, const Point& c, const Point& d);
int orient3d_integer(const Point& a, const Point& b, const Point& c, const Point& d);

// Tier 1 of insphere: the proven sign, or nullopt when the error bound does not decide.
std::optional<int> insphere_filtered(const Point& a, const Point& b, const Point& c, const Point& d,
                                     const Point& e);
int insphere_exact(const Point& a, const Point& b, const Point& c, const Point& d, const Point& e);
int insphere_expansion(const Point& a, const Point& b, const Point& c, const Point& d,
                       const Point& e);
int insphere_integer(const Point& a, const Point& b, const Point& c, const Point& d,
                     const Point& e);

}  // namespace afmesh::predicates_internal
