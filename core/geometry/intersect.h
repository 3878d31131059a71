// Exact intersection tests between points, segments, triangles and tetrahedra, built only on the
// exact predicates of predicates.h (no tolerances): every answer is the one exact arithmetic on
// the double inputs would give.
//
// All shapes are closed point sets: a segment includes its end points, a triangle its edges and
// vertices, a tet its faces. Degenerate inputs (a segment with equal ends, a triangle with
// collinear vertices) are handled as the point sets they are (a point, a segment) unless a
// function says otherwise.
//
// Mesh variants (the `..._improperly` functions) take vertex indices into a point array and
// decide whether two elements meet in more than the vertices they share imply; "shared" means
// the same index, so two distinct indices at the same location are two different vertices that
// touch, which is improper.
#pragma once

#include <span>

#include "core/mesh/mesh.h"

namespace afmesh {

// -----------------------------------------------------------------------------------------------
// point_on_segment(x, p, q): x lies on the closed segment [p, q] (for p == q: x == p). Exact.
// -----------------------------------------------------------------------------------------------
bool point_on_segment(const Point& x, const Point& p, const Point& q);

// -----------------------------------------------------------------------------------------------
// segments_intersect(p, q, r, s): the closed segments [p, q] and [r, s] share at least one point
// (crossing, touching at an end point, or overlapping along a common line). Exact.
// -----------------------------------------------------------------------------------------------
bool segments_intersect(const Point& p, const Point& q, const Point& r, const Point& s);

// -----------------------------------------------------------------------------------------------
// point_in_triangle(x, a, b, c): x lies in the closed triangle (a, b, c): in its plane and inside
// or on its boundary. For collinear a, b, c: x lies on the segment they span. Exact.
// -----------------------------------------------------------------------------------------------
bool point_in_triangle(const Point& x, const Point& a, const Point& b, const Point& c);

// -----------------------------------------------------------------------------------------------
// segment_triangle_intersect(p, q, a, b, c): the closed segment [p, q] and the closed triangle
// (a, b, c) share at least one point: the segment crosses or touches the triangle, or lies in its
// plane and overlaps it. Exact; degenerate segment / triangle allowed.
// -----------------------------------------------------------------------------------------------
bool segment_triangle_intersect(const Point& p, const Point& q, const Point& a, const Point& b,
                                const Point& c);

// -----------------------------------------------------------------------------------------------
// segment_crosses_triangle_interior(p, q, a, b, c): the strict, transversal case only: p and q lie
// strictly on opposite sides of the plane of (a, b, c) and the segment passes through the
// triangle's relative interior (not through an edge or vertex). False for every touching,
// coplanar or degenerate configuration. Exact. Cheaper than segment_triangle_intersect: five
// orient3d calls at most.
// -----------------------------------------------------------------------------------------------
bool segment_crosses_triangle_interior(const Point& p, const Point& q, const Point& a,
                                       const Point& b, const Point& c);

// -----------------------------------------------------------------------------------------------
// triangles_intersect(a0, a1, a2, b0, b1, b2): the closed triangles share at least one point
// (crossing, touching at a vertex or along an edge, coplanar overlap). Exact; symmetric in the
// two triangles and invariant under permutations of each triangle's vertices.
// -----------------------------------------------------------------------------------------------
bool triangles_intersect(const Point& a0, const Point& a1, const Point& a2, const Point& b0,
                         const Point& b1, const Point& b2);

// -----------------------------------------------------------------------------------------------
// point_in_tet(p, a, b, c, d): +1 when p lies strictly inside tet (a, b, c, d), 0 when on its
// boundary (a face, edge or vertex), -1 when outside. Either orientation of the tet is accepted.
// A flat tet (orient3d(a, b, c, d) == 0) has no inside: 0 when p lies in the flat set (the hull
// of the four points), -1 otherwise. Exact.
// -----------------------------------------------------------------------------------------------
int point_in_tet(const Point& p, const Point& a, const Point& b, const Point& c, const Point& d);

// -----------------------------------------------------------------------------------------------
// triangles_intersect_improperly(points, t, u): for two triangles of one mesh (indices into
// `points`, N×3), true when they intersect in anything other than what their shared vertices
// imply:
//   no shared vertex     -> any contact is improper;
//   one shared vertex v  -> improper unless the intersection is exactly {v};
//   two shared (an edge) -> improper unless the intersection is exactly that edge (e.g. two
//                           triangles folded onto each other, coplanar and overlapping);
//   three shared         -> always improper (a duplicate triangle).
// This is the self-intersection test of a surface validator. Exact. Degenerate (zero-area)
// triangles are treated as the segments they are. Precondition: each triangle has three distinct
// indices.
// -----------------------------------------------------------------------------------------------
bool triangles_intersect_improperly(std::span<const Point> points, const Triangle& t,
                                    const Triangle& u);

// -----------------------------------------------------------------------------------------------
// segment_triangle_intersect_improperly(points, p, q, t): for a mesh edge (p, q) and a mesh
// triangle t, true when they intersect in anything other than what their shared vertices imply:
//   no shared vertex -> any contact;   one shared vertex v -> anything beyond {v};
//   both shared      -> never (the edge is an edge of t).
// For an advancing front: a candidate element's new edges against nearby front faces. Exact.
// Precondition: p != q, t has three distinct indices.
// -----------------------------------------------------------------------------------------------
bool segment_triangle_intersect_improperly(std::span<const Point> points, Index p, Index q,
                                           const Triangle& t);

// -----------------------------------------------------------------------------------------------
// tet_triangle_intersect_improperly(points, tet, t): for a tet and a triangle of one mesh, true
// when the closed tet and the closed triangle intersect in anything other than the convex hull of
// their shared vertices (nothing, a vertex, an edge, or the whole triangle when t is a face of
// the tet). For an advancing front: a candidate tet against every nearby front face, which covers
// the tet's edges crossing front faces, front edges crossing the tet's faces, and front faces
// inside the tet. Exact.
// Precondition: the tet has nonzero volume (either orientation) and four distinct indices, t has
// three distinct indices. A flat tet is reported as improper (true), so a caller never accepts it.
// -----------------------------------------------------------------------------------------------
bool tet_triangle_intersect_improperly(std::span<const Point> points, const Tet& tet,
                                       const Triangle& t);

}  // namespace afmesh
