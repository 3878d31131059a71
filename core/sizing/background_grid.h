// A tetrahedral background grid with a size at every point (paper §4, delta_bg of eq. 15).
//
// Inside the grid the size is the linear interpolation of the four point sizes of the tet that
// contains x; outside it is the size of the nearest grid point. The default grid of a
// specification is a box split into five tets with the same size at its eight corners.
//
// Locating x: a walk through face neighbours from a start tet (the caller's Hint: the last tet
// found), with exact orientation tests; if it ends strictly inside a tet, that tet is the only one
// containing x. When x lies on a face, edge or point of the tet reached, or the walk leaves the
// grid, cycles or runs long, an AABB tree over the tets' boxes gives every tet containing x and
// the one with the smallest index is used. So the tet, and the size, depend only on x and the
// grid, never on the hint, and there is never a scan of all tets. Outside points use a kd-tree.
//
// The grid must be conforming: tets meet only in shared faces, edges and points (not checked).
#pragma once

#include <array>
#include <vector>

#include "absl/status/statusor.h"
#include "core/mesh/mesh.h"
#include "core/sizing/point_kd_tree.h"
#include "core/sizing/size_spec.h"
#include "core/spatial/aabb_tree.h"
#include "core/spatial/box.h"

namespace afmesh {

class BackgroundGrid {
 public:
  // Walk start for locate / size_at: explicit state a caller keeps between nearby queries (one
  // per thread). Only speeds up the search; results never depend on it.
  struct Hint {
    Index tet = kInvalidIndex;
  };

  // An empty grid; size_at must not be called on it.
  BackgroundGrid() = default;

  // The grid of `points` (N×3), `tets` (K×4, positive) and `sizes` (N, > 0), checked as by
  // validate_background_grid (INVALID_ARGUMENT names the field under "background").
  static absl::StatusOr<BackgroundGrid> from_arrays(std::vector<Point> points,
                                                    std::vector<Tet> tets,
                                                    std::vector<double> sizes);
  static absl::StatusOr<BackgroundGrid> from_spec(BackgroundGridSpec spec);

  // The box split into five tets (four corner tets and the central one) with `size` (> 0) at
  // every corner: the default background grid. The box must have positive extent on every axis.
  static BackgroundGrid box_grid(const Box& box, double size);

  // The size at x (finite): linear in the containing tet, else that of the nearest point.
  double size_at(const Point& x, Hint* hint = nullptr) const;

  // The tet containing x (closed), the smallest index if several; kInvalidIndex outside.
  Index locate(const Point& x, Hint* hint = nullptr) const;

  const std::vector<Point>& points() const { return points_; }
  const std::vector<Tet>& tets() const { return tets_; }
  const std::vector<double>& sizes() const { return sizes_; }

 private:
  explicit BackgroundGrid(BackgroundGridSpec spec);

  void build_neighbours();
  void build_interpolation();
  int side(Index t, int face, const Point& x) const;
  Index walk(Index start, const Point& x) const;
  Index smallest_containing(const Point& x) const;
  double interpolate(Index t, const Point& x) const;

  std::vector<Point> points_;
  std::vector<Tet> tets_;
  std::vector<double> sizes_;
  std::vector<std::array<Index, 4>> neighbours_;  // K×4: tet across the face opposite corner i
  std::vector<std::array<double, 9>> inverse_;     // K×(3×3): rows map x - a to (l1, l2, l3)
  AabbTree tet_tree_;
  PointKdTree nearest_;
  bool uniform_ = false;  // every size equal: size_at needs no search
};

}  // namespace afmesh
