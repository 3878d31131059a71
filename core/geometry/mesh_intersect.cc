// Intersection tests between elements of one mesh that discount the vertices they share (the
// `..._improperly` functions of intersect.h).
//
// Two closed convex sets that share a vertex v meet in more than {v} exactly when their tangent
// cones at v overlap beyond v. The helpers below decide that with the point-set tests of
// intersect.h, case by case on which element is flat (collinear vertices).

#include <algorithm>
#include <array>
#include <cstddef>

#include "core/geometry/intersect.h"
#include "core/geometry/predicates.h"

namespace afmesh {
namespace {

// The closed segments [v, x] and [v, y], which start at the same point v, share a point other
// than v: both are proper and one's far end lies on the other.
bool segments_from_vertex_overlap(const Point& v, const Point& x, const Point& y) {
  if (x == v || y == v) return false;
  return point_on_segment(y, v, x) || point_on_segment(x, v, y);
}

// The closed segment [v, x] and the closed triangle (v, u1, u2), which share the point v, meet
// somewhere other than v.
//   Non-flat triangle: [v, x] runs from v into the triangle exactly when x lies in it or the
//   segment reaches the opposite edge [u1, u2] (which does not contain v).
//   Flat triangle: it is the union of [v, u1] and [v, u2].
bool segment_meets_beyond_vertex(const Point& v, const Point& x, const Point& u1, const Point& u2) {
  if (x == v) return false;
  if (collinear(v, u1, u2)) {
    return segments_from_vertex_overlap(v, x, u1) || segments_from_vertex_overlap(v, x, u2);
  }
  return point_in_triangle(x, v, u1, u2) || segments_intersect(v, x, u1, u2);
}

// Closed triangles T = (v, t1, t2) and U = (v, u1, u2), sharing only the vertex v, meet in more
// than {v}.
//   Both non-flat: a ray from v into both triangles leaves them through their opposite edges;
//   the nearer exit lies in the other triangle. So they overlap beyond v iff [t1, t2] meets U or
//   [u1, u2] meets T (neither opposite edge contains v).
//   A flat triangle is the union of its two segments from v.
bool triangles_meet_beyond_vertex(const Point& v, const Point& t1, const Point& t2, const Point& u1,
                                  const Point& u2) {
  if (collinear(v, t1, t2)) {
    return segment_meets_beyond_vertex(v, t1, u1, u2) || segment_meets_beyond_vertex(v, t2, u1, u2);
  }
  if (collinear(v, u1, u2)) {
    return segment_meets_beyond_vertex(v, u1, t1, t2) || segment_meets_beyond_vertex(v, u2, t1, t2);
  }
  return segment_triangle_intersect(t1, t2, v, u1, u2) ||
         segment_triangle_intersect(u1, u2, v, t1, t2);
}

// A flat triangle (v, w, x) (x on the line of v, w) and a triangle (v, w, y) meet beyond the
// shared edge [v, w]: the flat one is [v, w] extended past w or past v up to x, and that
// extension must enter the other triangle.
bool flat_triangle_meets_beyond_edge(const Point& v, const Point& w, const Point& x,
                                     const Point& y) {
  if (point_on_segment(x, v, w)) return false;  // the flat triangle is [v, w] itself
  if (point_on_segment(w, v, x)) return segment_meets_beyond_vertex(w, x, v, y);
  return segment_meets_beyond_vertex(v, x, w, y);
}

// Closed triangles T = (v, w, t) and U = (v, w, u), sharing the edge [v, w], meet in more than
// that edge. Both non-flat: only when coplanar with t and u on the same side of the edge's line
// (the triangles fold onto each other); otherwise the planes meet in the edge's line, or the
// triangles lie in opposite half-planes.
bool triangles_meet_beyond_edge(const Point& v, const Point& w, const Point& t, const Point& u) {
  if (collinear(v, w, t)) return flat_triangle_meets_beyond_edge(v, w, t, u);
  if (collinear(v, w, u)) return flat_triangle_meets_beyond_edge(v, w, u, t);
  if (orient3d(v, w, t, u) != 0) return false;
  for (int axis = 0; axis < 3; ++axis) {
    const int side_t = orient2d_projected(v, w, t, axis);
    if (side_t != 0) return orient2d_projected(v, w, u, axis) == side_t;
  }
  return false;  // unreachable: (v, w, t) is not collinear
}

// The closed axis-aligned bounding boxes of two point sets are disjoint.
template <std::size_t NA, std::size_t NB>
bool boxes_disjoint(const std::array<const Point*, NA>& a, const std::array<const Point*, NB>& b) {
  for (int k = 0; k < 3; ++k) {
    double a_min = (*a[0])[k], a_max = a_min, b_min = (*b[0])[k], b_max = b_min;
    for (const Point* p : a) a_min = std::min(a_min, (*p)[k]), a_max = std::max(a_max, (*p)[k]);
    for (const Point* p : b) b_min = std::min(b_min, (*p)[k]), b_max = std::max(b_max, (*p)[k]);
    if (a_max < b_min || b_max < a_min) return true;
  }
  return false;
}

// Which vertices of t appear in u (by index) and how many.
struct SharedVertices {
  std::array<bool, 3> in_t = {false, false, false};
  std::array<bool, 3> in_u = {false, false, false};
  int count = 0;
};

SharedVertices shared_vertices(const Triangle& t, const Triangle& u) {
  SharedVertices shared;
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      if (t[i] == u[j]) {
        shared.in_t[i] = shared.in_u[j] = true;
        ++shared.count;
      }
    }
  }
  return shared;
}

// Position of the first vertex whose flag equals `flag`.
int first_with(const std::array<bool, 3>& flags, bool flag) {
  for (int i = 0; i < 3; ++i) {
    if (flags[i] == flag) return i;
  }
  return -1;
}

}  // namespace

bool triangles_intersect_improperly(std::span<const Point> points, const Triangle& t,
                                    const Triangle& u) {
  const SharedVertices shared = shared_vertices(t, u);
  const auto at = [&](Index i) -> const Point& { return points[i]; };
  switch (shared.count) {
    case 0:
      return triangles_intersect(at(t[0]), at(t[1]), at(t[2]), at(u[0]), at(u[1]), at(u[2]));
    case 1: {
      const int i = first_with(shared.in_t, true);
      const int j = first_with(shared.in_u, true);
      return triangles_meet_beyond_vertex(at(t[i]), at(t[(i + 1) % 3]), at(t[(i + 2) % 3]),
                                          at(u[(j + 1) % 3]), at(u[(j + 2) % 3]));
    }
    case 2: {
      const int i = first_with(shared.in_t, false);
      const int j = first_with(shared.in_u, false);
      return triangles_meet_beyond_edge(at(t[(i + 1) % 3]), at(t[(i + 2) % 3]), at(t[i]), at(u[j]));
    }
    default:
      return true;  // the same triangle twice
  }
}

bool segment_triangle_intersect_improperly(std::span<const Point> points, Index p, Index q,
                                           const Triangle& t) {
  const auto at = [&](Index i) -> const Point& { return points[i]; };
  int p_in_t = -1;
  int q_in_t = -1;
  for (int i = 0; i < 3; ++i) {
    if (t[i] == p) p_in_t = i;
    if (t[i] == q) q_in_t = i;
  }
  if (p_in_t >= 0 && q_in_t >= 0) return false;  // an edge of t
  if (p_in_t < 0 && q_in_t < 0) {
    return segment_triangle_intersect(at(p), at(q), at(t[0]), at(t[1]), at(t[2]));
  }
  const int v = p_in_t >= 0 ? p_in_t : q_in_t;
  const Index other = p_in_t >= 0 ? q : p;
  return segment_meets_beyond_vertex(at(t[v]), at(other), at(t[(v + 1) % 3]), at(t[(v + 2) % 3]));
}

// With S the shared vertices and K the tet, K ∩ t is a convex polygon; it exceeds hull(S) iff one
// of its extreme points lies outside hull(S). Such a point is either on a face G of K, where it
// makes G and t meet improperly (G ∩ hull(S) is the hull of G's shared vertices), or strictly
// inside K, where it can only be a vertex of t. Cheap rejections first: disjoint bounding boxes,
// or t strictly outside one face's plane.
bool tet_triangle_intersect_improperly(std::span<const Point> points, const Tet& tet,
                                       const Triangle& t) {
  const auto at = [&](Index i) -> const Point& { return points[i]; };
  const int orientation = orient3d(at(tet[0]), at(tet[1]), at(tet[2]), at(tet[3]));
  if (orientation == 0) return true;
  if (boxes_disjoint(std::array{&at(tet[0]), &at(tet[1]), &at(tet[2]), &at(tet[3])},
                     std::array{&at(t[0]), &at(t[1]), &at(t[2])})) {
    return false;
  }

  int shared = 0;
  for (const Index i : t) shared += int(i == tet[0] || i == tet[1] || i == tet[2] || i == tet[3]);
  if (shared == 3) return false;  // t is a face of the tet

  // barycentric[j][k]: sign of the k-th barycentric coordinate of t's vertex j in the tet, i.e.
  // the orientation of the tet with corner k replaced by that vertex, relative to the tet's own.
  std::array<std::array<int, 4>, 3> barycentric;
  for (int k = 0; k < 4; ++k) {
    for (int j = 0; j < 3; ++j) {
      std::array<const Point*, 4> corners = {&at(tet[0]), &at(tet[1]), &at(tet[2]), &at(tet[3])};
      corners[k] = &at(t[j]);
      barycentric[j][k] =
          orientation * orient3d(*corners[0], *corners[1], *corners[2], *corners[3]);
    }
    if (barycentric[0][k] < 0 && barycentric[1][k] < 0 && barycentric[2][k] < 0) return false;
  }
  for (const auto& signs : barycentric) {
    if (signs[0] > 0 && signs[1] > 0 && signs[2] > 0 && signs[3] > 0) return true;
  }
  const std::array<Triangle, 4> faces = {
      Triangle{tet[1], tet[2], tet[3]}, Triangle{tet[0], tet[2], tet[3]},
      Triangle{tet[0], tet[1], tet[3]}, Triangle{tet[0], tet[1], tet[2]}};
  for (const Triangle& face : faces) {
    if (triangles_intersect_improperly(points, face, t)) return true;
  }
  return false;
}

}  // namespace afmesh
