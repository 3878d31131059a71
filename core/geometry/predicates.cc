// Exact tiers of the predicates (see exact_predicates.h for the tier structure) and insphere.
//
// Each determinant is written once as a polynomial template over its ring type and instantiated
// for expansions (tier 2) and BigInteger (tier 3), so both tiers evaluate the same formula as
// the double filter.

#include "core/geometry/predicates.h"

#include <algorithm>
#include <array>
#include <climits>
#include <cmath>
#include <initializer_list>
#include <optional>
#include <span>
#include <vector>

#include "core/geometry/big_integer.h"
#include "core/geometry/exact_predicates.h"
#include "core/geometry/expansion.h"

namespace afmesh {
namespace predicates_internal {
namespace {

using expansion::exact_difference;
using expansion::Expansion;

// ----- determinant polynomials, shared by tiers 2 and 3 ----------------------------------------

// det[u, v] for 2-D vectors u, v.
template <class T>
auto orient2d_polynomial(const T& ux, const T& uy, const T& vx, const T& vy) {
  return ux * vy - uy * vx;
}

// det[u, v, w] expanded along u: u · (v × w). Minors are multiplied on the left so that, for
// expansions, the longer operand is scaled (see expansion::operator*).
template <class T>
auto orient3d_polynomial(const std::array<T, 3>& u, const std::array<T, 3>& v,
                         const std::array<T, 3>& w) {
  return (v[1] * w[2] - v[2] * w[1]) * u[0] + (v[2] * w[0] - v[0] * w[2]) * u[1] +
         (v[0] * w[1] - v[1] * w[0]) * u[2];
}

// Minus the determinant of the 4x4 matrix with rows (p, |p|^2) for p = A, B, C, D (coordinates
// relative to e), expanded along the lift column: each 3x3 minor det[P; Q; R] is expanded along
// its z column into 2x2 xy-minors xy(P, Q) = Px Qy - Qx Py.
template <class T>
T insphere_polynomial(const std::array<std::array<T, 3>, 4>& rows) {
  const auto& [A, B, C, D] = rows;
  const auto xy = [](const std::array<T, 3>& p, const std::array<T, 3>& q) {
    return p[0] * q[1] - q[0] * p[1];
  };
  const auto lift = [](const std::array<T, 3>& p) {
    return p[0] * p[0] + p[1] * p[1] + p[2] * p[2];
  };
  const T ab = xy(A, B), ac = xy(A, C), ad = xy(A, D);
  const T bc = xy(B, C), bd = xy(B, D), cd = xy(C, D);
  const T bcd = B[2] * cd - C[2] * bd + D[2] * bc;
  const T acd = A[2] * cd - C[2] * ad + D[2] * ac;
  const T abd = A[2] * bd - B[2] * ad + D[2] * ab;
  const T abc = A[2] * bc - B[2] * ac + C[2] * ab;
  return lift(A) * bcd - lift(B) * acd + lift(C) * abd - lift(D) * abc;
}

// ----- tier 2 helpers ---------------------------------------------------------------------------

bool in_range(double x, ExpansionRange range) {
  const double magnitude = std::fabs(x);
  return magnitude == 0.0 || (magnitude >= range.min && magnitude <= range.max);
}

bool all_in_range(std::initializer_list<double> values, ExpansionRange range) {
  return std::all_of(values.begin(), values.end(), [&](double x) { return in_range(x, range); });
}

bool all_in_range(std::initializer_list<const Point*> points, ExpansionRange range) {
  return std::all_of(points.begin(), points.end(), [&](const Point* p) {
    return in_range((*p)[0], range) && in_range((*p)[1], range) && in_range((*p)[2], range);
  });
}

// Exact p - origin, coordinate-wise, as expansions.
std::array<Expansion<2>, 3> exact_differences(const Point& p, const Point& origin) {
  return {exact_difference(p[0], origin[0]), exact_difference(p[1], origin[1]),
          exact_difference(p[2], origin[2])};
}

// An expansion of unbounded length on the heap, for insphere, whose fixed-capacity form would
// need hundreds of kilobytes of stack. Supports the ring operations insphere_polynomial uses.
class DynamicExpansion {
 public:
  DynamicExpansion() = default;
  explicit DynamicExpansion(const Expansion<2>& e)
      : components_(e.components().begin(), e.components().end()) {}

  int sign() const { return expansion::sign(components_); }

  friend DynamicExpansion operator+(const DynamicExpansion& e, const DynamicExpansion& f) {
    return combine(e, f, 1.0);
  }

  friend DynamicExpansion operator-(const DynamicExpansion& e, const DynamicExpansion& f) {
    return combine(e, f, -1.0);
  }

  // Scales the longer operand by each component of the shorter one and sums the partials.
  friend DynamicExpansion operator*(const DynamicExpansion& e, const DynamicExpansion& f) {
    const auto& longer = e.components_.size() >= f.components_.size() ? e : f;
    const auto& shorter = e.components_.size() >= f.components_.size() ? f : e;
    DynamicExpansion product;
    DynamicExpansion partial;
    for (const double component : shorter.components_) {
      partial.components_.resize(2 * longer.components_.size());
      partial.components_.resize(
          expansion::scale(longer.components_, component, partial.components_.data()));
      product = product + partial;
    }
    return product;
  }

 private:
  // e + f_sign * f.
  static DynamicExpansion combine(const DynamicExpansion& e, const DynamicExpansion& f,
                                  double f_sign) {
    DynamicExpansion h;
    h.components_.resize(e.components_.size() + f.components_.size());
    h.components_.resize(
        expansion::sum(e.components_, f.components_, h.components_.data(), f_sign));
    return h;
  }

  std::vector<double> components_;
};

// ----- tier 3 helpers ---------------------------------------------------------------------------

// The common power of two that turns every given coordinate into an integer: the smallest
// lowest-set-bit exponent among the nonzero ones.
int common_exponent_base(std::initializer_list<double> values) {
  int base = INT_MAX;
  for (const double x : values) {
    if (x != 0.0) base = std::min(base, BigInteger::lowest_bit_exponent(x));
  }
  return base == INT_MAX ? 0 : base;
}

int common_exponent_base(std::initializer_list<const Point*> points) {
  int base = INT_MAX;
  for (const Point* p : points) {
    for (const double x : *p) {
      if (x != 0.0) base = std::min(base, BigInteger::lowest_bit_exponent(x));
    }
  }
  return base == INT_MAX ? 0 : base;
}

// p - origin, coordinate-wise, in units of 2^base.
std::array<BigInteger, 3> integer_differences(const Point& p, const Point& origin, int base) {
  std::array<BigInteger, 3> result;
  for (int i = 0; i < 3; ++i) {
    result[i] = BigInteger::from_scaled_double(p[i], base) -
                BigInteger::from_scaled_double(origin[i], base);
  }
  return result;
}

// ----- insphere filter --------------------------------------------------------------------------

// Rounding: the longest chain of roundings into a term of insphere_polynomial (difference,
// square, two additions in the lift; difference, product, subtraction, product, two additions in
// the 3x3 minor; the final product and all but the last of three additions) has 16 roundings,
// as in Shewchuk's isperrboundA = (16 + 224 eps) eps. Rounded up with margin to 18 eps.
constexpr double kInsphereErrorFactor = 0x1.2p-49;  // 18 eps

// Underflow: with m the largest coordinate difference, the absolute errors of subnormal products
// add up to at most 2^8 · 2^-1075 · (m^3 + m^2 + 1). The guard is much larger so that it stays a
// normal number (subnormal arithmetic is slow), as kUnderflowGuard in predicates.h.
constexpr double kInsphereUnderflowGuard = 0x1p-1000;

struct Row {
  double x, y, z, lift;
};

Row relative_row(const Point& p, const Point& e) {
  const double x = p[0] - e[0], y = p[1] - e[1], z = p[2] - e[2];
  return {x, y, z, x * x + y * y + z * z};
}

}  // namespace

// ----- orient2d ---------------------------------------------------------------------------------

int orient2d_expansion(const double a[2], const double b[2], const double c[2]) {
  return orient2d_polynomial(exact_difference(b[0], a[0]), exact_difference(b[1], a[1]),
                             exact_difference(c[0], a[0]), exact_difference(c[1], a[1]))
      .sign();
}

int orient2d_integer(const double a[2], const double b[2], const double c[2]) {
  const int base = common_exponent_base({a[0], a[1], b[0], b[1], c[0], c[1]});
  const auto integer = [base](double x) { return BigInteger::from_scaled_double(x, base); };
  return orient2d_polynomial(integer(b[0]) - integer(a[0]), integer(b[1]) - integer(a[1]),
                             integer(c[0]) - integer(a[0]), integer(c[1]) - integer(a[1]))
      .sign();
}

int orient2d_exact(const double a[2], const double b[2], const double c[2]) {
  // A zero column (all points share a coordinate) makes the determinant 0: common for points
  // on an axis-aligned line, and cheaper to see here than to prove in the tiers below.
  for (int k = 0; k < 2; ++k) {
    if (b[k] == a[k] && c[k] == a[k]) return 0;
  }
  if (all_in_range({a[0], a[1], b[0], b[1], c[0], c[1]}, kOrient2dRange)) {
    return orient2d_expansion(a, b, c);
  }
  return orient2d_integer(a, b, c);
}

// ----- orient3d ---------------------------------------------------------------------------------

// Adaptive evaluation (Shewchuk 1997, §4.3): the differences b - a etc. are split into a rounded
// part (head) and its exact rounding error (tail, |tail| <= eps |head|), and the determinant
// det = det(heads) + (terms with tails) is refined only as far as the sign needs:
//   stage B: det(heads) exactly; enough when every tail is 0, or when it outweighs the bound
//            3 eps (1 + O(eps)) P on all tail terms, P = permanent of the heads;
//   stage C: adds the first-order tail terms in doubles; the remaining error is at most
//            ~34 eps^2 P (second-order terms and rounding) + ~2 eps |result|;
//   stage D: the whole determinant in exact expansion arithmetic.
// The constants below round those bounds up with a margin.
int orient3d_expansion(const Point& a, const Point& b, const Point& c, const Point& d) {
  constexpr double kStageBErrorFactor = 0x1p-51;     // 4 eps
  constexpr double kStageCErrorFactor = 0x1.8p-101;  // 48 eps^2
  constexpr double kStageCResultFactor = 0x1p-51;    // 4 eps

  std::array<std::array<double, 3>, 3> head;  // rows u = b - a, v = c - a, w = d - a
  std::array<std::array<double, 3>, 3> tail;
  bool tails_are_zero = true;
  const Point* ends[3] = {&b, &c, &d};
  for (int r = 0; r < 3; ++r) {
    for (int i = 0; i < 3; ++i) {
      const expansion::Pair difference = expansion::two_difference((*ends[r])[i], a[i]);
      head[r][i] = difference.hi;
      tail[r][i] = difference.lo;
      tails_are_zero = tails_are_zero && difference.lo == 0.0;
    }
  }

  const auto as_expansions = [](const std::array<double, 3>& row) {
    return std::array<Expansion<1>, 3>{Expansion<1>(row[0]), Expansion<1>(row[1]),
                                       Expansion<1>(row[2])};
  };
  const auto head_determinant =
      orient3d_polynomial(as_expansions(head[0]), as_expansions(head[1]), as_expansions(head[2]));
  if (tails_are_zero) return head_determinant.sign();

  const auto& [u, v, w] = head;
  const double permanent = std::fabs(u[0]) * (std::fabs(v[1] * w[2]) + std::fabs(v[2] * w[1])) +
                           std::fabs(u[1]) * (std::fabs(v[2] * w[0]) + std::fabs(v[0] * w[2])) +
                           std::fabs(u[2]) * (std::fabs(v[0] * w[1]) + std::fabs(v[1] * w[0]));
  const double estimate = head_determinant.estimate();
  if (std::fabs(estimate) > kStageBErrorFactor * permanent) return head_determinant.sign();

  const auto determinant = [](const std::array<double, 3>& p, const std::array<double, 3>& q,
                              const std::array<double, 3>& r) {
    return p[0] * (q[1] * r[2] - q[2] * r[1]) + p[1] * (q[2] * r[0] - q[0] * r[2]) +
           p[2] * (q[0] * r[1] - q[1] * r[0]);
  };
  const double corrected = estimate + (determinant(tail[0], v, w) + determinant(u, tail[1], w) +
                                       determinant(u, v, tail[2]));
  const double bound = kStageCErrorFactor * permanent + kStageCResultFactor * std::fabs(corrected);
  if (std::fabs(corrected) > bound) return corrected > 0.0 ? 1 : -1;

  return orient3d_polynomial(exact_differences(b, a), exact_differences(c, a),
                             exact_differences(d, a))
      .sign();
}

int orient3d_integer(const Point& a, const Point& b, const Point& c, const Point& d) {
  const int base = common_exponent_base({&a, &b, &c, &d});
  return orient3d_polynomial(integer_differences(b, a, base), integer_differences(c, a, base),
                             integer_differences(d, a, base))
      .sign();
}

int orient3d_exact(const Point& a, const Point& b, const Point& c, const Point& d) {
  // A zero column (all points share a coordinate, e.g. on a plane z = const) makes the
  // determinant 0: common on axis-aligned boundaries, and cheap to see here.
  for (int k = 0; k < 3; ++k) {
    if (b[k] == a[k] && c[k] == a[k] && d[k] == a[k]) return 0;
  }
  if (all_in_range({&a, &b, &c, &d}, kOrient3dRange)) return orient3d_expansion(a, b, c, d);
  return orient3d_integer(a, b, c, d);
}

// ----- insphere ---------------------------------------------------------------------------------

std::optional<int> insphere_filtered(const Point& a, const Point& b, const Point& c, const Point& d,
                                     const Point& e) {
  const Row A = relative_row(a, e), B = relative_row(b, e);
  const Row C = relative_row(c, e), D = relative_row(d, e);

  // insphere_polynomial in doubles, with the permanent (every product replaced by the product of
  // magnitudes) alongside.
  const auto xy = [](const Row& p, const Row& q) { return p.x * q.y - q.x * p.y; };
  const auto xy_abs = [](const Row& p, const Row& q) {
    return std::fabs(p.x * q.y) + std::fabs(q.x * p.y);
  };
  const double ab = xy(A, B), ac = xy(A, C), ad = xy(A, D);
  const double bc = xy(B, C), bd = xy(B, D), cd = xy(C, D);
  const double bcd = B.z * cd - C.z * bd + D.z * bc;
  const double acd = A.z * cd - C.z * ad + D.z * ac;
  const double abd = A.z * bd - B.z * ad + D.z * ab;
  const double abc = A.z * bc - B.z * ac + C.z * ab;
  const double det = A.lift * bcd - B.lift * acd + C.lift * abd - D.lift * abc;

  const double ab_abs = xy_abs(A, B), ac_abs = xy_abs(A, C), ad_abs = xy_abs(A, D);
  const double bc_abs = xy_abs(B, C), bd_abs = xy_abs(B, D), cd_abs = xy_abs(C, D);
  const double az = std::fabs(A.z), bz = std::fabs(B.z), cz = std::fabs(C.z), dz = std::fabs(D.z);
  const double permanent = A.lift * (bz * cd_abs + cz * bd_abs + dz * bc_abs) +
                           B.lift * (az * cd_abs + cz * ad_abs + dz * ac_abs) +
                           C.lift * (az * bd_abs + bz * ad_abs + dz * ab_abs) +
                           D.lift * (az * bc_abs + bz * ac_abs + cz * ab_abs);
  const double m =
      std::max({std::fabs(A.x), std::fabs(A.y), az, std::fabs(B.x), std::fabs(B.y), bz,
                std::fabs(C.x), std::fabs(C.y), cz, std::fabs(D.x), std::fabs(D.y), dz});
  const double bound =
      kInsphereErrorFactor * permanent + kInsphereUnderflowGuard * (m * m * m + m * m + 1.0);
  if (det > bound) return 1;
  if (det < -bound) return -1;
  return std::nullopt;
}

int insphere_expansion(const Point& a, const Point& b, const Point& c, const Point& d,
                       const Point& e) {
  std::array<std::array<DynamicExpansion, 3>, 4> rows;
  const Point* points[4] = {&a, &b, &c, &d};
  for (int r = 0; r < 4; ++r) {
    for (int i = 0; i < 3; ++i) {
      rows[r][i] = DynamicExpansion(exact_difference((*points[r])[i], e[i]));
    }
  }
  return insphere_polynomial(rows).sign();
}

int insphere_integer(const Point& a, const Point& b, const Point& c, const Point& d,
                     const Point& e) {
  const int base = common_exponent_base({&a, &b, &c, &d, &e});
  const std::array<std::array<BigInteger, 3>, 4> rows = {
      integer_differences(a, e, base), integer_differences(b, e, base),
      integer_differences(c, e, base), integer_differences(d, e, base)};
  return insphere_polynomial(rows).sign();
}

int insphere_exact(const Point& a, const Point& b, const Point& c, const Point& d, const Point& e) {
  if (all_in_range({&a, &b, &c, &d, &e}, kInsphereRange)) return insphere_expansion(a, b, c, d, e);
  return insphere_integer(a, b, c, d, e);
}

}  // namespace predicates_internal

bool collinear(const Point& a, const Point& b, const Point& c) {
  return orient2d_projected(a, b, c, 0) == 0 && orient2d_projected(a, b, c, 1) == 0 &&
         orient2d_projected(a, b, c, 2) == 0;
}

int insphere(const Point& a, const Point& b, const Point& c, const Point& d, const Point& e) {
  if (const std::optional<int> sign = predicates_internal::insphere_filtered(a, b, c, d, e)) {
    return *sign;
  }
  return predicates_internal::insphere_exact(a, b, c, d, e);
}

}  // namespace afmesh
