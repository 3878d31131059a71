#include "core/sizing/source_set.h"

#include <Eigen/Core>
#include <algorithm>
#include <array>
#include <cmath>
#include <variant>

#include "core/geometry/predicates.h"
#include "core/geometry/vec.h"

namespace afmesh {
namespace {

using Block = Eigen::Array<double, SourceSet::kBlock, 1>;

// The precomputed columns of a source (struct of arrays), in the order the kernels read them.
enum Column : int {
  kX1x, kX1y, kX1z,  // x1
  kNx, kNy, kNz,     // g3, the unit normal (0 without interior)
  kC1x, kC1y, kC1z,  // g^1 (0 without interior)
  kC2x, kC2y, kC2z,  // g^2 (0 without interior)
  kInterior,         // 1 when the triangle has an interior, else 0
  kEdge0,            // edges k = 0, 1, 2 (vertex k to vertex k + 1 mod 3), kEdgeColumns each:
                     // start a (x, y, z), vector g (x, y, z), 1 / (g · g) or 0
};
constexpr int kEdgeColumns = 7;
static_assert(kEdge0 + 3 * kEdgeColumns == SourceSet::kColumns);

// ---- The distance kernel (eq. 1–9), written once for one source (V = double) and for a block
// of kBlock sources (V = Block). The lane operations below give the same bits lane by lane for
// the values that occur (finite, no NaN), so every path computes the same r.

inline double lane_min(double a, double b) { return b < a ? b : a; }
inline Block lane_min(const Block& a, const Block& b) { return a.min(b); }
inline double clamp01(double t) { return std::max(0.0, std::min(1.0, t)); }
inline Block clamp01(const Block& t) { return t.min(1.0).max(0.0); }
inline double lane_sqrt(double a) { return std::sqrt(a); }
inline Block lane_sqrt(const Block& a) { return a.sqrt(); }

// Squared distance from x to edge k (eq. 2–4): xi = (x - a) · g / (g · g), clamped to [0, 1]
// (eq. 3), then |x - a - xi' g|^2 (eq. 4). A zero-length edge has 1 / (g · g) stored as 0, so it
// is its start point a.
template <class V, class Load>
V edge_distance2(const Load& col, const Point& x, int first) {
  const V wx = x[0] - col(first + 0), wy = x[1] - col(first + 1), wz = x[2] - col(first + 2);
  const V gx = col(first + 3), gy = col(first + 4), gz = col(first + 5);
  const V t = clamp01((wx * gx + wy * gy + wz * gz) * col(first + 6));
  const V dx = wx - t * gx, dy = wy - t * gy, dz = wz - t * gz;
  return dx * dx + dy * dy + dz * dz;
}

// The smallest squared distance to the three edges.
template <class V, class Load>
V edges_distance2(const Load& col, const Point& x) {
  const V d0 = edge_distance2<V>(col, x, kEdge0);
  const V d1 = edge_distance2<V>(col, x, kEdge0 + kEdgeColumns);
  const V d2 = edge_distance2<V>(col, x, kEdge0 + 2 * kEdgeColumns);
  return lane_min(lane_min(d0, d1), d2);
}

// x in the source's plane coordinates: xi, eta (eq. 7) and the offset h along g3 (eq. 5).
template <class V>
struct PlaneCoordinates {
  V xi, eta, h;
};

template <class V, class Load>
PlaneCoordinates<V> plane_coordinates(const Load& col, const Point& x) {
  const V wx = x[0] - col(kX1x), wy = x[1] - col(kX1y), wz = x[2] - col(kX1z);
  return {wx * col(kC1x) + wy * col(kC1y) + wz * col(kC1z),
          wx * col(kC2x) + wy * col(kC2y) + wz * col(kC2z),
          wx * col(kNx) + wy * col(kNy) + wz * col(kNz)};
}

// eq. 8: 0 <= xi, eta, zeta = 1 - xi - eta.
inline bool projects_inside(const PlaneCoordinates<double>& p) {
  return p.xi >= 0.0 && p.eta >= 0.0 && p.xi + p.eta <= 1.0;
}

// r(x) for one source: one segment, or the normal distance inside the triangle, or its edges.
template <class Load>
double one_distance(const Load& col, const Point& x, bool segment) {
  if (segment) return lane_sqrt(edge_distance2<double>(col, x, kEdge0));
  const PlaneCoordinates<double> p = plane_coordinates<double>(col, x);
  if (col(kInterior) > 0.0 && projects_inside(p)) return lane_sqrt(p.h * p.h);
  return lane_sqrt(edges_distance2<double>(col, x));
}

// r(x) for a block of sources, all segments (their three edge slots are equal, so the first
// gives the same value as the minimum over three).
template <class Load>
Block block_segment_distance(const Load& col, const Point& x) {
  return lane_sqrt(edge_distance2<Block>(col, x, kEdge0));
}

// r(x) for a block of sources of any kind: the normal distance where x projects inside a
// triangle with interior, else the distance to the nearest edge.
template <class Load>
Block block_distance(const Load& col, const Point& x) {
  const PlaneCoordinates<Block> p = plane_coordinates<Block>(col, x);
  const auto inside = (col(kInterior) > 0.0) && (p.xi >= 0.0) && (p.eta >= 0.0) &&
                      (p.xi + p.eta <= 1.0);
  const Block h2 = p.h * p.h;
  return lane_sqrt(inside.select(h2, edges_distance2<Block>(col, x)));
}

// ---- Precomputation (once per source).

// 1 / gg, or 0 when gg is 0 or so small that its inverse overflows (the edge is then a point).
double safe_inverse(double gg) {
  if (!(gg > 0.0)) return 0.0;
  const double inv = 1.0 / gg;
  return std::isfinite(inv) ? inv : 0.0;
}

// The columns of one source, and whether it is a segment (exactly collinear points).
struct SourceColumns {
  std::array<double, SourceSet::kColumns> value{};
  bool segment = false;
};

// The triangle of a source: 1, 2 or 3 points padded by repeating the last, rotated so that x1 is
// opposite the longest edge (vertices 1 and 2 then end the longest edge): g1 and g2 are the two
// shorter edges, whose cross product is the most accurate normal.
std::array<Point, 3> source_triangle(const std::vector<Point>& points) {
  std::array<Point, 3> v;
  for (int i = 0; i < 3; ++i) v[i] = points[std::min<std::size_t>(i, points.size() - 1)];
  const double l0 = squared_distance(v[1], v[2]);  // opposite v0
  const double l1 = squared_distance(v[2], v[0]);  // opposite v1
  const double l2 = squared_distance(v[0], v[1]);  // opposite v2
  if (l1 > l0 && l1 >= l2) return {v[1], v[2], v[0]};
  if (l2 > l0 && l2 > l1) return {v[2], v[0], v[1]};
  return v;
}

void set_edge(SourceColumns& c, int edge, const Point& a, const Point& b) {
  const Point g = sub(b, a);
  const int first = kEdge0 + edge * kEdgeColumns;
  for (int k = 0; k < 3; ++k) {
    c.value[first + k] = a[k];
    c.value[first + 3 + k] = g[k];
  }
  c.value[first + 6] = safe_inverse(dot(g, g));
}

// The geometric parameters of eq. 1–9 of one source.
SourceColumns precompute(const std::vector<Point>& points) {
  SourceColumns c;
  const std::array<Point, 3> v = source_triangle(points);
  const Point g1 = sub(v[1], v[0]), g2 = sub(v[2], v[0]);
  const Point normal = cross(g1, g2);
  const double twice_area = norm(normal);
  for (int k = 0; k < 3; ++k) c.value[kX1x + k] = v[0][k];
  c.segment = collinear(v[0], v[1], v[2]);
  if (c.segment) {
    for (int e = 0; e < 3; ++e) set_edge(c, e, v[1], v[2]);  // the longest edge: all of it
    return c;
  }
  for (int e = 0; e < 3; ++e) set_edge(c, e, v[e], v[(e + 1) % 3]);
  if (!(twice_area > SourceSet::kFlatSine * norm(g1) * norm(g2))) return c;  // flat: edges only
  const Point g3 = scale(normal, 1.0 / twice_area);         // eq. 6
  const Point c1 = scale(cross(g2, g3), 1.0 / twice_area);  // g1 · g^1 = 1, g2 · g^1 = 0
  const Point c2 = scale(cross(g3, g1), 1.0 / twice_area);  // g2 · g^2 = 1, g1 · g^2 = 0
  for (int k = 0; k < 3; ++k) {
    c.value[kNx + k] = g3[k];
    c.value[kC1x + k] = c1[k];
    c.value[kC2x + k] = c2[k];
  }
  c.value[kInterior] = 1.0;
  return c;
}

// ---- Bounds used for pruning.

// Distance between two closed boxes (0 when they overlap).
double box_distance(const Box& a, const Box& b) {
  double d2 = 0.0;
  for (int k = 0; k < 3; ++k) {
    const double gap = std::max({0.0, a.lo[k] - b.hi[k], b.lo[k] - a.hi[k]});
    d2 += gap * gap;
  }
  return std::sqrt(d2);
}

// Largest distance from p to a point of the closed box (reached at a corner).
double farthest_corner_distance(const Box& box, const Point& p) {
  double d2 = 0.0;
  for (int k = 0; k < 3; ++k) {
    const double far = std::max(std::fabs(box.lo[k] - p[k]), std::fabs(box.hi[k] - p[k]));
    d2 += far * far;
  }
  return std::sqrt(d2);
}

}  // namespace

SourceSet::SourceSet(std::span<const SizeSource> sources) {
  resize(static_cast<Index>(sources.size()));
  std::vector<SourceColumns> columns(sources.size());
  for (std::size_t s = 0; s < sources.size(); ++s) columns[s] = precompute(sources[s].points);
  // Segments first, each group in the given order.
  Index slot = 0;
  for (const bool segments : {true, false}) {
    for (Index s = 0; s < count_; ++s) {
      if (columns[s].segment != segments) continue;
      slot_[s] = slot;
      for (int c = 0; c < kColumns; ++c) column(c)[slot] = columns[s].value[c];
      segment_[slot] = segments;
      set_law(slot, sources[s]);
      Box box = empty_box();
      for (const Point& p : sources[s].points) enclose(box, p);
      box_[slot] = box;
      diameter_[slot] = norm(sub(box.hi, box.lo));
      ++slot;
    }
  }
  mark_segment_blocks();
}

void SourceSet::resize(Index count) {
  count_ = count;
  stride_ = (count + kBlock - 1) / kBlock * kBlock;
  slot_.resize(count);
  columns_.assign(static_cast<std::size_t>(kColumns) * stride_, 0.0);
  segment_.resize(count);
  kind_.resize(count);
  delta0_.resize(count);
  r0_.resize(count);
  r1_.resize(count);
  gamma_.resize(count);
  coefficient_begin_.resize(count);
  coefficient_count_.resize(count);
  box_.resize(count);
  diameter_.resize(count);
}

// A block is all segments when each of its used slots is (padding slots are zero segments).
void SourceSet::mark_segment_blocks() {
  segment_block_.assign(stride_ / kBlock, 1);
  for (Index slot = 0; slot < count_; ++slot) {
    if (!segment_[slot]) segment_block_[slot / kBlock] = 0;
  }
}

void SourceSet::set_law(Index slot, const SizeSource& source) {
  delta0_[slot] = source.delta0;
  r0_[slot] = source.r0;
  r1_[slot] = source.r1;
  gamma_[slot] = 0.0;
  coefficient_begin_[slot] = static_cast<Index>(coefficients_.size());
  coefficient_count_[slot] = 0;
  if (const auto* power = std::get_if<PowerLaw>(&source.law)) {
    kind_[slot] = LawKind::kPower;
    gamma_[slot] = power->gamma;
  } else if (const auto* exponential = std::get_if<ExponentialLaw>(&source.law)) {
    kind_[slot] = LawKind::kExponential;
    gamma_[slot] = exponential->gamma;
  } else {
    const auto& a = std::get<PolynomialLaw>(source.law).coefficients;
    kind_[slot] = LawKind::kPolynomial;
    coefficients_.insert(coefficients_.end(), a.begin(), a.end());
    coefficient_count_[slot] = static_cast<Index>(a.size());
  }
}

double SourceSet::size_at_distance(Index slot, double r) const {
  const std::span<const double> a(coefficients_.data() + coefficient_begin_[slot],
                                  static_cast<std::size_t>(coefficient_count_[slot]));
  return law_size(kind_[slot], delta0_[slot], gamma_[slot], a,
                  scaled_distance(r, r0_[slot], r1_[slot]));
}

double SourceSet::slot_distance(Index slot, const Point& x) const {
  const auto col = [&](int c) { return column(c)[slot]; };
  return one_distance(col, x, segment_[slot]);
}

double SourceSet::distance(Index s, const Point& x) const { return slot_distance(slot_[s], x); }

double SourceSet::size(Index s, const Point& x) const {
  const Index slot = slot_[s];
  return size_at_distance(slot, slot_distance(slot, x));
}

double SourceSet::min_size(const Point& x, double upper) const {
  return min_size_bounded(x, upper, {});
}

double SourceSet::min_size_bounded(const Point& x, double upper,
                                   std::span<const double> lower) const {
  const bool bounded = !lower.empty();
  double current = upper;
  for (Index first = 0; first < count_; first += kBlock) {
    if (bounded && lower[first] >= current) break;
    const auto col = [&](int c) { return Eigen::Map<const Block>(column(c) + first); };
    const Block r = segment_block_[first / kBlock] ? block_segment_distance(col, x)
                                                   : block_distance(col, x);
    const Index last = std::min<Index>(first + kBlock, count_);
    for (Index slot = first; slot < last; ++slot) {
      if (bounded && lower[slot] >= current) return current;
      current = std::min(current, size_at_distance(slot, r[slot - first]));
    }
  }
  return current;
}

void SourceSet::copy_source(const SourceSet& from, Index from_slot, Index slot) {
  for (int c = 0; c < kColumns; ++c) column(c)[slot] = from.column(c)[from_slot];
  segment_[slot] = from.segment_[from_slot];
  kind_[slot] = from.kind_[from_slot];
  delta0_[slot] = from.delta0_[from_slot];
  r0_[slot] = from.r0_[from_slot];
  r1_[slot] = from.r1_[from_slot];
  gamma_[slot] = from.gamma_[from_slot];
  coefficient_begin_[slot] = static_cast<Index>(coefficients_.size());
  coefficient_count_[slot] = from.coefficient_count_[from_slot];
  const auto a = from.coefficients_.begin() + from.coefficient_begin_[from_slot];
  coefficients_.insert(coefficients_.end(), a, a + from.coefficient_count_[from_slot]);
  box_[slot] = from.box_[from_slot];
  diameter_[slot] = from.diameter_[from_slot];
}

SourceSet SourceSet::gather(std::span<const Index> ids) const {
  SourceSet subset;
  subset.resize(static_cast<Index>(ids.size()));
  for (Index i = 0; i < subset.count_; ++i) {
    subset.slot_[i] = i;
    subset.copy_source(*this, slot_[ids[i]], i);
  }
  subset.mark_segment_blocks();
  return subset;
}

Point SourceSet::x1(Index slot) const {
  return {column(kX1x)[slot], column(kX1y)[slot], column(kX1z)[slot]};
}

// r(x) >= (distance from the cell to the source's box) for x in the cell; rounding makes the
// computed r smaller by at most ~1e-7 (|x - x1| + diameter) (see the header), which the slack
// covers with a wide margin. The law is non-decreasing in r up to a last-bit wobble of
// std::pow / std::exp, covered by the relative margin on the result.
double SourceSet::size_lower_bound(Index s, const Box& cell) const {
  const Index slot = slot_[s];
  const double slack =
      kBoundMargin * (farthest_corner_distance(cell, x1(slot)) + diameter_[slot]);
  const double r = std::max(0.0, box_distance(cell, box_[slot]) - slack);
  return size_at_distance(slot, r) * (1.0 - kBoundMargin);
}

// r(x) <= |x - p| <= (distance from p to the cell's farthest corner) for p = x1, a point of the
// source; the margins cover rounding as for the lower bound.
double SourceSet::size_upper_bound(Index s, const Box& cell) const {
  const Index slot = slot_[s];
  const double far = farthest_corner_distance(cell, x1(slot));
  const double r = far + kBoundMargin * (far + diameter_[slot]);
  return size_at_distance(slot, r) * (1.0 + kBoundMargin);
}

}  // namespace afmesh
