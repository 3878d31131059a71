#include "core/geometry/closest_points.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "core/geometry/vec.h"

namespace afmesh {

Point closest_point_on_segment(const Point& x, const Point& p, const Point& q) {
  const Point d = sub(q, p);
  const double length2 = squared_norm(d);
  if (!(length2 > 0.0)) return p;
  const double t = std::clamp(dot(sub(x, p), d) / length2, 0.0, 1.0);
  return lerp(p, q, t);
}

Point closest_point_on_triangle(const Point& x, const Point& a, const Point& b, const Point& c) {
  const Point ab = sub(b, a), ac = sub(c, a);
  if (!(squared_norm(cross(ab, ac)) > 0.0)) {  // degenerate: the closest of its edges
    Point best = closest_point_on_segment(x, a, b);
    for (const Point& candidate :
         {closest_point_on_segment(x, b, c), closest_point_on_segment(x, c, a)}) {
      if (squared_distance(x, candidate) < squared_distance(x, best)) best = candidate;
    }
    return best;
  }
  // Vertex region of a.
  const Point ax = sub(x, a);
  const double d1 = dot(ab, ax), d2 = dot(ac, ax);
  if (d1 <= 0.0 && d2 <= 0.0) return a;
  // Vertex region of b.
  const Point bx = sub(x, b);
  const double d3 = dot(ab, bx), d4 = dot(ac, bx);
  if (d3 >= 0.0 && d4 <= d3) return b;
  // Edge region of ab.
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0) return add(a, scale(ab, d1 / (d1 - d3)));
  // Vertex region of c.
  const Point cx = sub(x, c);
  const double d5 = dot(ab, cx), d6 = dot(ac, cx);
  if (d6 >= 0.0 && d5 <= d6) return c;
  // Edge region of ac.
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0) return add(a, scale(ac, d2 / (d2 - d6)));
  // Edge region of bc.
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0) {
    return add(b, scale(sub(c, b), (d4 - d3) / ((d4 - d3) + (d5 - d6))));
  }
  // Interior: barycentric coordinates from the three areas.
  const double denominator = 1.0 / (va + vb + vc);
  return add(a, add(scale(ab, vb * denominator), scale(ac, vc * denominator)));
}

ClosestPair closest_points_segments(const Point& p0, const Point& q0, const Point& p1,
                                    const Point& q1) {
  const Point d0 = sub(q0, p0), d1 = sub(q1, p1), r = sub(p0, p1);
  const double a = squared_norm(d0), e = squared_norm(d1), f = dot(d1, r);
  double s = 0.0, t = 0.0;
  if (!(a > 0.0) && !(e > 0.0)) {
    // Two points.
  } else if (!(a > 0.0)) {
    t = std::clamp(f / e, 0.0, 1.0);
  } else {
    const double c = dot(d0, r);
    if (!(e > 0.0)) {
      s = std::clamp(-c / a, 0.0, 1.0);
    } else {
      const double b = dot(d0, d1);
      const double denominator = a * e - b * b;  // >= 0; 0 for parallel segments
      s = denominator > 0.0 ? std::clamp((b * f - c * e) / denominator, 0.0, 1.0) : 0.0;
      t = (b * s + f) / e;
      if (t < 0.0) {
        t = 0.0;
        s = std::clamp(-c / a, 0.0, 1.0);
      } else if (t > 1.0) {
        t = 1.0;
        s = std::clamp((b - c) / a, 0.0, 1.0);
      }
    }
  }
  ClosestPair pair;
  pair.first = add(p0, scale(d0, s));
  pair.second = add(p1, scale(d1, t));
  pair.squared_distance = squared_distance(pair.first, pair.second);
  return pair;
}

ClosestPair closest_points_triangles(const Point& a0, const Point& a1, const Point& a2,
                                     const Point& b0, const Point& b1, const Point& b2) {
  const std::array<Point, 3> a = {a0, a1, a2};
  const std::array<Point, 3> b = {b0, b1, b2};
  ClosestPair best;
  bool found = false;
  const auto consider = [&](const ClosestPair& candidate) {
    if (!found || candidate.squared_distance < best.squared_distance) {
      best = candidate;
      found = true;
    }
  };
  for (int i = 0; i < 3; ++i) {
    const Point on_b = closest_point_on_triangle(a[i], b0, b1, b2);
    consider({a[i], on_b, squared_distance(a[i], on_b)});
    const Point on_a = closest_point_on_triangle(b[i], a0, a1, a2);
    consider({on_a, b[i], squared_distance(on_a, b[i])});
  }
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      consider(closest_points_segments(a[i], a[(i + 1) % 3], b[j], b[(j + 1) % 3]));
    }
  }
  return best;
}

double ray_triangle_parameter(const Point& x, const Point& u, const Point& a, const Point& b,
                              const Point& c) {
  constexpr double kMiss = std::numeric_limits<double>::infinity();
  const Point e1 = sub(b, a), e2 = sub(c, a);
  const Point h = cross(u, e2);
  const double det = dot(e1, h);
  // The ray's direction against the triangle's plane, relative to their sizes: parallel (or a
  // degenerate triangle) when the determinant is lost in rounding.
  if (!(std::fabs(det) > 1e-14 * norm(u) * norm(e1) * norm(e2))) return kMiss;
  const double inverse = 1.0 / det;
  const Point s = sub(x, a);
  const double beta = dot(s, h) * inverse;
  if (beta < 0.0 || beta > 1.0) return kMiss;
  const Point q = cross(s, e1);
  const double gamma = dot(u, q) * inverse;
  if (gamma < 0.0 || beta + gamma > 1.0) return kMiss;
  const double t = dot(e2, q) * inverse;
  return t > 0.0 ? t : kMiss;
}

}  // namespace afmesh
