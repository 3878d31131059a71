// Exact point / segment / triangle / tet intersection tests (see intersect.h for contracts).
//
// Method: every decision is a sign of orient3d or orient2d, or a comparison of coordinates, all
// exact. Coplanar configurations are decided in 2-D after dropping a coordinate axis along which
// the common plane's normal has a nonzero component; that projection is an affine bijection of
// the plane onto the coordinate plane, so it preserves incidences and (up to one global sign)
// orientations.

#include "core/geometry/intersect.h"

#include <algorithm>
#include <array>
#include <cstddef>
#include <tuple>

#include "core/geometry/predicates.h"

namespace afmesh {
namespace {

using Point2 = std::array<double, 2>;

// The coordinates kept when dropping `axis`, in the cyclic order orient2d_projected uses.
Point2 project(const Point& p, int axis) { return {p[(axis + 1) % 3], p[(axis + 2) % 3]}; }

int orient2(const Point2& a, const Point2& b, const Point2& c) {
  return orient2d(a.data(), b.data(), c.data());
}

// An axis along which the normal (b-a)x(c-a) has a nonzero component, or -1 when a, b, c are
// collinear. Dropping it projects the plane of a, b, c one-to-one onto a coordinate plane.
int projection_axis(const Point& a, const Point& b, const Point& c) {
  for (int axis = 0; axis < 3; ++axis) {
    if (orient2d_projected(a, b, c, axis) != 0) return axis;
  }
  return -1;
}

// The closed axis-aligned bounding boxes of two point sets (2-D or 3-D) overlap.
template <class P, std::size_t NA, std::size_t NB>
bool boxes_overlap(const std::array<const P*, NA>& a, const std::array<const P*, NB>& b) {
  for (std::size_t k = 0; k < std::tuple_size_v<P>; ++k) {
    double a_min = (*a[0])[k], a_max = a_min, b_min = (*b[0])[k], b_max = b_min;
    for (const P* p : a) a_min = std::min(a_min, (*p)[k]), a_max = std::max(a_max, (*p)[k]);
    for (const P* p : b) b_min = std::min(b_min, (*p)[k]), b_max = std::max(b_max, (*p)[k]);
    if (a_max < b_min || b_max < a_min) return false;
  }
  return true;
}

// ----- 2-D tests (in a projection) -------------------------------------------------------------

// Closed 2-D segments [p, q] and [r, s] share a point. When neither segment's line strictly
// separates the other's end points they meet, unless r and s both lie on the line of [p, q]:
// then all four points are collinear (or p == q, or r == s with r on that line), the segments
// are intervals of one line, and they overlap exactly when their boxes do. (If p and q lie on
// the line of [r, s] while r, s are off the line of [p, q], then r == s off the line, which the
// first separation test already rejected.)
bool segments_intersect_2d(const Point2& p, const Point2& q, const Point2& r, const Point2& s) {
  const int o_r = orient2(p, q, r), o_s = orient2(p, q, s);
  if (o_r * o_s > 0) return false;
  const int o_p = orient2(r, s, p), o_q = orient2(r, s, q);
  if (o_p * o_q > 0) return false;
  if (o_r == 0 && o_s == 0) return boxes_overlap(std::array{&p, &q}, std::array{&r, &s});
  return true;
}

// x lies in the closed 2-D triangle (a, b, c), which must not be degenerate: no edge has x
// strictly on its outer side.
bool point_in_triangle_2d(const Point2& x, const Point2& a, const Point2& b, const Point2& c) {
  const int outer = -orient2(a, b, c);
  return orient2(a, b, x) != outer && orient2(b, c, x) != outer && orient2(c, a, x) != outer;
}

// Closed 2-D segment [p, q] meets the closed non-degenerate triangle (a, b, c): an end point is
// inside, or the segment meets an edge.
bool segment_triangle_intersect_2d(const Point2& p, const Point2& q, const Point2& a,
                                   const Point2& b, const Point2& c) {
  return point_in_triangle_2d(p, a, b, c) || point_in_triangle_2d(q, a, b, c) ||
         segments_intersect_2d(p, q, a, b) || segments_intersect_2d(p, q, b, c) ||
         segments_intersect_2d(p, q, c, a);
}

// Closed 2-D triangles meet, the first one non-degenerate: an edge of the second meets the first,
// or else (the second's boundary missing the first, connected triangle) the first lies inside
// the second, which a single vertex tells. A degenerate second triangle is the union of its
// edges.
bool triangles_intersect_2d(const std::array<Point2, 3>& a, const std::array<Point2, 3>& b) {
  for (int i = 0; i < 3; ++i) {
    if (segment_triangle_intersect_2d(b[i], b[(i + 1) % 3], a[0], a[1], a[2])) return true;
  }
  return orient2(b[0], b[1], b[2]) != 0 && point_in_triangle_2d(a[0], b[0], b[1], b[2]);
}

// ----- 3-D helpers -----------------------------------------------------------------------------

// The closed segment [p, q] meets the closed non-degenerate triangle (a, b, c), given the sides
// side_p, side_q (orient3d(a, b, c, .)) of its end points and a projection axis of the
// triangle's plane. Off the plane, it meets the triangle iff its end points are not strictly on
// one side and its line passes through the closed triangle, i.e. the line's orientations against
// the three edges (orient3d(p, q, edge)) are not of mixed sign. In the plane, a 2-D test.
bool segment_meets_triangle(const Point& p, const Point& q, int side_p, int side_q, const Point& a,
                            const Point& b, const Point& c, int axis) {
  if (side_p * side_q > 0) return false;
  if (side_p == 0 && side_q == 0) {
    return segment_triangle_intersect_2d(project(p, axis), project(q, axis), project(a, axis),
                                         project(b, axis), project(c, axis));
  }
  const int s_ab = orient3d(p, q, a, b);
  const int s_bc = orient3d(p, q, b, c);
  const int s_ca = orient3d(p, q, c, a);
  const bool some_positive = s_ab > 0 || s_bc > 0 || s_ca > 0;
  const bool some_negative = s_ab < 0 || s_bc < 0 || s_ca < 0;
  return !(some_positive && some_negative);
}

// All three values are 0 or of one sign, and some is nonzero.
bool strictly_one_side(int s0, int s1, int s2) {
  return (s0 > 0 && s1 > 0 && s2 > 0) || (s0 < 0 && s1 < 0 && s2 < 0);
}

// The closed segment [p, q] meets a closed triangle whose vertices are collinear: the triangle
// is the union of its edges.
bool segment_flat_triangle_intersect(const Point& p, const Point& q, const Point& a, const Point& b,
                                     const Point& c) {
  return segments_intersect(p, q, a, b) || segments_intersect(p, q, b, c) ||
         segments_intersect(p, q, c, a);
}

}  // namespace

bool point_on_segment(const Point& x, const Point& p, const Point& q) {
  for (int k = 0; k < 3; ++k) {
    if (x[k] < std::min(p[k], q[k]) || x[k] > std::max(p[k], q[k])) return false;
  }
  return collinear(x, p, q);
}

// Segments in space meet only if coplanar; then they are compared in a projection of a plane
// that holds them (found from a non-collinear triple), or, when all four points are collinear,
// as intervals of their common line, which overlap exactly when their boxes do.
bool segments_intersect(const Point& p, const Point& q, const Point& r, const Point& s) {
  if (!boxes_overlap(std::array{&p, &q}, std::array{&r, &s})) return false;
  if (orient3d(p, q, r, s) != 0) return false;
  const std::array<std::array<const Point*, 3>, 4> triples = {
      {{&p, &q, &r}, {&p, &q, &s}, {&r, &s, &p}, {&r, &s, &q}}};
  for (const auto& [x, y, z] : triples) {
    const int axis = projection_axis(*x, *y, *z);
    if (axis >= 0) {
      return segments_intersect_2d(project(p, axis), project(q, axis), project(r, axis),
                                   project(s, axis));
    }
  }
  return true;  // collinear, and the boxes overlap
}

bool point_in_triangle(const Point& x, const Point& a, const Point& b, const Point& c) {
  const int axis = projection_axis(a, b, c);
  if (axis < 0) return segment_flat_triangle_intersect(x, x, a, b, c);
  if (orient3d(a, b, c, x) != 0) return false;
  return point_in_triangle_2d(project(x, axis), project(a, axis), project(b, axis),
                              project(c, axis));
}

bool segment_triangle_intersect(const Point& p, const Point& q, const Point& a, const Point& b,
                                const Point& c) {
  if (!boxes_overlap(std::array{&p, &q}, std::array{&a, &b, &c})) return false;
  const int axis = projection_axis(a, b, c);
  if (axis < 0) return segment_flat_triangle_intersect(p, q, a, b, c);
  return segment_meets_triangle(p, q, orient3d(a, b, c, p), orient3d(a, b, c, q), a, b, c, axis);
}

bool segment_crosses_triangle_interior(const Point& p, const Point& q, const Point& a,
                                       const Point& b, const Point& c) {
  const int side_p = orient3d(a, b, c, p);
  if (side_p == 0) return false;
  if (orient3d(a, b, c, q) != -side_p) return false;
  const int s_ab = orient3d(p, q, a, b);
  if (s_ab == 0) return false;
  return orient3d(p, q, b, c) == s_ab && orient3d(p, q, c, a) == s_ab;
}

// Two closed triangles meet iff an edge of one meets the other: their intersection is convex, and
// an extreme point of it lies on the boundary of one of them (for crossing planes, an end of the
// intersection segment on the common line; for coplanar ones, a vertex of the overlap polygon).
// Cheap rejections first: disjoint boxes, or one triangle strictly on one side of the other's
// plane. The vertices' sides are computed once and reused by the edge tests; coplanar triangles
// go straight to a 2-D test.
bool triangles_intersect(const Point& a0, const Point& a1, const Point& a2, const Point& b0,
                         const Point& b1, const Point& b2) {
  if (!boxes_overlap(std::array{&a0, &a1, &a2}, std::array{&b0, &b1, &b2})) return false;
  const std::array<const Point*, 3> a = {&a0, &a1, &a2};
  const std::array<const Point*, 3> b = {&b0, &b1, &b2};
  const int axis_a = projection_axis(a0, a1, a2);
  const int axis_b = projection_axis(b0, b1, b2);
  if (axis_a < 0 || axis_b < 0) {  // a flat triangle: the union of its edges
    for (int i = 0; i < 3; ++i) {
      if (segment_triangle_intersect(*a[i], *a[(i + 1) % 3], b0, b1, b2) ||
          segment_triangle_intersect(*b[i], *b[(i + 1) % 3], a0, a1, a2)) {
        return true;
      }
    }
    return false;
  }
  std::array<int, 3> side_of_b;  // sides of b's vertices relative to a's plane
  for (int i = 0; i < 3; ++i) side_of_b[i] = orient3d(a0, a1, a2, *b[i]);
  if (strictly_one_side(side_of_b[0], side_of_b[1], side_of_b[2])) return false;
  if (side_of_b == std::array<int, 3>{0, 0, 0}) {
    const auto project_all = [axis_a](const std::array<const Point*, 3>& t) {
      return std::array<Point2, 3>{project(*t[0], axis_a), project(*t[1], axis_a),
                                   project(*t[2], axis_a)};
    };
    return triangles_intersect_2d(project_all(a), project_all(b));
  }
  std::array<int, 3> side_of_a;  // sides of a's vertices relative to b's plane
  for (int i = 0; i < 3; ++i) side_of_a[i] = orient3d(b0, b1, b2, *a[i]);
  if (strictly_one_side(side_of_a[0], side_of_a[1], side_of_a[2])) return false;
  for (int i = 0; i < 3; ++i) {
    const int j = (i + 1) % 3;
    if (segment_meets_triangle(*a[i], *a[j], side_of_a[i], side_of_a[j], b0, b1, b2, axis_b) ||
        segment_meets_triangle(*b[i], *b[j], side_of_b[i], side_of_b[j], a0, a1, a2, axis_a)) {
      return true;
    }
  }
  return false;
}

// Barycentric signs: replacing vertex k by p gives a tet whose orientation, relative to the
// tet's own, is the sign of p's k-th barycentric coordinate.
int point_in_tet(const Point& p, const Point& a, const Point& b, const Point& c, const Point& d) {
  const int orientation = orient3d(a, b, c, d);
  if (orientation == 0) {
    const bool in_flat_hull = point_in_triangle(p, a, b, c) || point_in_triangle(p, a, b, d) ||
                              point_in_triangle(p, a, c, d) || point_in_triangle(p, b, c, d);
    return in_flat_hull ? 0 : -1;
  }
  const std::array<std::array<const Point*, 4>, 4> with_p_replacing = {
      {{&p, &b, &c, &d}, {&a, &p, &c, &d}, {&a, &b, &p, &d}, {&a, &b, &c, &p}}};
  bool on_boundary = false;
  for (const auto& [w, x, y, z] : with_p_replacing) {
    const int barycentric_sign = orient3d(*w, *x, *y, *z);
    if (barycentric_sign == -orientation) return -1;
    on_boundary = on_boundary || barycentric_sign == 0;
  }
  return on_boundary ? 0 : 1;
}

}  // namespace afmesh
