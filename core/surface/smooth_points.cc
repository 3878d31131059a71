#include "core/surface/smooth_points.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include "core/geometry/closest_points.h"
#include "core/geometry/vec.h"
#include "core/mesh/simplex_incidence.h"
#include "core/quality/measures.h"

namespace afmesh {
namespace {

// The fan of point q with q moved to `x`: its smallest angle, and whether every triangle's normal
// stays within `min_cosine` of `before` (its normal with q where it was).
struct Fan {
  double min_angle = 180.0;
  bool turned = false;
};

Fan fan_at(const SurfaceMeshState& s, Index q, const Point& x, const std::vector<Index>& fan,
           const std::vector<Point>& before, double min_cosine) {
  Fan out;
  for (std::size_t i = 0; i < fan.size(); ++i) {
    const Triangle& t = s.triangles[fan[i]];
    const auto at = [&](Index k) -> const Point& { return k == q ? x : s.points[k]; };
    out.min_angle = std::min(out.min_angle, triangle_min_angle_deg(at(t[0]), at(t[1]), at(t[2])));
    if (dot(unit_normal(at(t[0]), at(t[1]), at(t[2])), before[i]) < min_cosine)
      out.turned = true;
  }
  return out;
}

// The lines' polylines by arc length, for the line points' slides (not in the paper): for line
// l, the arc length at each of its input vertices, and where a line point lies along it.
class LineArcs {
 public:
  explicit LineArcs(const SurfaceMeshState& s) : s_(s) {
    const std::vector<Point>& p = s.surface.local_points();
    first_.reserve(s.features.lines.size() + 1);
    for (const DiscreteLine& line : s.features.lines) {
      first_.push_back(static_cast<Index>(arc_.size()));
      double total = 0.0;
      arc_.push_back(0.0);
      for (std::size_t j = 0; j + 1 < line.vertices.size(); ++j) {
        total += distance(p[line.vertices[j]], p[line.vertices[j + 1]]);
        arc_.push_back(total);
      }
    }
    first_.push_back(static_cast<Index>(arc_.size()));
  }

  // The arc length of point i of line l's points (SurfaceMeshState::points_along_lines), from
  // the segment it lies on.
  double arc_of(Index l, std::size_t i) const {
    const SurfaceMeshState::LinePoints& along = s_.points_along_lines[l];
    const Index seg = along.segment[i];
    const Point& start = s_.surface.local_points()[s_.features.lines[l].vertices[seg]];
    return arc_[first_[l] + seg] + distance(start, s_.points[along.ids[i]]);
  }

  // How far the chord from x (on segment `from`) to y (on segment `to`, not before it) of line
  // l passes from the line's input vertices between them: the largest distance of one.
  double chord_deviation(Index l, Index from, const Point& x, Index to, const Point& y) const {
    const std::vector<Index>& v = s_.features.lines[l].vertices;
    double deviation = 0.0;
    for (Index j = from + 1; j <= to; ++j) {
      const Point& w = s_.surface.local_points()[v[j]];
      deviation = std::max(deviation, distance(w, closest_point_on_segment(w, x, y)));
    }
    return deviation;
  }

  // The point at arc length a of line l, on a segment from `lo` on (the segment of a point
  // before it), and that segment.
  Point point_at(Index l, double a, Index lo, Index& seg) const {
    const std::vector<Index>& v = s_.features.lines[l].vertices;
    const Index last_segment = static_cast<Index>(v.size()) - 2;
    seg = lo;
    while (seg < last_segment && arc_[first_[l] + seg + 1] < a) ++seg;
    const double start = arc_[first_[l] + seg], length = arc_[first_[l] + seg + 1] - start;
    const Point& x = s_.surface.local_points()[v[seg]];
    const Point& y = s_.surface.local_points()[v[seg + 1]];
    const double t = length > 0.0 ? std::clamp((a - start) / length, 0.0, 1.0) : 0.0;
    return add(x, scale(sub(y, x), t));
  }

 private:
  const SurfaceMeshState& s_;
  std::vector<double> arc_;   // by line: its vertices' arc lengths, from first_[l]
  std::vector<Index> first_;  // lines + 1
};

// Where a line point lies in SurfaceMeshState::points_along_lines: its line and place there,
// neither end (the ends are corners, which never move); line kInvalidIndex for other points.
struct LineSlot {
  Index line = kInvalidIndex;
  Index i = 0;
};

std::vector<LineSlot> line_slots(const SurfaceMeshState& s) {
  std::vector<LineSlot> slots(s.points.size());
  for (std::size_t l = 0; l < s.points_along_lines.size(); ++l) {
    const std::vector<Index>& ids = s.points_along_lines[l].ids;
    for (std::size_t i = 1; i + 1 < ids.size(); ++i)
      slots[ids[i]] = {static_cast<Index>(l), static_cast<Index>(i)};
  }
  return slots;
}

// The places a line point tries between its neighbours on the line, as fractions of the arc
// between them (not in the paper): a point never comes nearer to a neighbour than
// kSlideSpan[0] of that arc, so its sides stay within a factor of about two of each other.
constexpr double kSlideSpan[2] = {0.3, 0.7};
constexpr int kSlideSteps = 8;

}  // namespace

absl::StatusOr<std::int64_t> smooth_points(SurfaceMeshState& s, const SmoothParams& params,
                                           Progress& progress) {
  SimplexIncidence<3> incidence = SimplexIncidence<3>::of(s.triangles);
  const double min_cosine = std::cos(params.max_normal_turn_deg * std::numbers::pi / 180.0);
  CancelCheck cancel(progress, 1024);  // each point a walk and a few fans
  std::vector<Index> fan;
  std::vector<Point> before;
  // The smallest angle of each triangle, computed when first needed (negative: not yet) and
  // forgotten when a corner moves: a triangle is in the fans of its three corners, and each
  // fan's angles are measured where it stands before a move is tried.
  std::vector<double> smallest_angle(s.triangles.size(), -1.0);
  const auto angle_of = [&](Index t) {
    if (smallest_angle[t] < 0) {
      const Triangle& k = s.triangles[t];
      smallest_angle[t] = triangle_min_angle_deg(s.points[k[0]], s.points[k[1]], s.points[k[2]]);
    }
    return smallest_angle[t];
  };
  const std::vector<LineSlot> slots =
      params.slide_line_points ? line_slots(s) : std::vector<LineSlot>(s.points.size());
  const LineArcs arcs(s);
  // A point is looked at in a pass when it or a neighbour moved in the one before.
  std::vector<char> due(s.points.size(), 1), next(s.points.size(), 0);
  std::int64_t moves = 0;
  for (int pass = 0; pass < params.max_passes; ++pass) {
    std::int64_t moved = 0;
    for (Index q = 0; q < static_cast<Index>(s.points.size()); ++q) {
      if (cancel.due()) return absl::CancelledError("surface meshing cancelled");
      if (!due[q]) continue;
      const LineSlot slot = slots[q];
      const bool on_line = s.anchor[q] != kInvalidIndex;
      if (on_line && slot.line == kInvalidIndex) continue;  // a corner
      fan.clear();
      incidence.elements_of(s.triangles, q, fan);
      if (fan.size() < (on_line ? 2u : 3u)) continue;
      double now = 180.0;
      for (const Index t : fan) now = std::min(now, angle_of(t));
      if (now >= params.good_fan_deg) continue;
      before.clear();
      for (const Index t : fan) {
        const Triangle& k = s.triangles[t];
        before.push_back(unit_normal(s.points[k[0]], s.points[k[1]], s.points[k[2]]));
      }
      if (on_line) {
        // A line point slides along its line's polyline between its neighbours there, to the
        // place of kSlideSteps + 1 tried whose fan has the largest smallest angle (not in the
        // paper): on the input's edges, so it stays on the input and on the line, and its
        // sides stay the line's. Between two lines closer than the size, points split at the
        // same places on both make right triangles across the strip, staggered ones
        // isosceles ones.
        SurfaceMeshState::LinePoints& along = s.points_along_lines[slot.line];
        const double from = arcs.arc_of(slot.line, slot.i - 1);
        const double to = arcs.arc_of(slot.line, slot.i + 1);
        if (!(to > from)) continue;
        // The two sides' chords may pass no farther from the line's input vertices than they do
        // now: on a curved line the longer side would cut the curve by more.
        const Point& back = s.points[along.ids[slot.i - 1]];
        const Point& ahead = s.points[along.ids[slot.i + 1]];
        const Index seg_back = along.segment[slot.i - 1], seg_ahead = along.segment[slot.i + 1];
        const auto deviation = [&](const Point& x, Index seg) {
          return std::max(arcs.chord_deviation(slot.line, seg_back, back, seg, x),
                          arcs.chord_deviation(slot.line, seg, x, seg_ahead, ahead));
        };
        const double deviation_now = deviation(s.points[q], along.segment[slot.i]);
        double best_angle = now + params.min_gain_deg;
        Index best_segment = kInvalidIndex;
        Point best{0, 0, 0};
        for (int step = 0; step <= kSlideSteps; ++step) {
          const double tau =
              kSlideSpan[0] + (kSlideSpan[1] - kSlideSpan[0]) * step / kSlideSteps;
          Index segment = 0;
          const Point x = arcs.point_at(slot.line, from + tau * (to - from), seg_back, segment);
          const Fan moved_fan = fan_at(s, q, x, fan, before, min_cosine);
          if (moved_fan.turned || !(moved_fan.min_angle >= best_angle) ||
              deviation(x, segment) > deviation_now)
            continue;
          best_angle = moved_fan.min_angle;
          best_segment = segment;
          best = x;
        }
        if (best_segment == kInvalidIndex) continue;
        // Host and anchor as the line's split gives them (sides_along_lines): a face at the
        // segment the point lies on, and the segment's first vertex.
        const std::vector<Index>& vertices = s.features.lines[slot.line].vertices;
        const Index a = vertices[best_segment], b = vertices[best_segment + 1];
        s.host[q] = s.surface.face_at_edge(a, b);
        s.anchor[q] = a;
        along.segment[slot.i] = best_segment;
        s.points[q] = best;
      } else {
        // The mean of the fan's other corners, in the patch's tangent plane after projection.
        Point mean{0, 0, 0};
        for (const Index t : fan)
          for (const Index r : s.triangles[t])
            if (r != q) mean = add(mean, s.points[r]);
        mean = scale(mean, 1.0 / (2.0 * static_cast<double>(fan.size())));
        const PatchId patch{s.triangle_patch[fan[0]]};
        const Located on =                                                       // S8
            locate_in_patch(s.surface, s.features, patch, mean, patch_hint(s, patch, q));
        const Fan moved_fan = fan_at(s, q, on.closest, fan, before, min_cosine);
        if (moved_fan.turned || !(moved_fan.min_angle >= now + params.min_gain_deg)) continue;
        s.points[q] = on.closest;
        s.host[q] = on.face;
      }
      ++moved;
      for (const Index t : fan) {
        smallest_angle[t] = -1.0;
        for (const Index r : s.triangles[t]) next[r] = 1;
      }
    }
    moves += moved;
    if (moved == 0) break;
    due.swap(next);
    std::fill(next.begin(), next.end(), 0);
  }
  return moves;
}

}  // namespace afmesh
