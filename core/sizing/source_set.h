// Point, line and surface sources (paper §4.1, eq. 1–14), stored for fast evaluation.
//
// Every source is evaluated as one type, a triangle (x1, x2, x3), as the paper advises: a line
// source is the triangle (x1, x2, x2) and a point source (x1, x1, x1). Instead of the paper's
// "small distance between the points", degenerate triangles are handled exactly: three collinear
// points (exact test, coincident points included) are the segment between the two farthest
// apart, and a segment of zero length is a point.
//
// r(x), the Euclidean distance from x to the closed triangle:
//  - the triangle is stored with x1 the vertex opposite its longest edge, g1 = x2 - x1,
//    g2 = x3 - x1, the unit normal g3 (eq. 6) and the contravariant vectors g^1, g^2 (eq. 7);
//  - when 0 <= xi, eta, zeta (eq. 7–8), r = |(x - x1) · g3|, the normal distance (equal to eq. 9
//    in exact arithmetic, and accurate for thin triangles);
//  - otherwise r is the smallest distance to the three edges, each a line source (eq. 2–4).
// A triangle whose largest angle has a sine below kFlatSine (nearly collinear points) is
// treated as its three edges: r is then at most kFlatSine times its second-longest edge too
// large. Elsewhere r carries only rounding error (relative ~1e-8 at worst near that limit, ~1e-16
// for well-shaped triangles, relative to |x - x1| plus the source's size).
//
// Storage is struct-of-arrays, one column per precomputed quantity, padded to whole blocks of
// kBlock sources so that min_size evaluates kBlock sources at a time with Eigen. Segment sources
// (collinear points) keep their segment in all three edge slots and are stored before the
// triangles, so that whole blocks of them take a one-segment kernel. Every path (one source, a
// block of triangles, a block of segments) runs the same operations on a source, so its size at
// a point is the same double whichever path computes it.
#pragma once

#include <span>
#include <vector>

#include "core/mesh/mesh.h"
#include "core/sizing/decay_law.h"
#include "core/sizing/size_spec.h"
#include "core/spatial/box.h"

namespace afmesh {

class SourceSet {
 public:
  // Sources evaluated together by min_size (vector lanes).
  static constexpr int kBlock = 8;
  // Below this sine of the largest angle a triangle source is treated as its three edges.
  static constexpr double kFlatSine = 1e-8;
  // Relative margin of size_lower_bound / size_upper_bound over every rounding error of the
  // distance and the law (see there).
  static constexpr double kBoundMargin = 1e-6;
  // Number of precomputed columns per source (layout in source_set.cc).
  static constexpr int kColumns = 34;

  SourceSet() = default;

  // Precomputes `sources`, which must pass validate_size_spec (as part of a SizeSpec).
  explicit SourceSet(std::span<const SizeSource> sources);

  // Number of sources.
  Index count() const { return count_; }

  // r(x) of source s: the distance from x to its point, segment or triangle (eq. 1–9).
  double distance(Index s, const Point& x) const;

  // delta_s(x): the size of source s at x (eq. 10–13). May be +inf far from the source.
  double size(Index s, const Point& x) const;

  // min(upper, size(s, x) over every source s) (eq. 14), kBlock sources at a time.
  double min_size(const Point& x, double upper) const;

  // The same minimum over the sources of this set taken in order, stopping at the first source
  // whose entry in `lower` (one per source, ascending) is >= the minimum so far. Equal to
  // min_size when lower[s] <= size(s, x) for every s (as for the bounds below).
  double min_size_bounded(const Point& x, double upper, std::span<const double> lower) const;

  // A set whose source i is source ids[i] of this one, evaluated in that order by min_size*,
  // with the same precomputed values (so the same sizes, bit for bit).
  SourceSet gather(std::span<const Index> ids) const;

  // Bounds on size(s, x) over every x in the closed box `cell`, as computed by size() (rounding
  // included): from the distance between `cell` and the source's bounding box (lower) and the
  // distance from `cell`'s farthest corner to x1 (upper), with relative margins kBoundMargin
  // that exceed every rounding error of the distance and of the law.
  double size_lower_bound(Index s, const Box& cell) const;
  double size_upper_bound(Index s, const Box& cell) const;

  // delta0 of source s: its smallest size (every law is >= delta0).
  double smallest_size(Index s) const { return delta0_[slot_[s]]; }

  // The bounding box of source s's points.
  const Box& box(Index s) const { return box_[slot_[s]]; }

 private:
  void resize(Index count);
  void set_law(Index slot, const SizeSource& source);
  void copy_source(const SourceSet& from, Index from_slot, Index slot);
  void mark_segment_blocks();
  double slot_distance(Index slot, const Point& x) const;
  double size_at_distance(Index slot, double r) const;
  Point x1(Index slot) const;
  const double* column(int c) const { return columns_.data() + c * stride_; }
  double* column(int c) { return columns_.data() + c * stride_; }

  // Sources are numbered as given (spec order) and stored in slots (segments first).
  Index count_ = 0;
  Index stride_ = 0;                   // count_ rounded up to whole blocks
  std::vector<Index> slot_;            // per source: its slot
  std::vector<double> columns_;        // kColumns × stride_, by slot
  std::vector<char> segment_block_;    // per block: every slot in it holds a segment
  // Per slot:
  std::vector<char> segment_;          // collinear points: one segment in all three edge slots
  std::vector<LawKind> kind_;
  std::vector<double> delta0_, r0_, r1_, gamma_;
  std::vector<Index> coefficient_begin_, coefficient_count_;  // into coefficients_
  std::vector<double> coefficients_;
  std::vector<Box> box_;               // bounding box of the source's points
  std::vector<double> diameter_;       // diagonal of box_
};

}  // namespace afmesh
