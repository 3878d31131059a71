// Robust geometric predicates: exact signs from a floating-point filter with an exact fallback.
//
// Every predicate here returns the exact sign (-1, 0, +1) of a determinant of its double inputs,
// as if evaluated in exact arithmetic: a fast double evaluation is used when its error bound
// proves the sign, and an exact expansion-arithmetic evaluation (Shewchuk 1997) otherwise.
// Inputs must be finite; any finite doubles are allowed (huge, tiny and subnormal coordinates
// included: inputs outside the range where expansion arithmetic is exact are evaluated with
// integer arithmetic instead, see exact_predicates.h).
//
// Floating-point environment: IEEE-754 binary64, round-to-nearest (the default), no
// flush-to-zero / denormals-are-zero (do not build with -ffast-math). Contraction of a*b+c into
// fused multiply-adds is harmless: it only lowers the filters' rounding error.
//
// The filters (the first stage of orient2d / orient3d) are inline so that the common case, where
// the double evaluation already proves the sign, costs a few nanoseconds and no call.
#pragma once

#include <cmath>

#include "core/mesh/mesh.h"

namespace afmesh {

namespace predicates_internal {

// Exact fallbacks (out of line, predicates.cc); each returns the exact sign of the same
// determinant as its public counterpart below.
int orient2d_exact(const double a[2], const double b[2], const double c[2]);
int orient3d_exact(const Point& a, const Point& b, const Point& c, const Point& d);

// Forward error bounds of the filters (Shewchuk 1997, §4.2), with eps = 2^-53 the unit roundoff.
// Counting the roundings that reach a term of the determinant (the final addition does not count:
// rounding never changes a sign) gives |computed - exact| <= (k eps + O(eps^2)) * permanent, with
// k = 3 for orient2d and k = 7 for orient3d; the factors below round k + O(eps) up to 4 and 8.
inline constexpr double kOrient2dErrorFactor = 0x1p-51;  // 4 eps
inline constexpr double kOrient3dErrorFactor = 0x1p-50;  // 8 eps

// Absolute term covering underflow: a product whose result is subnormal has an absolute error up
// to 2^-1075 instead of a relative one. orient2d has two such products (error < 2^-1073); in
// orient3d each 2x2 minor's error is then multiplied by the outer factor |u_i|, giving at most
// 2^-1073 (sum |u_i| + 2). The guard is far larger than needed so that it is a normal number:
// arithmetic on subnormals is very slow on common CPUs. It only sends determinants below
// ~1e-301 (times sum |u_i| + 1) to the exact path.
inline constexpr double kUnderflowGuard = 0x1p-1000;

}  // namespace predicates_internal

// -----------------------------------------------------------------------------------------------
// orient3d(a, b, c, d): sign of det[b-a, c-a, d-a] = 6 × signed volume of tet (a, b, c, d).
//   +1: d lies on the side of plane (a, b, c) that (b-a)x(c-a) points to (tet (a, b, c, d) is
//       positive in the mesh convention);
//   -1: the other side;  0: a, b, c, d are coplanar (including any degenerate a, b, c). Exact.
// Antisymmetric: swapping any two arguments negates the result.
// -----------------------------------------------------------------------------------------------
inline int orient3d(const Point& a, const Point& b, const Point& c, const Point& d) {
  const double ux = b[0] - a[0], uy = b[1] - a[1], uz = b[2] - a[2];
  const double vx = c[0] - a[0], vy = c[1] - a[1], vz = c[2] - a[2];
  const double wx = d[0] - a[0], wy = d[1] - a[1], wz = d[2] - a[2];
  const double vywz = vy * wz, vzwy = vz * wy;
  const double vzwx = vz * wx, vxwz = vx * wz;
  const double vxwy = vx * wy, vywx = vy * wx;
  const double det = ux * (vywz - vzwy) + uy * (vzwx - vxwz) + uz * (vxwy - vywx);

  const double aux = std::fabs(ux), auy = std::fabs(uy), auz = std::fabs(uz);
  const double permanent = aux * (std::fabs(vywz) + std::fabs(vzwy)) +
                           auy * (std::fabs(vzwx) + std::fabs(vxwz)) +
                           auz * (std::fabs(vxwy) + std::fabs(vywx));
  const double bound = predicates_internal::kOrient3dErrorFactor * permanent +
                       predicates_internal::kUnderflowGuard * (aux + auy + auz + 1.0);
  // Overflow makes det or bound infinite or NaN, and the comparison false. One well-predicted
  // branch; the sign itself is computed without branching.
  if (std::fabs(det) > bound) [[likely]] {
    return (det > 0.0) - (det < 0.0);
  }
  return predicates_internal::orient3d_exact(a, b, c, d);
}

// -----------------------------------------------------------------------------------------------
// Orient3dPlane(a, b, c).side(d) == orient3d(a, b, c, d), exactly, for many points d against one
// plane: the cross product n = (b-a)x(c-a) of the filter and its absolute terms are computed once,
// so each side(d) costs a dot product. The filter evaluates det[b-a, c-a, d-a] expanded along
// w = d-a, w · n, which has the same rounding structure as orient3d's expansion along b-a (a
// rounded coordinate difference times a rounded difference of products of rounded differences),
// so the same bound holds with the roles of u and w exchanged; when it does not prove the sign,
// side(d) calls the exact orient3d(a, b, c, d). a, b, c are copied (the object owns its plane).
// -----------------------------------------------------------------------------------------------
class Orient3dPlane {
 public:
  Orient3dPlane() = default;
  Orient3dPlane(const Point& a, const Point& b, const Point& c) : a_(a), b_(b), c_(c) {
    const double ux = b[0] - a[0], uy = b[1] - a[1], uz = b[2] - a[2];
    const double vx = c[0] - a[0], vy = c[1] - a[1], vz = c[2] - a[2];
    const double uyvz = uy * vz, uzvy = uz * vy;
    const double uzvx = uz * vx, uxvz = ux * vz;
    const double uxvy = ux * vy, uyvx = uy * vx;
    n_ = {uyvz - uzvy, uzvx - uxvz, uxvy - uyvx};
    abs_n_ = {std::fabs(uyvz) + std::fabs(uzvy), std::fabs(uzvx) + std::fabs(uxvz),
              std::fabs(uxvy) + std::fabs(uyvx)};
  }

  int side(const Point& d) const {
    const double wx = d[0] - a_[0], wy = d[1] - a_[1], wz = d[2] - a_[2];
    const double det = wx * n_[0] + wy * n_[1] + wz * n_[2];
    const double awx = std::fabs(wx), awy = std::fabs(wy), awz = std::fabs(wz);
    const double permanent = awx * abs_n_[0] + awy * abs_n_[1] + awz * abs_n_[2];
    const double bound = predicates_internal::kOrient3dErrorFactor * permanent +
                         predicates_internal::kUnderflowGuard * (awx + awy + awz + 1.0);
    if (std::fabs(det) > bound) [[likely]] {
      return (det > 0.0) - (det < 0.0);
    }
    return predicates_internal::orient3d_exact(a_, b_, c_, d);
  }

 private:
  Point a_{}, b_{}, c_{};
  Point n_{};      // (b-a)x(c-a), rounded as orient3d's filter rounds its minors
  Point abs_n_{};  // per component, the sum of the absolute values of its two products
};

// -----------------------------------------------------------------------------------------------
// orient3d_fast(a, b, c, d): det[b-a, c-a, d-a] in plain double arithmetic (6 × signed volume),
// same formula as orient3d's filter. NOT exact and its sign may be wrong for nearly coplanar
// points: for volumes, quality measures and other non-predicate uses only.
// -----------------------------------------------------------------------------------------------
inline double orient3d_fast(const Point& a, const Point& b, const Point& c, const Point& d) {
  const double ux = b[0] - a[0], uy = b[1] - a[1], uz = b[2] - a[2];
  const double vx = c[0] - a[0], vy = c[1] - a[1], vz = c[2] - a[2];
  const double wx = d[0] - a[0], wy = d[1] - a[1], wz = d[2] - a[2];
  return ux * (vy * wz - vz * wy) + uy * (vz * wx - vx * wz) + uz * (vx * wy - vy * wx);
}

// -----------------------------------------------------------------------------------------------
// orient2d(a, b, c): sign of det[b-a, c-a] for 2-D points (x, y).
//   +1: a, b, c turn counter-clockwise;  -1: clockwise;  0: collinear. Exact.
// -----------------------------------------------------------------------------------------------
inline int orient2d(const double a[2], const double b[2], const double c[2]) {
  const double ux = b[0] - a[0], uy = b[1] - a[1];
  const double vx = c[0] - a[0], vy = c[1] - a[1];
  const double uxvy = ux * vy, uyvx = uy * vx;
  const double det = uxvy - uyvx;
  const double bound =
      predicates_internal::kOrient2dErrorFactor * (std::fabs(uxvy) + std::fabs(uyvx)) +
      predicates_internal::kUnderflowGuard;
  if (std::fabs(det) > bound) [[likely]] {
    return (det > 0.0) - (det < 0.0);
  }
  return predicates_internal::orient2d_exact(a, b, c);
}

// -----------------------------------------------------------------------------------------------
// orient2d_projected(a, b, c, axis): orient2d of the projections of a, b, c onto the coordinate
// plane that drops `axis` (0 = x, 1 = y, 2 = z), keeping the remaining two coordinates in cyclic
// order ((y, z) for axis 0, (z, x) for axis 1, (x, y) for axis 2), so that for a triangle with
// normal n = (b-a)x(c-a), orient2d_projected(a, b, c, axis) has the sign of n[axis]. Exact.
// -----------------------------------------------------------------------------------------------
inline int orient2d_projected(const Point& a, const Point& b, const Point& c, int axis) {
  const int i = (axis + 1) % 3;
  const int j = (axis + 2) % 3;
  const double pa[2] = {a[i], a[j]};
  const double pb[2] = {b[i], b[j]};
  const double pc[2] = {c[i], c[j]};
  return orient2d(pa, pb, pc);
}

// True when a, b, c lie on one line (all three projected orientations vanish, i.e.
// (b-a)x(c-a) = 0), including when two or three of them coincide. Exact.
bool collinear(const Point& a, const Point& b, const Point& c);

// -----------------------------------------------------------------------------------------------
// insphere(a, b, c, d, e): where e lies relative to the sphere through a, b, c, d.
//   Result = orient3d(a, b, c, d) × (+1 if e is strictly inside the sphere, 0 if on it,
//   -1 if strictly outside). So for a positive tet (orient3d(a, b, c, d) = +1, the mesh
//   convention) +1 means inside; for a negative tet the sign flips. Exact.
// It is the sign of -det of the 4x4 matrix with rows (p - e, |p - e|^2), p = a, b, c, d.
// When a, b, c, d are coplanar there is no sphere and the result is that determinant's sign,
// which says nothing about a sphere: check orient3d(a, b, c, d) != 0 first.
// -----------------------------------------------------------------------------------------------
int insphere(const Point& a, const Point& b, const Point& c, const Point& d, const Point& e);

}  // namespace afmesh
