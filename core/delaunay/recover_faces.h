// Recovery of prescribed triangles in a tetrahedralisation by flips, not in the paper.
//
// A Delaunay tetrahedralisation of a region's boundary points (delaunay_3d.h) need not have the
// region's boundary triangles among its faces. Local transformations can bring many of them in
// without new points (Joe 1991, "Construction of three-dimensional Delaunay triangulations using
// local transformations"; George, Hecht & Saltel 1991, "Automatic mesh generator with specified
// boundary", whose flips TetGen's boundary recovery uses too): a 2-3 flip replaces two elements
// sharing a face by three around the edge joining their far corners, a 3-2 flip the reverse, and
// a 4-4 flip (two coplanar faces inside) or a 2-2 flip (two coplanar faces on the hull) turns
// the diagonal of a planar quadrilateral. Here the flips are chosen greedily: for a missing
// triangle, among the flips of the elements that meet it, the one that most reduces the number
// of elements meeting it (tet_triangle_intersect_improperly), never one that removes a
// prescribed triangle already present. No new point is added, so what needs one stays missing
// and is reported: a twisted prism (Schönhardt), and what the greedy choice cannot reach (a
// planar cap of many points on one circle fanned from one of them, whose diagonals only flips
// of more than two hull elements turn; CAD parts such as libcgal-demo's boeing).
//
// Every test is an exact predicate (core/geometry). Work: per triangle, the elements meeting it
// are found by a flood from its corners' elements (no scan of the whole complex); the work is
// bounded by a number of element-triangle tests.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "core/common/progress.h"
#include "core/mesh/mesh.h"

namespace afmesh {

// Flips the positive tetrahedra `tets` of `points` (a tetrahedralisation: elements meet face to
// face) until every triangle of `faces` (vertices of `points`, either orientation) is a face of
// one of them, or no flip that helps is left, or `max_tests` element-triangle tests
// (tet_triangle_intersect_improperly) have been made. `tets` stays a positive
// tetrahedralisation of the same region. Returns the triangles (indices into `faces`, ascending)
// that are not faces of `tets` at the end (none: all recovered). Stops early, as if out of
// work, once `stop` (when given) finds the caller cancelled.
std::vector<Index> recover_faces_by_flips(std::span<const Point> points, std::vector<Tet>& tets,
                                          std::span<const Triangle> faces,
                                          std::int64_t max_tests, CancelCheck* stop = nullptr);

}  // namespace afmesh
