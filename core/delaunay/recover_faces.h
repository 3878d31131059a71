// Recovery of prescribed triangles in a tetrahedralisation, by flips and by refilling
// cavities, not in the paper.
//
// A Delaunay tetrahedralisation of a region's boundary points (delaunay_3d.h) need not have the
// region's boundary triangles among its faces. Local transformations can bring many of them in
// without new points (Joe 1991, "Construction of three-dimensional Delaunay triangulations using
// local transformations"; George, Hecht & Saltel 1991, "Automatic mesh generator with specified
// boundary", whose flips TetGen's boundary recovery uses too): a 2-3 flip replaces two elements
// sharing a face by three around the edge joining their far corners, and an edge removal
// (Shewchuk 2002; optimise_steps.h) the n elements around an edge by 2(n - 2) over a
// triangulation of its ring (n = 3: the 3-2 flip; n = 4 with a planar quadrilateral: the 4-4
// flip); on the boundary, the n elements around an edge whose two boundary faces are coplanar
// become 2(n - 1), turning the boundary quadrilateral's diagonal (n = 2: the 2-2 flip on a hull).
// Here the flips are chosen greedily: for a missing triangle, among the flips of the elements
// that meet it, the one that most reduces the number of elements meeting it
// (tet_triangle_intersect_improperly), never one that removes a prescribed triangle already
// present or an edge of one. No new point is added, so what needs one stays missing and is
// reported: a twisted prism (Schönhardt), and what the greedy choice cannot reach (CAD parts
// such as libcgal-demo's boeing, sliver scans); recover_faces_by_cavities below adds points.
//
// Every test is an exact predicate (core/geometry). Work: per triangle, the elements meeting it
// are found by a flood from its corners' elements (no scan of the whole complex); the work is
// bounded by a number of element-triangle tests.
#pragma once

#include <cstdint>
#include <functional>
#include <optional>
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

// Recovery of the triangles the flips leave missing, with new points inside, not in the paper. The
// missing triangles are taken in groups joined through edges that no tet has (mostly two sliver
// triangles whose shared edge is missing), with any missing triangle through their cavity. A
// group's cavity is the tets meeting its triangles; the front triangles inside it (the group's, and
// those that are faces of two of its tets) split it into regions, told apart at each edge by the
// sides' orientations or, where those do not decide, by the sides' order around the edge (exact
// orient3d). Each region on the inner side of the front is refilled with the tets joining its
// boundary to one point that sees all of it from inside (its kernel): one of its corners, or else a
// new point (a Steiner point), the deepest inside (a small linear programme); or else, where the
// kernel is empty, by `fill` below. The regions on the outer side of the front are left empty: the
// tets no longer cover the whole hull. A cavity that cannot be refilled so is tried again grown by
// a layer of tets (five times at most), and then left as it was. Every new tet is checked positive
// by exact orient3d, and a refill replaces its cavity only when the faces pair up
// (TetComplex::replace).
//
// `front`: closed, outward-oriented triangles of `points` (a region's side is its inner side);
// `tets`, a positive tetrahedralisation of `points` (after recover_faces_by_flips); `missing`,
// the front triangles (indices) not faces of it. New points are appended to `points`. Returns
// the triangles still missing, ascending. Stops early, as if nothing were recovered, once `stop`
// (when given) finds the caller cancelled. Work: a group of at most 256 triangles and a cavity
// of at most 4,096 tets, each group tried at most six times (grown a layer each time); the
// missing triangles through a cavity are found in a box tree of the missing triangles.
//
// `fill`, when given, fills a region no point sees whole: called with the region's corners and then
// one point inside it or near (`points`), and its sides (closed, outward-oriented triangles of the
// corners), it appends any new points to `points` and returns positive tets on them that fill the
// region, each side a face of one of them; or nothing when it cannot (conforming_fill.h fills
// regions so, recursively).
using RegionFill = std::function<std::optional<std::vector<Tet>>(
    std::vector<Point>& points, std::span<const Triangle> sides)>;
std::vector<Index> recover_faces_by_cavities(std::vector<Point>& points, std::vector<Tet>& tets,
                                             std::span<const Triangle> front,
                                             std::span<const Index> missing,
                                             CancelCheck* stop = nullptr,
                                             const RegionFill& fill = {});

}  // namespace afmesh
