// Small inline vector helpers on afmesh::Point (a 3-vector of doubles). Plain double arithmetic:
// for exact signs use predicates.h.
#pragma once

#include <cmath>
#include <vector>

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

// (b - a) x (c - a): the normal of triangle (a, b, c) times twice its area (zero for a
// degenerate one); in the second form, of triangle t of `points`.
inline Point vector_area(const Point& a, const Point& b, const Point& c) {
  return cross(sub(b, a), sub(c, a));
}
inline Point vector_area(const std::vector<Point>& points, const Triangle& t) {
  return vector_area(points[t[0]], points[t[1]], points[t[2]]);
}

// The unit normal of triangle (a, b, c), (b - a) x (c - a) scaled to length 1: zero for a
// degenerate triangle, or one whose normal's length is not finite.
inline Point unit_normal(const Point& a, const Point& b, const Point& c) {
  const Point n = vector_area(a, b, c);
  const double length = norm(n);
  return length > 0.0 && std::isfinite(length) ? scale(n, 1.0 / length) : Point{0.0, 0.0, 0.0};
}

// The area of triangle (a, b, c): half the length of (b - a) x (c - a).
inline double triangle_area(const Point& a, const Point& b, const Point& c) {
  return 0.5 * norm(vector_area(a, b, c));
}

// a + t (b - a): a at t = 0, b at t = 1.
inline Point lerp(const Point& a, const Point& b, double t) { return add(a, scale(sub(b, a), t)); }

}  // namespace afmesh
