// Element sizes from the curvature of a discrete surface (paper §4.4, eq. 20–22).
//
// For two adjacent faces whose normals differ by alpha_g and whose centroids are l_g apart, a
// circle through them has l_g / 2r = tan(alpha_g / 2) (eq. 20), so elements that turn by no more
// than a prescribed alpha_p are (eq. 21)
//   l_p = l_g tan(alpha_p / 2) / tan(alpha_g / 2)
// long, and the points of the edge take delta_i = min(delta_i, l_p) (eq. 22). Edges on discrete
// lines (ridges, boundaries, tag changes) are features, not curvature, and are left out.
// A line's own turn (along it, at its vertices) bounds the sizes of its vertices by the same
// eq. 20–22 over its pieces, at the element's scale (not in the paper; curvature_sizes.cc,
// LineTurns): its sides are chords of it, and a hole's rim split by the size alone lay 2.3% of
// the model from the input on netgen_part1.
//
// Two readings are ours, not the paper's, both with `deviation` > 0 only (without it the sizes
// are as before). The distance l_g is taken across the edge (the part of the centroids' distance
// normal to the edge): only that part bends, and a sliver's centroid lies far along its edge.
// And the angle bound is joined by a chord bound, one of the "other
// measures of surface accuracy" §4.4 leaves open: eq. 20 gives the radius r = l_g / (2
// tan(alpha_g / 2)), and an element sqrt(8 r epsilon) long has its midpoint epsilon from the arc
// (the sagitta l^2 / 8r). Eq. 21 alone lets an element of length l lie l tan(alpha_p / 2) / 4
// from the arc, 0.067 l at 30°: at the sizes of a CAD part (diag / 40) that is 0.17% of the
// model. The chord bound is the finer one wherever eq. 21's length is over 4 epsilon /
// tan(alpha_p / 2) (at 30° and epsilon = 0.0003 diag: diag / 223). The input is a polyhedron,
// not the circle eq. 20 fits to it: a chord of length l across a crease where two faces turn
// by alpha (a facet edge of a coarse CAD tessellation, a vertex of a line's polyline) lies up
// to (l / 2) sin(alpha / 2) from it when l is shorter than the faces, more than the sagitta
// l^2 / 8r of the circle (the two agree at l = l_g). So the chord bound is joined by this kink
// bound, l <= 2 epsilon / sin(alpha / 2), wherever it is smaller (ours): a 64-gon of radius 2
// split by the sagitta alone at epsilon 0.002 had sides of 0.179 cutting its vertices by 0.0044,
// and simbody_UR10_Wrist2, whose 0.004-wide facets turn by 29° (under the ridge angle), came
// out 0.26% of its diagonal from the input at epsilon = 0.03%. epsilon here bounds one chord of
// the size; generate_surface_mesh asks for a fraction of the user's deviation
// (kDeviationMargin) so that the triangles it makes, longer and wider than one chord, keep it.
//
// The turn is read at the element's scale (not in the paper, which measures it between the faces
// of a grid of about the size in force). On a scan whose faces are smaller than the size, noise
// turns neighbouring faces by degrees over a fraction of an element, and eq. 21 between the faces
// reads that as curvature (a scanned sphere at h = 0.012: 1.2M triangles where ~200k are asked).
// So where eq. 21 between an edge's faces asks for less than the base size, the edge is judged
// at scales rho: the base size (at most 16 face spacings, which bounds the work), then halved
// while a disk still reaches past the two faces. At each, the faces within 0.6 rho of the edge's
// midpoint (an element's circumradius; reached without crossing a line) are split by the edge
// into two halves, and eq. 21 is taken between the halves' mean normals, over the distance
// between their centroids. The first rho whose size is at least rho gives the size (no more than
// the last rho passed over); when none does, eq. 21 between the faces does. A turn counts only
// where it persists at the scale of the element it limits: noise averages out within the halves,
// while a rounding narrower than the disk turns by as much between the halves as its faces do in
// all, so it is passed over until rho fits it and keeps its own size. The
// sizes attached to the input's points (these and the gaps of gap_sizes.h) are then graded by
// the growth factor c_i: delta_j <= delta_i + (c_i - 1) |x_j - x_i| along the surface's edges
// (the continuous form of eq. 15; not in the paper's §4.4, which grades through the background
// grid), so a small hole does not put a size jump into its surroundings. The paper iterates this
// with remeshing through an adapted background grid (AdaptBackground); MeshSurface applies it
// once, on the input.
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "absl/status/statusor.h"
#include "core/common/progress.h"
#include "core/mesh/mesh.h"
#include "core/sizing/size_field.h"
#include "core/surface/discrete_surface.h"
#include "core/surface/features.h"

namespace afmesh {

// delta_i for every input point of `surface` (N values; +infinity where the surface is flat or
// only meets lines), not graded. `alpha_p_deg` in (0, 180), or 0: no angle bound; `deviation`
// (epsilon, in the units of the points) > 0, or 0: no chord bound; `base` is the size in force
// without the curvature (the largest scale at which a turn is read). CANCELLED soon after
// progress.cancelled() turns true: it is looked at every few hundred faces and every line (a
// 1M-face scan asked for a coarse size spends tens of seconds here). With `face_sizes`, it also
// gets for every input face (M values) the smallest of the sizes eq. 21–22 and the bounds above
// gave its edges (+infinity for none), not graded: CurvatureLimitedSize's face caps.
absl::StatusOr<std::vector<double>> curvature_point_sizes(
    const DiscreteSurface& surface, const SurfaceFeatures& features, double alpha_p_deg,
    double deviation, const SizeField& base, Progress& progress = no_progress(),
    std::vector<double>* face_sizes = nullptr);

// Grades point sizes (N values, +infinity for none) in place: each becomes the smallest
// delta_i + (c_i - 1) |x_j - x_i| over paths along the surface's edges (Dijkstra, O(N log N)).
// growth >= 1. CANCELLED soon after progress.cancelled() turns true (`size` then half graded).
absl::Status grade_point_sizes(const DiscreteSurface& surface, double growth,
                               std::vector<double>& size, Progress& progress = no_progress());

// min(base(x), the size attached to the input's points at x): the linear interpolation of the
// delta_i at the corners of the input face nearest to x, at the closest point of that face to x
// (x in global coordinates, as every SizeField). The input surface serves as a background grid
// for its attached sizes, interpolated as the tetrahedral grid is (background_grid.h; paper
// §4.4 grades through such a grid); the graded delta_i grow at c_i - 1 along the edges, and so
// inside the faces too. The smallest corner alone put a long face's finest corner along all of
// it: of_bullet's cylinder is 41 strips 0.013 long whose back ends touch faces 6.6e-5 wide, and
// the whole body came out at 8.7e-5 where 4e-4 was asked. A face with no area, or with a corner
// whose size holds over its faces (`held`: the gaps between lines, gap_sizes.h, where a face at
// a line point spans the narrow strip), gives its smallest corner.
// A point whose closest point lies on an edge or a corner of the input is as near to every face
// there, and takes the smallest of their sizes (ours, not the paper's): the tree's answer picked
// one, and where a face that holds its smallest corner meets one that interpolates, they differ.
// A line's points lie on the input's edges, and the patches on both of its sides are meshed
// from its sides: netgen_part1's line along a strip 1 wide was split at 0.77 from the strip's
// held face while the flat patch beside it, whose face holds a corner 2 away, was meshed at
// 0.085, and the long sides ended as caps (19 triangles under 15° at a deviation of 0.001).
// With `face_caps` (M values, or empty: none), an interpolating face gives no more than its cap
// (ours, not the paper's): generate_surface_mesh passes the sizes the deviation bound gave each
// face's edges (curvature_point_sizes' face_sizes), so that the size a crease asks holds over
// both faces of its edge and not only at the edge's two ends. Interpolated, it grew towards
// the faces' third corners, and an element crossing the crease there cut it by more than the
// bound: on cgal_homer at a deviation of 0.001 of its diagonal, an input vertex on a bump whose
// faces turn by 35° lay 1.02e-3 of the diagonal under the triangle over it.
// Where base(x) is at or below the smallest delta_i of all, the nearest face cannot lower it
// and is not searched for: the search (an AABB tree query, ~4000 instructions) is the surface
// front's costliest lookup, and at sizes well below the input's curvature radii it never binds.
// Elsewhere it is not searched for either where base(x) is at or below the smallest delta_i of
// the faces that can be nearest to x, which a grid over the surface bounds (smallest_near) from
// the distance to a face of x's cell: the curvature binds in some places of a surface (a
// bunny's ears), not all over it. Every answer is the one the tree alone gives, bit for bit.
class CurvatureLimitedSize final : public SizeField {
 public:
  // held: empty, or a flag per point (see above).
  CurvatureLimitedSize(const SizeField& base, const DiscreteSurface& surface,
                       std::vector<double> point_sizes, std::vector<bool> held = {},
                       std::vector<double> face_caps = {});
  double size_at(const Point& x) const override;

 private:
  // The corners' delta_i of `face` interpolated linearly at y, a point of the face (local
  // frame), no more than the face's cap.
  double interpolated(FaceId face, const Point& y) const;
  // The barycentric coordinates of y, a point of the face's plane (local frame): the signed area
  // of the sub-triangle opposite each corner over the face's; false for a face with no area.
  bool barycentric(FaceId face, const Point& y, std::array<double, 3>& lambda) const;
  // interpolated() at nearest.closest, the smallest over the faces at the edge or corner of
  // nearest.face it lies on, if any.
  double at_closest(const Located& nearest) const;
  // A face whose centroid shares x's cell (local frame), or kNoFace.
  FaceId face_near(const Point& x) const;
  // The smallest delta_i of the corners of the faces that may be nearest to x (local frame)
  // when some face is sqrt(squared_distance) from x, by the grid: a lower bound on what the
  // nearest face gives (-infinity when the grid cannot bound it cheaply). The nearest face's
  // ball meets DiscreteSurface::reach_box(x, squared_distance), so its ball's box meets the
  // cells that box meets. O(1): at most kMaxReachCells cells.
  double smallest_near(const Point& x, double squared_distance) const;
  using CellRange = std::array<std::array<std::int64_t, 2>, 3>;  // [axis][lo, hi], inclusive
  CellRange cells_of(const Point& lo, const Point& hi) const;
  std::int64_t cell_index(std::int64_t i, std::int64_t j, std::int64_t k) const {
    return (k * dims_[1] + j) * dims_[0] + i;
  }

  const SizeField& base_;
  const DiscreteSurface& surface_;
  std::vector<double> point_sizes_;
  std::vector<bool> held_;
  std::vector<double> face_caps_;  // per input face, or empty
  double smallest_;  // the smallest of point_sizes_ (+infinity when empty)
  // A dense grid over the surface's bounding box (local frame), about one cell per two faces:
  // per cell, the smallest delta_i of the corners of the faces whose ball_box meets it and of
  // the faces too large to be kept by cell (+infinity for none), and a face near it (the first
  // whose centroid is in it; kInvalidIndex for none), whose distance bounds a query's reach.
  Point origin_{0.0, 0.0, 0.0};
  double inverse_cell_ = 0.0;
  std::array<std::int64_t, 3> dims_{0, 0, 0};
  std::vector<double> cell_smallest_;
  std::vector<Index> cell_face_;
};

}  // namespace afmesh
