// Closest points between points, segments and triangles, in plain double arithmetic.
//
// These are measurements, not predicates: the distances and points carry the rounding error of a
// few dozen floating-point operations (relative to the coordinates' magnitude). Decisions that
// must be exact (do two triangles intersect? on which side of a plane is a point?) belong to
// predicates.h and intersect.h; use these functions for "how far apart" once the exact tests
// have said "apart".
//
// All shapes are closed point sets (a segment includes its end points, a triangle its edges).
// Degenerate inputs are handled as the point sets they are: a segment with equal ends is a point,
// a triangle with collinear vertices is the segment they span.
#pragma once

#include "core/mesh/mesh.h"

namespace afmesh {

// A pair of closest points: `first` on the first shape, `second` on the second, and the squared
// distance between them.
struct ClosestPair {
  Point first{0.0, 0.0, 0.0};
  Point second{0.0, 0.0, 0.0};
  double squared_distance = 0.0;
};

// The point of the closed segment [p, q] closest to x.
Point closest_point_on_segment(const Point& x, const Point& p, const Point& q);

// The point of the closed triangle (a, b, c) closest to x (Voronoi regions of the vertices,
// edges and interior; a degenerate triangle falls back to its three edges).
Point closest_point_on_triangle(const Point& x, const Point& a, const Point& b, const Point& c);

// Closest points of the closed segments [p0, q0] (first) and [p1, q1] (second). Parallel
// segments give one of the closest pairs.
ClosestPair closest_points_segments(const Point& p0, const Point& q0, const Point& p1,
                                    const Point& q1);

// Closest points of the closed triangles (a0, a1, a2) (first) and (b0, b1, b2) (second): the best
// of the six vertex-triangle and nine edge-edge pairs, which is the true minimum when the
// triangles do not intersect. For intersecting triangles the distance is not reliably 0; test
// intersection exactly first (intersect.h).
ClosestPair closest_points_triangles(const Point& a0, const Point& a1, const Point& a2,
                                     const Point& b0, const Point& b1, const Point& b2);

// Where the ray x + t u (t > 0) first meets the closed triangle (a, b, c): t (in units of |u|),
// or +infinity when it misses it, runs in its plane, or the triangle is degenerate (Moller and
// Trumbore, "Fast, minimum storage ray-triangle intersection", 1997). A measure too: a ray
// through an edge may be reported either way.
double ray_triangle_parameter(const Point& x, const Point& u, const Point& a, const Point& b,
                              const Point& c);

}  // namespace afmesh
