#include "core/quality/measures.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <string_view>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "absl/status/status.h"
#include "absl/strings/str_format.h"
#include "core/geometry/closest_points.h"
#include "core/geometry/vec.h"
#include "core/quality/compensated_sum.h"

namespace afmesh {
namespace {

using Vec = Eigen::Vector3d;

Vec vec(const Point& p) { return Vec(p[0], p[1], p[2]); }

double degrees(double radians) { return radians * (180.0 / std::numbers::pi); }

// Angle in [0, pi] between u and v, accurate also near 0 and pi; 0 when either is zero.
double angle_between(const Vec& u, const Vec& v) {
  const double sine = u.cross(v).norm();
  const double cosine = u.dot(v);
  if (sine == 0.0 && cosine == 0.0) return 0.0;
  return std::atan2(sine, cosine);
}

// The outward face normals of tet (p0, p1, p2, p3): n[i] is the normal of the face opposite p[i],
// twice its area long, pointing out of a positive tet (into an inverted one, which gives the same
// angles).
std::array<Vec, 4> face_normals(const Vec& p0, const Vec& p1, const Vec& p2, const Vec& p3) {
  return {(p2 - p1).cross(p3 - p1), (p3 - p0).cross(p2 - p0), (p1 - p0).cross(p3 - p0),
          (p2 - p0).cross(p1 - p0)};
}

// tan(theta / 2) for the angle theta in [0, pi] whose sine and cosine are `sine` / `scale` and
// `cosine` / `scale` (scale > 0): increasing in theta and, unlike either alone, accurate to a
// few ulps over the whole range, so it orders angles as atan2 would without calling it.
double half_angle_tangent(double sine, double cosine, double scale) {
  return cosine >= 0.0 ? sine / (scale + cosine) : (scale - cosine) / sine;
}

// The smallest and largest of the 6 dihedral angles (radians) of the tet with face normals `n`.
// The dihedral angle along the edge shared by faces i and j is pi minus the angle between their
// normals; it is taken as 0 when a face has no normal (coincident points). The pairs are ranked
// by half_angle_tangent and only the two extremes go through atan2 (angle_between), which gives
// them exactly the values of the full computation.
std::array<double, 2> dihedral_extremes(const std::array<Vec, 4>& n,
                                        const std::array<double, 4>& length) {
  std::array<int, 2> low{-1, -1}, high{-1, -1};  // face pairs (i, j) of the extremes
  double low_key = 0.0, high_key = 0.0;
  bool undefined = false;
  for (int i = 0; i < 4; ++i) {
    for (int j = i + 1; j < 4; ++j) {
      if (!(length[i] > 0.0 && length[j] > 0.0)) {
        undefined = true;
        continue;
      }
      const double key =
          half_angle_tangent(n[i].cross(n[j]).norm(), -n[i].dot(n[j]), length[i] * length[j]);
      if (low[0] < 0 || key < low_key) low_key = key, low = {i, j};
      if (high[0] < 0 || key > high_key) high_key = key, high = {i, j};
    }
  }
  auto angle = [&](const std::array<int, 2>& pair) {
    return pair[0] < 0 ? 0.0 : angle_between(n[pair[0]], -n[pair[1]]);
  };
  return {undefined ? 0.0 : angle(low), angle(high)};
}

// 3 r_in / r_circ = 108 V^2 / (A |m|), where A is the total face area and m the numerator of the
// circumcentre offset from p0: c - p0 = m / (12 V) with
// m = |b|^2 (c x d) + |c|^2 (d x b) + |d|^2 (b x c), (b, c, d) = (p1, p2, p3) - p0.
// So r_circ = |m| / (12 |V|) and r_in = 3 |V| / A. Zero for a flat tet.
double tet_radius_ratio(const Vec& p0, const Vec& p1, const Vec& p2, const Vec& p3,
                        const std::array<Vec, 4>& n, const std::array<double, 4>& length,
                        double volume) {
  const Vec b = p1 - p0, c = p2 - p0, d = p3 - p0;
  const double area = 0.5 * (length[0] + length[1] + length[2] + length[3]);
  // c x d = -n[1], d x b = -n[2], b x c = -n[3], exactly (the same products, negated).
  const Vec m = -(b.squaredNorm() * n[1] + c.squaredNorm() * n[2] + d.squaredNorm() * n[3]);
  const double denominator = area * m.norm();
  if (volume == 0.0 || !(denominator > 0.0)) return 0.0;
  return 108.0 * volume * volume / denominator;
}

// Error naming the first element of `elements` with an index outside [0, point_count).
template <typename Element>
absl::Status check_indices(const std::vector<Element>& elements, std::size_t point_count,
                           std::string_view kind) {
  for (std::size_t e = 0; e < elements.size(); ++e) {
    for (Index v : elements[e]) {
      if (v < 0 || static_cast<std::size_t>(v) >= point_count) {
        return absl::InvalidArgumentError(absl::StrFormat(
            "%s %d has point index %d outside [0, %d): fix the element array before measuring "
            "quality",
            kind, e, v, point_count));
      }
    }
  }
  return absl::OkStatus();
}

// Accumulates count, extremes and the compensated mean of one measure.
class StatsAccumulator {
 public:
  void add(double x) {
    if (stats_.count == 0) {
      stats_.min = x;
      stats_.max = x;
    } else {
      stats_.min = std::min(stats_.min, x);
      stats_.max = std::max(stats_.max, x);
    }
    ++stats_.count;
    sum_.add(x);
  }
  MeasureStats result() const {
    MeasureStats s = stats_;
    if (s.count > 0) s.mean = sum_.value() / static_cast<double>(s.count);
    return s;
  }

 private:
  MeasureStats stats_;
  CompensatedSum sum_;
};

// Per point: whether it is a corner of a tet near a boundary sliver (QualitySummary's
// tets_away_from_slivers; a tet with such a corner is near one), from the points on slivers
// (summarize_triangles). O(T).
std::vector<bool> near_slivers(const Mesh& mesh, const std::vector<bool>& on_sliver) {
  std::vector<bool> near(mesh.points.size(), false);
  for (const Tet& tet : mesh.tets) {
    if (!(on_sliver[tet[0]] || on_sliver[tet[1]] || on_sliver[tet[2]] || on_sliver[tet[3]]))
      continue;
    for (const Index v : tet) near[v] = true;
  }
  return near;
}

// `on_sliver`: the points of the boundary's slivers (summarize_triangles).
void summarize_tets(const Mesh& mesh, const std::vector<bool>& on_sliver, QualitySummary& summary,
                    CancelCheck& stop) {
  StatsAccumulator min_dihedral, max_dihedral, ratio, volume, away;
  std::int64_t below_10 = 0, below_20 = 0, away_below_20 = 0;
  const std::vector<bool> near = near_slivers(mesh, on_sliver);
  for (const Tet& tet : mesh.tets) {
    if (stop.due()) return;
    const TetQuality q = tet_quality(mesh.points, tet);
    if (!(near[tet[0]] || near[tet[1]] || near[tet[2]] || near[tet[3]])) {
      away.add(q.min_dihedral_deg);
      if (q.min_dihedral_deg < 20.0) ++away_below_20;
    }
    min_dihedral.add(q.min_dihedral_deg);
    max_dihedral.add(q.max_dihedral_deg);
    ratio.add(q.radius_ratio);
    volume.add(q.volume);
    if (q.volume <= 0.0) ++summary.tets_with_nonpositive_volume;
    if (q.min_dihedral_deg < 10.0) ++below_10;
    if (q.min_dihedral_deg < 20.0) ++below_20;
    summary.tet_min_dihedral_hist.add(q.min_dihedral_deg);
    summary.tet_max_dihedral_hist.add(q.max_dihedral_deg);
    summary.tet_radius_ratio_hist.add(q.radius_ratio);
  }
  summary.tet_count = static_cast<std::int64_t>(mesh.tets.size());
  summary.tet_min_dihedral_deg = min_dihedral.result();
  summary.tet_max_dihedral_deg = max_dihedral.result();
  summary.tet_radius_ratio = ratio.result();
  summary.tet_volume = volume.result();
  if (summary.tet_count > 0) {
    summary.share_min_dihedral_below_10 = static_cast<double>(below_10) / summary.tet_count;
    summary.share_min_dihedral_below_20 = static_cast<double>(below_20) / summary.tet_count;
  }
  summary.away_min_dihedral_deg = away.result();
  summary.tets_away_from_slivers = summary.away_min_dihedral_deg.count;
  if (summary.tets_away_from_slivers > 0)
    summary.share_away_below_20 =
        static_cast<double>(away_below_20) / summary.tets_away_from_slivers;
}

// Also counts the boundary's slivers and returns their points (per point: on a sliver).
std::vector<bool> summarize_triangles(const Mesh& mesh, QualitySummary& summary) {
  StatsAccumulator min_angle, ratio;
  std::vector<bool> on_sliver(mesh.points.size(), false);
  for (const Triangle& t : mesh.triangles) {
    const TriangleQuality q = triangle_quality(mesh.points, t);
    if (q.min_angle_deg < kSliverTriangleDeg) {
      ++summary.boundary_slivers;
      for (const Index v : t) on_sliver[v] = true;
    }
    min_angle.add(q.min_angle_deg);
    ratio.add(q.radius_ratio);
    summary.triangle_min_angle_hist.add(q.min_angle_deg);
    summary.triangle_radius_ratio_hist.add(q.radius_ratio);
  }
  summary.triangle_count = static_cast<std::int64_t>(mesh.triangles.size());
  summary.triangle_min_angle_deg = min_angle.result();
  summary.triangle_radius_ratio = ratio.result();
  return on_sliver;
}

}  // namespace

double tet_signed_volume(const Point& a, const Point& b, const Point& c, const Point& d) {
  const Vec pa = vec(a);
  return (vec(b) - pa).cross(vec(c) - pa).dot(vec(d) - pa) / 6.0;
}

TetQuality tet_quality(const Point& a, const Point& b, const Point& c, const Point& d) {
  const Vec p0 = vec(a), p1 = vec(b), p2 = vec(c), p3 = vec(d);
  const std::array<Vec, 4> n = face_normals(p0, p1, p2, p3);
  const std::array<double, 4> length = {n[0].norm(), n[1].norm(), n[2].norm(), n[3].norm()};
  TetQuality q;
  q.volume = tet_signed_volume(a, b, c, d);
  const std::array<double, 2> extremes = dihedral_extremes(n, length);
  q.min_dihedral_deg = degrees(extremes[0]);
  q.max_dihedral_deg = degrees(extremes[1]);
  q.radius_ratio = tet_radius_ratio(p0, p1, p2, p3, n, length, q.volume);
  return q;
}

TetQuality tet_quality(const std::vector<Point>& points, const Tet& tet) {
  return tet_quality(points[tet[0]], points[tet[1]], points[tet[2]], points[tet[3]]);
}

// Corner angles from the edge vectors at each corner; ratio = 16 A^2 / (perimeter · abc), which
// is 2 r_in / r_circ with r_in = 2A / perimeter and r_circ = abc / (4A).
namespace {

// The smallest corner angle, degrees, of the triangle with edge vectors ab, bc, ca of lengths
// lc, la, lb (all non-zero): the smallest of the three angle_between values, bit for bit.
// The corners are ranked by half_angle_tangent, as dihedral_extremes ranks its pairs, and only
// those whose key is within a relative 1e-9 of the smallest go through atan2: the keys and the
// angles agree to a few ulps and an angle under 60 degrees moves by at least 0.8 of its key's
// relative change, so a corner farther off cannot hold the minimum. (Usually one atan2, not
// three: they were most of the cost of the front's, the flips' and the smoothing's angle tests.)
// Lengths far from 1 (products near the under- and overflow) and NaNs take all three atan2.
double smallest_corner_angle_deg(const Vec& ab, const Vec& bc, const Vec& ca, double la,
                                 double lb, double lc) {
  const std::array<Vec, 3> u{ab, bc, ca}, v{-ca, -ab, -bc};
  const std::array<double, 3> scale{lc * lb, la * lc, lb * la};
  std::array<double, 3> key;
  bool ranked = std::min({la, lb, lc}) > 1e-100 && std::max({la, lb, lc}) < 1e100;
  for (int k = 0; k < 3; ++k) {
    key[k] = half_angle_tangent(u[k].cross(v[k]).norm(), u[k].dot(v[k]), scale[k]);
    ranked = ranked && key[k] >= 0.0;  // false for a NaN
  }
  if (!ranked) {
    return degrees(std::min(
        {angle_between(u[0], v[0]), angle_between(u[1], v[1]), angle_between(u[2], v[2])}));
  }
  const double bound = std::min({key[0], key[1], key[2]}) * (1.0 + 1e-9);
  double smallest = std::numeric_limits<double>::infinity();
  for (int k = 0; k < 3; ++k) {
    if (key[k] <= bound) smallest = std::min(smallest, angle_between(u[k], v[k]));
  }
  return degrees(smallest);
}

}  // namespace

double triangle_min_angle_deg(const Point& a, const Point& b, const Point& c) {
  const Vec pa = vec(a), pb = vec(b), pc = vec(c);
  const Vec ab = pb - pa, bc = pc - pb, ca = pa - pc;
  const double la = bc.norm(), lb = ca.norm(), lc = ab.norm();
  if (la == 0.0 || lb == 0.0 || lc == 0.0) return 0.0;
  return smallest_corner_angle_deg(ab, bc, ca, la, lb, lc);
}

TriangleQuality triangle_quality(const Point& a, const Point& b, const Point& c) {
  const Vec pa = vec(a), pb = vec(b), pc = vec(c);
  const Vec ab = pb - pa, bc = pc - pb, ca = pa - pc;
  TriangleQuality q;
  q.area = 0.5 * ab.cross(-ca).norm();
  const double la = bc.norm(), lb = ca.norm(), lc = ab.norm();
  if (la == 0.0 || lb == 0.0 || lc == 0.0) return q;
  q.min_angle_deg = smallest_corner_angle_deg(ab, bc, ca, la, lb, lc);
  const double denominator = (la + lb + lc) * la * lb * lc;
  q.radius_ratio = denominator > 0.0 ? 16.0 * q.area * q.area / denominator : 0.0;
  return q;
}

TriangleQuality triangle_quality(const std::vector<Point>& points, const Triangle& triangle) {
  return triangle_quality(points[triangle[0]], points[triangle[1]], points[triangle[2]]);
}

Histogram::Histogram(double lo_value, double hi_value, int bins)
    : lo(lo_value), hi(hi_value), counts(std::max(bins, 1), 0) {}

void Histogram::add(double value) {
  if (std::isnan(value)) {
    ++nan_count;
    return;
  }
  const int bins = static_cast<int>(counts.size());
  const double position = (value - lo) / (hi - lo) * bins;
  // `!(position > 0)` also catches a NaN position from an empty range (hi == lo).
  const int bin = !(position > 0.0)  ? 0
                  : position >= bins ? bins - 1
                                     : static_cast<int>(position);
  ++counts[bin];
}

double Histogram::bin_lo(int i) const {
  return lo + (hi - lo) * static_cast<double>(i) / static_cast<double>(counts.size());
}

std::int64_t Histogram::total() const {
  std::int64_t sum = nan_count;
  for (std::int64_t c : counts) sum += c;
  return sum;
}

absl::StatusOr<QualitySummary> summarize_quality(const Mesh& mesh, Progress& progress) {
  if (absl::Status s = check_indices(mesh.tets, mesh.points.size(), "tet"); !s.ok()) return s;
  if (absl::Status s = check_indices(mesh.triangles, mesh.points.size(), "triangle"); !s.ok()) {
    return s;
  }
  QualitySummary summary;
  CancelCheck stop(progress);
  const std::vector<bool> on_sliver = summarize_triangles(mesh, summary);
  summarize_tets(mesh, on_sliver, summary, stop);
  if (stop.stopped()) return absl::CancelledError("the quality summary was cancelled");
  return summary;
}

bool comes_near(std::span<const Point> points, const Triangle& t, const Point& x, double radius) {
  const Point c = closest_point_on_triangle(x, points[t[0]], points[t[1]], points[t[2]]);
  return norm(sub(c, x)) <= radius;
}

TrianglesNear triangles_near(std::span<const Point> points, std::span<const Triangle> triangles,
                             const Point& x, double radius) {
  TrianglesNear near;
  for (const Triangle& t : triangles) {
    if (!comes_near(points, t, x, radius)) continue;
    ++near.count;
    near.smallest_angle_deg = std::min(near.smallest_angle_deg,
                                       triangle_min_angle_deg(points[t[0]], points[t[1]], points[t[2]]));
    for (int k = 0; k < 3; ++k) {
      const double length = norm(sub(points[t[(k + 1) % 3]], points[t[k]]));
      near.shortest_edge = std::min(near.shortest_edge, length);
      near.longest_edge = std::max(near.longest_edge, length);
    }
  }
  return near;
}

double mean_edge_length(const Mesh& surface) {
  const auto in_range = [&surface](Index i) {
    return i >= 0 && static_cast<std::size_t>(i) < surface.points.size();
  };
  double sum = 0.0;
  std::size_t edges = 0;
  for (const Triangle& triangle : surface.triangles) {
    if (!in_range(triangle[0]) || !in_range(triangle[1]) || !in_range(triangle[2])) continue;
    for (int corner = 0; corner < 3; ++corner) {
      const Point& a = surface.points[triangle[corner]];
      const Point& b = surface.points[triangle[(corner + 1) % 3]];
      sum += std::hypot(b[0] - a[0], b[1] - a[1], b[2] - a[2]);
      ++edges;
    }
  }
  return edges == 0 ? 1.0 : sum / static_cast<double>(edges);
}

}  // namespace afmesh
