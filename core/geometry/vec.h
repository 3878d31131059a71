// Small inline vector helpers on afmesh::Point (a 3-vector of doubles). Plain double arithmetic:
// for exact signs use predicates.h.
#pragma once

#include <cmath>

#include "core/mesh/mesh.h"

namespace afmesh {

inline Point add(const Point& a, const Point& b) { return {a[0] + b[0], a[1] + b[1], a[2] + b[2]}; }

inline Point sub(const Point& a, const Point& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }

inline Point scale(const Point& a, double s) { return {a[0] * s, a[1] * s, a[2] * s}; }

inline double dot(const Point& a, const Point& b) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

inline Point cross(const Point& a, const Point& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}

inline double squared_norm(const Point& a) { return dot(a, a); }

inline double norm(const Point& a) { return std::sqrt(squared_norm(a)); }

inline double squared_distance(const Point& a, const Point& b) { return squared_norm(sub(a, b)); }

inline double distance(const Point& a, const Point& b) { return norm(sub(a, b)); }

// The unit normal of triangle (a, b, c), (b - a) x (c - a) scaled to length 1: zero for a
// degenerate triangle, or one whose normal's length is not finite.
inline Point unit_normal(const Point& a, const Point& b, const Point& c) {
  const Point n = cross(sub(b, a), sub(c, a));
  const double length = norm(n);
  return length > 0.0 && std::isfinite(length) ? scale(n, 1.0 / length) : Point{0.0, 0.0, 0.0};
}

// The area of triangle (a, b, c): half the length of (b - a) x (c - a).
inline double triangle_area(const Point& a, const Point& b, const Point& c) {
  return 0.5 * norm(cross(sub(b, a), sub(c, a)));
}

// a + t (b - a): a at t = 0, b at t = 1.
inline Point lerp(const Point& a, const Point& b, double t) { return add(a, scale(sub(b, a), t)); }

}  // namespace afmesh
