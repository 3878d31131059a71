// The surface front of paper §3, steps S1–S11: one patch of a discrete surface triangulated
// from the sides along its lines, with the dimension-generic front of core/front/ (items of
// Arity 2: sides).
//
// A side (a, b) of the front has the unmeshed part of its patch on its left, seen from the
// surface normal; the triangle built on it is (a, b, p), oriented as the input.
//
//  S1  pop the side forming the smallest new face (AdvancingFront<2>, FrontQueue).
//  S2  the host face of the side's midpoint, by a walk restricted to the patch
//      (locate_in_patch), so that no point is ever placed across a ridge.
//  S3  the host's unit normal n.
//  S4  the best point: above the midpoint in the patch's tangent plane, left of the side, at the
//      height that makes its two new sides the wanted size (eq. 15, front_sizes.h), moved onto
//      the surface (S8 done before the checks, so they see where the point will be).
//  S5  front points near the best point are tried in lieu of it, nearest first.
//  S6  the new face must not cross a front side nor cover a front point, checked in the plane
//      of the side's midpoint and n with exact orientation tests (paper Figure 6).
//  S7  the face is added; S10 the sides it closes leave the front, its other sides join it
//      with their sizes (S9).
//  S11 until the patch's front is empty.
// A side that fails is tried again later with relaxed rules (as the volume front does); one
// that fails in every class and bounds no small hole makes the front back off (not in the
// paper; as the volume front's cavity re-meshing): the patch's triangles near it are removed
// and the cavity's boundary goes back on the front. Only when that has been tried too often
// does the patch stop with FAILED_PRECONDITION naming where.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <optional>
#include <span>
#include <utility>
#include <vector>

#include "absl/container/flat_hash_set.h"
#include "absl/status/status.h"
#include "core/common/progress.h"
#include "core/mesh/mesh.h"
#include "core/sizing/size_field.h"
#include "core/spatial/box.h"
#include "core/surface/discrete_surface.h"
#include "core/surface/features.h"

namespace afmesh {

using Side = std::array<Index, 2>;

// What the patches of one surface share while they are meshed in turn.
struct SurfaceMeshState {
  SurfaceMeshState(const DiscreteSurface& surface_in, const SurfaceFeatures& features_in,
                   const SizeField& field_in, double growth_in)
      : surface(surface_in), features(features_in), field(field_in), growth(growth_in) {}

  const DiscreteSurface& surface;
  const SurfaceFeatures& features;
  const SizeField& field;  // in global coordinates: local points are shifted by the origin
  double growth;           // c_i of eq. 15 (at least kMinAttachedGrowth)

  // The output's points, local frame: the corners and line points first, then each patch's.
  std::vector<Point> points;
  std::vector<double> point_size;  // delta of each point (eq. 15)
  std::vector<FaceId> host;        // a host face of each point (S2)
  // For a line point: an input vertex of the line segment it lies on (the walk into a patch
  // starts from a face around it); kInvalidIndex for a patch's interior points.
  std::vector<Index> anchor;
  // A triangle removed by a back-off has triangles[t][0] == kInvalidIndex until its patch is
  // done (compact_patch).
  std::vector<Triangle> triangles;
  std::vector<Index> triangle_tags;   // the input tag of each triangle's patch
  std::vector<Index> triangle_patch;  // the patch each triangle was meshed in
  // The sides along the discrete lines, as (min, max) point pairs: kept by every clean-up.
  absl::flat_hash_set<std::pair<Index, Index>> line_sides;
  // The corners and line points are points [0, line_points) (set once the lines are split).
  Index line_points = 0;
  // The points of each discrete line in its order (ids: its first corner, the points between,
  // its last corner) and the polyline segment each lies on (LineSplit::segment), one entry per
  // features.lines; for a patch re-triangulated from its input (patch_from_input.h).
  struct LinePoints {
    std::vector<Index> ids;
    std::vector<Index> segment;
  };
  std::vector<LinePoints> points_along_lines;
  // The edges of the patches meshed so far that join two line points off the lines, as (min,
  // max): two patches that meet at a corner where their lines turn can each cut the corner by
  // the same chord, and the surface would carry one edge four times (not in the paper).
  absl::flat_hash_set<std::pair<Index, Index>> chords_between_line_points;
  // Where a patch's front stopped (local frame: its side's first point) and the reach within
  // which the failure message describes the input (three times the larger of the side's length
  // and its target size); set by mesh_patch when it stops (not in the paper).
  struct StoppedAt {
    Point x;
    double reach = 0.0;
  };
  std::optional<StoppedAt> stopped_at;
  // Whether edge (a, b) joins two line points and a patch meshed before has it off the lines.
  bool chord_of_another_patch(Index a, Index b) const {
    return a < line_points && b < line_points &&
           chords_between_line_points.contains({std::min(a, b), std::max(a, b)});
  }

  // The wanted size at x (local frame): the size field there.
  double field_size(const Point& x) const { return field.size_at(surface.to_global(x)); }
  Index add_point(const Point& x, double size, FaceId host_face, Index anchor_vertex);
  // Takes back the last add_point (a new point whose face was refused).
  void drop_last_point();
  void add_triangle(const Triangle& t, PatchId patch);
  // The one place where removed elements go: drops the removed triangles from `first_triangle`
  // on, and the points from `first_point` on that no remaining triangle from `first_triangle`
  // on uses, renumbering the rest (every array kept parallel). The points and triangles before
  // are untouched: a patch's own points are used by its triangles only.
  void compact_patch(Index first_point, std::size_t first_triangle);
  // Takes a patch back: drops every triangle from `first_triangle` on and the points from
  // `first_point` on (compact_patch), so that the state is as before the patch was begun.
  void take_back_patch(Index first_point, std::size_t first_triangle);
};

// S2 within one patch: the face of `patch` nearest to x (local frame), walking from `hint` (a
// face of the patch) to the edge or vertex neighbour of the patch that is strictly nearer, until
// none is (our rule, as DiscreteSurface::locate's, but never leaving the patch: a point near a
// ridge stays on its own side). At most `max_steps` moves.
Located locate_in_patch(const DiscreteSurface& surface, const SurfaceFeatures& features,
                        PatchId patch, const Point& x, FaceId hint, int max_steps = 256);

// A face of `patch` to start a walk for point p from: its host when that is in the patch, else
// a face of the patch around its anchor vertex, else the patch's first face.
FaceId patch_hint(const SurfaceMeshState& s, PatchId patch, Index p);

// The pairs (i, j), i < j, of sides of one patch's initial front (`sides`, each with the patch
// on its left) that cross or touch away from a point they share, each pair in the plane of side
// i (its first point's face of the patch); sides whose points lie farther off that plane than
// side i is long are another sheet and are not compared. Not in the paper: the chords of two
// lines running closer than their sides' sagitta (a ledge narrower than the size, gmsh_lever)
// pass beyond each other's points, and a front that starts folded cannot close. Sides are
// found through FrontBins of cells of their mean length, by their bounding boxes: O(n) for
// sides of similar lengths.
std::vector<std::pair<std::size_t, std::size_t>> crossing_sides(const SurfaceMeshState& s,
                                                                PatchId patch,
                                                                std::span<const Side> sides);

// The patch's triangles from `first` on are a closed cover of the region its initial `sides`
// bound: every directed edge used once, and its reverse too unless it is an initial side, which
// every one is. FAILED_PRECONDITION naming the first edge that is not. O(N log N).
absl::Status check_patch_closed(const SurfaceMeshState& s, PatchId patch,
                                const std::vector<Side>& sides, std::size_t first);

// Records the edges of the patch's triangles (from `first` on) that join two line points off
// the lines, for the patches meshed after it (SurfaceMeshState::chords_between_line_points).
void keep_chords_between_line_points(SurfaceMeshState& s, std::size_t first);

struct PatchFrontParams {
  // The front stops with FAILED_PRECONDITION after this many steps per side it started with
  // plus per triangle built (a bound proportional to the patch's size; not in the paper).
  std::int64_t steps_per_item = 8;
  std::int64_t step_slack = 100000;
  // ... and once it has built more triangles than this (> 0): a patch meshed far finer than
  // its size field asks (about its area over the area of a triangle of the local size) is
  // going wrong, wherever it is, and would otherwise never stop.
  std::int64_t max_triangles = std::numeric_limits<std::int64_t>::max();
  // ... or once its triangles cover more than this area: a cover of the patch has about its
  // input faces' area, and a front that runs over its own triangles (across a ridge that ends
  // inside the patch, where the patch lies on both sides) piles layer on layer.
  double max_area = std::numeric_limits<double>::infinity();
  // A side that cannot be closed makes the front back off (re-open the triangles around it) at
  // most this many times in the patch, and at most 6 times in the same region
  // (kMaxBackOffsAtPlace in surface_front.cc; not in the paper).
  std::int64_t max_back_offs = 50;
};

// S1–S11 for `patch` from its initial sides (each oriented with the patch on its left; corners
// and line points already in s.points), or, when there are none (a patch without lines), from a
// seed triangle laid on its first face. `domain` bounds the patch (its bins' box). Appends the
// patch's triangles (tag: the patch's input tag) and its new points to s (those a back-off left
// unused are dropped, compact_patch). CANCELLED once progress is cancelled; FAILED_PRECONDITION
// when a side cannot be closed even after the back-offs allowed, or when the result is not a
// closed cover of the patch, naming where.
absl::Status mesh_patch(SurfaceMeshState& s, PatchId patch, const std::vector<Side>& sides,
                        const Box& domain, const PatchFrontParams& params, Progress& progress);

}  // namespace afmesh
