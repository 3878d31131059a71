// Axis-aligned bounding boxes: the key type of the AABB tree (aabb_tree.h).
//
// Boxes are closed: two boxes that only touch (share a face, an edge or a corner) overlap. That
// is what intersection tests need, since touching triangles must still be tested exactly.
#pragma once

#include <algorithm>
#include <vector>

#include "core/mesh/mesh.h"

namespace afmesh {

// A closed axis-aligned box [lo[0], hi[0]] × [lo[1], hi[1]] × [lo[2], hi[2]]. A box with
// lo[k] > hi[k] on some axis is empty and overlaps nothing.
struct Box {
  Point lo{0.0, 0.0, 0.0};
  Point hi{0.0, 0.0, 0.0};
};

// An empty box (lo = +inf, hi = -inf): the identity of `enclose`.
Box empty_box();

// True when the box has no points (lo > hi on some axis, or a NaN coordinate).
inline bool is_empty(const Box& box) {
  return !(box.lo[0] <= box.hi[0] && box.lo[1] <= box.hi[1] && box.lo[2] <= box.hi[2]);
}

// True when the closed boxes a and b have a common point.
inline bool boxes_overlap(const Box& a, const Box& b) {
  return a.lo[0] <= b.hi[0] && b.lo[0] <= a.hi[0] &&  //
         a.lo[1] <= b.hi[1] && b.lo[1] <= a.hi[1] &&  //
         a.lo[2] <= b.hi[2] && b.lo[2] <= a.hi[2];
}

// Grows `box` to contain point p.
inline void enclose(Box& box, const Point& p) {
  for (int k = 0; k < 3; ++k) {
    box.lo[k] = std::min(box.lo[k], p[k]);
    box.hi[k] = std::max(box.hi[k], p[k]);
  }
}

// Grows `box` to contain box b.
inline void enclose(Box& box, const Box& b) {
  for (int k = 0; k < 3; ++k) {
    box.lo[k] = std::min(box.lo[k], b.lo[k]);
    box.hi[k] = std::max(box.hi[k], b.hi[k]);
  }
}

// `box` grown by `margin` on every side.
inline Box grown(const Box& box, double margin) {
  Box out = box;
  for (int k = 0; k < 3; ++k) {
    out.lo[k] -= margin;
    out.hi[k] += margin;
  }
  return out;
}

// The smallest box containing triangle t of `points` (N×3). Indices must be in range.
Box triangle_box(const std::vector<Point>& points, const Triangle& t);

// The smallest box containing tet t of `points`.
inline Box tet_box(const std::vector<Point>& points, const Tet& t) {
  Box b{points[t[0]], points[t[0]]};
  for (int k = 1; k < 4; ++k) enclose(b, points[t[k]]);
  return b;
}

// The boxes of `triangles` (M×3) over `points` (N×3): M boxes, in triangle order.
// Indices must be in range.
std::vector<Box> triangle_boxes(const std::vector<Point>& points,
                                const std::vector<Triangle>& triangles);

// The boxes of mesh.triangles, in triangle order. Indices must be in range.
inline std::vector<Box> triangle_boxes(const Mesh& mesh) {
  return triangle_boxes(mesh.points, mesh.triangles);
}

}  // namespace afmesh
