// Floating-point expansion arithmetic: exact sums and products of doubles, after
// J. R. Shewchuk, "Adaptive precision floating-point arithmetic and fast robust geometric
// predicates", Discrete & Computational Geometry 18 (1997), §2.
//
// An expansion is a sequence of doubles e[0], ..., e[n-1] whose exact sum is the value it
// represents. The routines here keep every expansion
//   - nonoverlapping and ordered by increasing magnitude (each component's lowest set bit lies
//     above the highest set bit of the one before), so the last component has the value's sign
//     and |e[n-1]| > |e[0] + ... + e[n-2]|;
//   - zero-free (zero components are dropped; the empty expansion is 0).
//
// Exactness assumptions: IEEE-754 binary64 arithmetic, round-to-nearest-even (the default mode),
// no flush-to-zero, no overflow, and no underflow of a product's rounding error (a two_product of
// x and y is exact when the lowest set bits of x and y have exponents summing to at least -1074).
// The predicates that use these routines check their input range and otherwise fall back to
// integer arithmetic (big_integer.h). Everything here is header-only so the compiler can inline
// the error-free transformations into the predicates.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <span>

namespace afmesh::expansion {

// A value split into a rounded part and its exact rounding error: value == hi + lo exactly.
struct Pair {
  double hi;
  double lo;
};

// ---------------------------------------------------------------------------------------------
// two_sum(a, b): hi = fl(a + b), lo = (a + b) - hi exactly (Knuth's branch-free form; Shewchuk
// Theorem 7). No precondition on the magnitudes.
// ---------------------------------------------------------------------------------------------
inline Pair two_sum(double a, double b) {
  const double hi = a + b;
  const double b_virtual = hi - a;
  const double a_virtual = hi - b_virtual;
  const double b_roundoff = b - b_virtual;
  const double a_roundoff = a - a_virtual;
  return {hi, a_roundoff + b_roundoff};
}

// ---------------------------------------------------------------------------------------------
// fast_two_sum(a, b): as two_sum, but requires |a| >= |b| (or a == 0); three operations
// (Dekker; Shewchuk Theorem 6).
// ---------------------------------------------------------------------------------------------
inline Pair fast_two_sum(double a, double b) {
  const double hi = a + b;
  return {hi, b - (hi - a)};
}

// two_difference(a, b): hi = fl(a - b), lo = (a - b) - hi exactly. Negation is exact.
inline Pair two_difference(double a, double b) { return two_sum(a, -b); }

// ---------------------------------------------------------------------------------------------
// two_product(a, b): hi = fl(a * b), lo = a * b - hi exactly. The fused multiply-add rounds
// a * b - hi once, and that value is representable (see the underflow assumption above), so lo is
// exact.
// ---------------------------------------------------------------------------------------------
inline Pair two_product(double a, double b) {
  const double hi = a * b;
  return {hi, std::fma(a, b, -hi)};
}

// ---------------------------------------------------------------------------------------------
// sum(e, f, h, f_sign): h = e + f_sign * f, exactly, with f_sign = +1 or -1. e and f are
// expansions (invariants above); h must have room for e.size() + f.size() components and may not
// alias e or f. Returns h's length.
//
// Merges e and f by increasing magnitude into one sequence g, then accumulates g from the
// smallest component upwards, emitting each two_sum's rounding error as an output component
// (Shewchuk's Fast-Expansion-Sum, Theorem 13, with zero elimination).
// ---------------------------------------------------------------------------------------------
inline int sum(std::span<const double> e, std::span<const double> f, double* h,
               double f_sign = 1.0) {
  std::size_t i = 0;
  std::size_t j = 0;
  const auto next_smallest = [&]() {
    if (j == f.size() || (i < e.size() && std::fabs(e[i]) < std::fabs(f[j]))) return e[i++];
    return f_sign * f[j++];
  };
  const std::size_t total = e.size() + f.size();
  if (total == 0) return 0;
  double q = next_smallest();
  if (total == 1) {
    h[0] = q;
    return 1;
  }
  int n = 0;
  const Pair first = fast_two_sum(next_smallest(), q);
  q = first.hi;
  h[n] = first.lo;
  n += first.lo != 0.0;
  for (std::size_t k = 2; k < total; ++k) {
    const Pair s = two_sum(q, next_smallest());
    q = s.hi;
    h[n] = s.lo;
    n += s.lo != 0.0;
  }
  h[n] = q;
  n += q != 0.0;
  return n;
}

// ---------------------------------------------------------------------------------------------
// scale(e, b, h): h = e * b, exactly. e is an expansion, b a double; h must have room for
// 2 * e.size() components and may not alias e. Returns h's length.
//
// Each component's product is split by two_product; the high parts are chained through the
// running sum so every rounding error is emitted in increasing order (Shewchuk's
// Scale-Expansion, Theorem 19, with zero elimination).
// ---------------------------------------------------------------------------------------------
inline int scale(std::span<const double> e, double b, double* h) {
  if (e.empty()) return 0;
  int n = 0;
  const Pair p0 = two_product(e[0], b);
  double q = p0.hi;
  h[n] = p0.lo;
  n += p0.lo != 0.0;
  for (std::size_t i = 1; i < e.size(); ++i) {
    const Pair p = two_product(e[i], b);
    const Pair s = two_sum(q, p.lo);
    h[n] = s.lo;
    n += s.lo != 0.0;
    const Pair t = fast_two_sum(p.hi, s.hi);
    h[n] = t.lo;
    n += t.lo != 0.0;
    q = t.hi;
  }
  h[n] = q;
  n += q != 0.0;
  return n;
}

// Sign of an expansion: the sign of its largest (last) component; 0 for the empty expansion.
inline int sign(std::span<const double> e) {
  if (e.empty()) return 0;
  return e.back() > 0.0 ? 1 : -1;
}

// ---------------------------------------------------------------------------------------------
// Expansion<N>: an expansion of at most N components stored inline (no allocation), for the
// fixed-shape formulas of orient2d / orient3d. The result types of +, - and * carry capacities
// large enough for any input, so no operation can overflow its storage.
// ---------------------------------------------------------------------------------------------
template <int N>
class Expansion {
 public:
  Expansion() = default;

  // The exact value of one double.
  explicit Expansion(double x) {
    static_assert(N >= 1);
    if (x != 0.0) components_[size_++] = x;
  }

  // The exact value hi + lo of a two_sum / two_difference / two_product result.
  explicit Expansion(Pair p) {
    static_assert(N >= 2);
    if (p.lo != 0.0) components_[size_++] = p.lo;
    if (p.hi != 0.0) components_[size_++] = p.hi;
  }

  // Copies only the meaningful components (the storage can be large and mostly unused).
  Expansion(const Expansion& other) : size_(other.size_) {
    std::copy_n(other.components_.data(), size_, components_.data());
  }
  Expansion& operator=(const Expansion& other) {
    size_ = other.size_;
    std::copy_n(other.components_.data(), size_, components_.data());
    return *this;
  }

  std::span<const double> components() const { return {components_.data(), std::size_t(size_)}; }
  int size() const { return size_; }
  int sign() const { return expansion::sign(components()); }

  // The value rounded to a double (approximately: summed from the smallest component up).
  double estimate() const {
    double total = 0.0;
    for (int i = 0; i < size_; ++i) total += components_[i];
    return total;
  }

  // Raw storage for the routines above: fill `data()`, then `resize` to the returned length.
  double* data() { return components_.data(); }
  void resize(int size) { size_ = size; }

  Expansion operator-() const {
    Expansion negated;
    for (int i = 0; i < size_; ++i) negated.components_[i] = -components_[i];
    negated.size_ = size_;
    return negated;
  }

 private:
  std::array<double, N> components_;  // only the first size_ are meaningful
  int size_ = 0;
};

template <int N, int M>
Expansion<N + M> operator+(const Expansion<N>& e, const Expansion<M>& f) {
  Expansion<N + M> h;
  h.resize(sum(e.components(), f.components(), h.data()));
  return h;
}

template <int N, int M>
Expansion<N + M> operator-(const Expansion<N>& e, const Expansion<M>& f) {
  Expansion<N + M> h;
  h.resize(sum(e.components(), f.components(), h.data(), -1.0));
  return h;
}

// e * f, by scaling e with each component of f and summing the partial products. Put the
// expansion with fewer components second: the work is linear in e's length per f component.
template <int N, int M>
Expansion<2 * N * M> operator*(const Expansion<N>& e, const Expansion<M>& f) {
  Expansion<2 * N * M> product;
  const std::span<const double> factors = f.components();
  if (factors.empty()) return product;
  if (factors.size() == 1) {
    product.resize(scale(e.components(), factors[0], product.data()));
    return product;
  }
  std::array<double, 2 * N> partial;
  std::array<std::array<double, 2 * N * M>, 2> running;  // partial sums, ping-ponged
  int current = 0;
  int current_size = scale(e.components(), factors[0], running[0].data());
  for (std::size_t k = 1; k < factors.size(); ++k) {
    const int partial_size = scale(e.components(), factors[k], partial.data());
    const bool last = k + 1 == factors.size();
    double* out = last ? product.data() : running[1 - current].data();
    current_size = sum(std::span<const double>(running[current].data(), std::size_t(current_size)),
                       std::span<const double>(partial.data(), std::size_t(partial_size)), out);
    current = 1 - current;
  }
  product.resize(current_size);
  return product;
}

// The exact difference a - b of two doubles, as an expansion of at most two components.
inline Expansion<2> exact_difference(double a, double b) {
  return Expansion<2>(two_difference(a, b));
}

}  // namespace afmesh::expansion
