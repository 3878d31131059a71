#include "core/surface/curvature_sizes.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <functional>
#include <limits>
#include <numbers>
#include <numeric>
#include <queue>
#include <utility>

#include "absl/container/flat_hash_set.h"
#include "core/geometry/vec.h"
#include "core/sizing/attached_sizes.h"
#include "core/spatial/box.h"
#include "core/spatial/z_order.h"

namespace afmesh {
namespace {

std::pair<Index, Index> edge_key(Index a, Index b) { return {std::min(a, b), std::max(a, b)}; }

// The turn test at the element's scale (see the header). Not in the paper.
// A disk at scale rho reaches kDiskRadius * rho from the edge's midpoint: about the
// circumradius (rho / sqrt(3)) of an element of that size, the part of the surface it stands for.
constexpr double kDiskRadius = 0.6;
// The largest scale tried, in face-centroid spacings l_g: disks of radius ~10 l_g hold ~250
// faces of an even triangulation, enough to average out a scan's noise, and bound the work.
constexpr double kTopScaleInSpacings = 16.0;
// A disk of more faces than this (finer faces round a coarse one) is not summed: that scale is
// passed over, and the next, smaller one tried.
constexpr std::size_t kMaxDiskFaces = 512;
// A half-disk whose normals cancel to less than this fraction of their total area turns by more
// than ~120° within itself: it wraps round the surface and says nothing at that scale.
constexpr double kMinCoherence = 0.5;
// Faces between two looks at the job's progress (cancellation): each face's edges walk disks of
// up to kMaxDiskFaces faces at a few scales, ~30 µs per face on a 1M-face scan at a coarse size.
constexpr Index kFacesPerLook = 256;
// Points settled between two looks by the grading (a 1M-face scan's 0.5M points take ~0.6 s).
constexpr std::int64_t kPointsPerLook = 8192;

// Bit k of a face's mask: edge k of the face lies on a discrete line.
using LineMask = std::vector<std::uint8_t>;

// What a turn allows: the angle bound and the chord bound (see the header).
struct TurnBound {
  double tan_p;      // tan(alpha_p / 2); +infinity: no angle bound
  double deviation;  // epsilon; 0: no chord bound
};

// The size for normals n_1, n_2 (any length; the second counted reversed when `reversed`) that
// turn by alpha over a distance l: eq. 21, l_p = l tan(alpha_p / 2) / tan(alpha / 2), the chord
// bound sqrt(8 r epsilon) with r = l / (2 tan(alpha / 2)) from eq. 20, and the kink bound
// 2 epsilon / sin(alpha / 2) (see the header). +infinity where they agree.
double turn_size(const Point& n_1, const Point& n_2, bool reversed, double l,
                 const TurnBound& bound) {
  const double cosine = std::clamp(
      (reversed ? -1.0 : 1.0) * dot(n_1, n_2) / (norm(n_1) * norm(n_2)), -1.0, 1.0);
  const double alpha = std::acos(cosine);
  if (!(alpha > 1e-9)) return std::numeric_limits<double>::infinity();
  const double tan_alpha = std::tan(0.5 * std::min(alpha, 0.99 * std::numbers::pi));
  const double l_p = l * bound.tan_p / tan_alpha;
  if (!(bound.deviation > 0.0)) return l_p;
  const double chord = std::sqrt(4.0 * l * bound.deviation / tan_alpha);
  const double kink = 2.0 * bound.deviation / std::sin(0.5 * alpha);
  return std::min({l_p, chord, kink});
}

// The distance over which normals at c_1 and c_2 turn about an edge along `edge`: its part across
// the edge (not in the paper, whose eq. 20 takes the whole distance). Between the long sides of
// a CAD tessellation's slivers the centroids lie far apart along the edge and a third of the
// faces' width across it, and only the width bends: part1's 10° facets of a hole of radius 0.5,
// 2 long and 0.087 wide, are 0.67 apart and 0.058 across, and eq. 21 over 0.67 let elements
// of twelve times eq. 21's length span the hole. Only with the chord bound (bound.deviation >
// 0); without it the whole distance, as eq. 20 takes it, so that the default output is what it
// was: the across reading alone moved the front on cgal_bones (dirty: 366 crossing pairs) to a
// non-manifold vertex, by a margin that moves with any change of the sizes.
double turn_distance(const Point& c_1, const Point& c_2, const Point& edge,
                     const TurnBound& bound) {
  const Point d = sub(c_2, c_1);
  if (!(bound.deviation > 0.0)) return norm(d);
  return norm(sub(d, scale(edge, dot(d, edge) / squared_norm(edge))));
}

// Eq. 20–21 across one edge at scale rho (not in the paper): the faces whose centroids lie within
// kDiskRadius * rho of the edge's midpoint, reached from its two faces without crossing a line
// (so a disk never reaches over a ridge), are split by the plane through the edge across the
// surface into the first face's half and the second's; eq. 21 between the halves' vector-area
// sums, over the distance between their area centroids. A face met across an edge that both
// faces traverse the same way (they disagree in orientation) counts reversed, so each sum is
// oriented as the face its half grew from. With a disk that holds only the two faces this is
// eq. 21 between the faces themselves.
class HalfDisks {
 public:
  HalfDisks(const DiscreteSurface& surface, const LineMask& line_mask, const TurnBound& bound)
      : surface_(surface), line_mask_(line_mask), bound_(bound) {}

  // l_p across edge k of input face `face_f` (whose other face is `face_g`) at scale rho; NaN
  // when a half is empty, not coherent, or the disk holds more than kMaxDiskFaces faces. The
  // walk is over slots (gather_faces): f and g below are the two faces' slots.
  double size_across(Index face_f, int k, Index face_g, double rho) {
    if (faces_.empty()) gather_faces();
    const std::vector<Point>& p = surface_.local_points();
    const Triangle& tri_f = surface_.triangle(FaceId{face_f});
    const Point& a = p[tri_f[k]];
    const Point& b = p[tri_f[(k + 1) % 3]];
    const Index f = slot_[face_f], g = slot_[face_g];
    const Point mid = scale(add(a, b), 0.5);
    const Point edge = sub(b, a);
    // The direction across the edge, in the surface, from f's side to g's.
    Point across = sub(faces_[g].centroid, faces_[f].centroid);
    across = sub(across, scale(edge, dot(across, edge) / squared_norm(edge)));
    const double r2 = kDiskRadius * kDiskRadius * rho * rho;
    ++visit_;
    stack_.clear();
    stack_.push_back({f, 1.0});
    stack_.push_back({g, (faces_[f].reversed >> k & 1) ? -1.0 : 1.0});
    stamp_[f] = stamp_[g] = visit_;
    // Half 0 is f's, half 1 is g's; sums oriented as f.
    Point normal[2] = {{0.0, 0.0, 0.0}, {0.0, 0.0, 0.0}};
    Point moment[2] = {{0.0, 0.0, 0.0}, {0.0, 0.0, 0.0}};
    double area[2] = {0.0, 0.0};
    std::size_t faces = 0;
    while (!stack_.empty()) {
      const auto [h, sign] = stack_.back();
      stack_.pop_back();
      if (++faces > kMaxDiskFaces) return std::numeric_limits<double>::quiet_NaN();
      const Face& face = faces_[h];
      const double h_area = norm(face.vector_area);
      const int half =
          h == f ? 0 : h == g ? 1 : dot(sub(face.centroid, mid), across) > 0.0 ? 1 : 0;
      normal[half] = add(normal[half], scale(face.vector_area, sign));
      moment[half] = add(moment[half], scale(face.centroid, h_area));
      area[half] += h_area;
      for (int j = 0; j < 3; ++j) {
        const Index n = face.across[j];
        if ((face.walls >> j & 1) || stamp_[n] == visit_) continue;
        if (squared_norm(sub(faces_[n].centroid, mid)) > r2) continue;
        stamp_[n] = visit_;
        stack_.push_back({n, (face.reversed >> j & 1) ? -sign : sign});
      }
    }
    for (int half = 0; half < 2; ++half)
      if (!(area[half] > 0.0) || !(norm(normal[half]) >= kMinCoherence * area[half]))
        return std::numeric_limits<double>::quiet_NaN();
    const double l =
        turn_distance(scale(moment[0], 1.0 / area[0]), scale(moment[1], 1.0 / area[1]), edge,
                      bound_);
    return turn_size(normal[0], normal[1], false, l, bound_);
  }

 private:
  // What the walk over a disk reads of one face, in one cache line: a disk of ~30 faces visits
  // each with its three neighbours, and on a 1M-face scan the separate arrays (points, centroids,
  // adjacency, masks) made the walk wait on memory for most of its time.
  struct Face {
    Point centroid;
    Point vector_area;  // (b - a) x (c - a): the normal times twice the area
    std::array<Index, 3> across;
    std::uint8_t walls = 0;     // bit j: edge j is on a line or has no single face across
    std::uint8_t reversed = 0;  // bit j: the face across traverses edge j the same way
  };

  // The faces are stored in the Z order (Morton order) of their centroids, not in the input's:
  // a disk's faces then lie near each other in memory. Only where they are stored changes: each
  // face keeps its edges' order, so a walk meets the same faces in the same order and sums them
  // in the same order as over the input's numbering, bit for bit. On the 1M-face scan at a
  // coarse size (0.3) the sizes took 22.5 s where they took 38.1 (3.5 against 4.5 s at 0.012);
  // on a 75k-face input the ordering costs ~10 ms.
  void gather_faces() {
    const std::vector<Point>& p = surface_.local_points();
    const std::vector<Triangle>& t = surface_.triangles();
    const EdgeNeighbours& neighbours = surface_.neighbours();
    const Index m = surface_.face_count();
    Box box = empty_box();
    for (Index h = 0; h < m; ++h) enclose(box, surface_.centroid(FaceId{h}));
    std::vector<std::pair<std::uint64_t, Index>> keyed(static_cast<std::size_t>(m));
    for (Index h = 0; h < m; ++h) keyed[h] = {z_order(surface_.centroid(FaceId{h}), box), h};
    std::sort(keyed.begin(), keyed.end());
    slot_.resize(static_cast<std::size_t>(m));
    for (Index i = 0; i < m; ++i) slot_[keyed[i].second] = i;
    faces_.resize(static_cast<std::size_t>(m));
    stamp_.assign(static_cast<std::size_t>(m), 0);
    for (Index h = 0; h < m; ++h) {
      Face& face = faces_[slot_[h]];
      face.centroid = surface_.centroid(FaceId{h});
      face.vector_area = afmesh::vector_area(p, t[h]);
      for (int j = 0; j < 3; ++j) {
        const Index across = neighbours.across[h][j];
        face.across[j] = across == kInvalidIndex ? kInvalidIndex : slot_[across];
        if (across == kInvalidIndex || (line_mask_[h] >> j & 1))
          face.walls |= static_cast<std::uint8_t>(1u << j);
        if (neighbours.same_way[h][j]) face.reversed |= static_cast<std::uint8_t>(1u << j);
      }
    }
  }

  const DiscreteSurface& surface_;
  const LineMask& line_mask_;
  TurnBound bound_;
  std::vector<Face> faces_;  // by slot, gathered at the first edge judged
  std::vector<Index> slot_;  // each input face's slot in faces_ (and stamp_)
  std::vector<std::uint32_t> stamp_;
  std::uint32_t visit_ = 0;
  std::vector<std::pair<Index, double>> stack_;
};

// A turn seen at the element's scale (not in the paper; see the header), for the faces across an
// edge and for a line at a vertex alike. `level` is eq. 21 at the pieces' own spacing l_g (between
// the two faces, or the two pieces of line); where it asks for less than the largest scale tried
// and than the base size (`base_size()`, asked only then: most edges turn slowly), the scales rho
// from the smaller of those down, halving: `size_at_scale(rho)` is eq. 21 between the halves at
// rho (NaN where it says nothing), and the first scale whose size is at least rho gives it, but no
// more than the last scale passed over (the turn was too much there). When no scale down to l_g
// passes, `level`, again no more than the last scale passed over.
template <typename BaseSize, typename SizeAtScale>
double turn_at_element_scale(double level, double l_g, BaseSize&& base_size,
                             SizeAtScale&& size_at_scale) {
  if (!(level < kTopScaleInSpacings * l_g)) return level;
  const double top = std::min(kTopScaleInSpacings * l_g, base_size());
  if (!(level < top)) return level;
  double passed_over = std::numeric_limits<double>::infinity();
  for (double rho = top; kDiskRadius * rho >= l_g; rho *= 0.5) {
    const double l_p = size_at_scale(rho);
    if (std::isnan(l_p)) continue;
    if (l_p >= rho) return std::min(l_p, passed_over);
    passed_over = rho;
  }
  return std::min(level, passed_over);
}

// Lines shorter than this many base sizes (at their middle vertex) keep no turn size: their
// corners already take the line's length (line_end_sizes, paper §4.2). Measured, not derived: on
// the corpus, the turns of short lines put sizes of a fifth of the size asked on the short crease
// lines of cgal_dino's eyes and claws, where the front then stopped; from 8 sizes up no file lost
// and netgen_part1's two-sided distance fell from 2.27% to 0.51% of its diagonal.
constexpr double kMinTurnLineSizes = 8.0;

// The turn of a discrete line at its vertices (not in the paper, whose eq. 20–22 bound the turn
// between faces and leave the lines' edges out). A line is split into sides along its own
// polyline (split_lines.h), so where it curves (a hole's rim, an open surface's boundary circle)
// its sides are chords of that curve, whatever the faces beside it ask: a rim of radius 3 split
// at 0.93 lay 0.33% of the model from the input. Eq. 20–21 apply to a curve as to a surface, with
// the directions of consecutive pieces of the line for the normals and the distance between
// their midpoints for l_g. Read at the element's scale as the faces' turn is
// (turn_at_element_scale):
// at scale rho the line's arc within kDiskRadius * rho of the vertex on each side (stopping at
// the line's ends; round a closed loop) is one half, its chord the half's direction and its
// length-weighted midpoint its centroid.
class LineTurns {
 public:
  LineTurns(const std::vector<Point>& points, const DiscreteLine& line, const TurnBound& bound)
      : p_(points), v_(line.vertices), closed_(line.closed), bound_(bound) {
    segments_ = static_cast<Index>(v_.size()) - 1;
    for (Index j = 0; j < segments_; ++j) total_ += distance(p_[v_[j]], p_[v_[j + 1]]);
  }
  Index segments() const { return segments_; }
  double length() const { return total_; }
  // Whether vertex i (0 ... segments) has a piece of line on both sides: an inner vertex, or any
  // vertex of a closed loop (whose ends are one point, the loop's start).
  bool inner(Index i) const { return closed_ ? i < segments_ : i > 0 && i < segments_; }

  // Eq. 21 between the two pieces at vertex i, over the distance between their midpoints.
  double between_pieces(Index i, double& l_g) const {
    const Index before = closed_ && i == 0 ? segments_ - 1 : i - 1;
    const Point& a = p_[v_[before]];
    const Point& b = p_[v_[before + 1]];
    const Point& c = p_[v_[i]];
    const Point& d = p_[v_[i + 1]];
    l_g = distance(scale(add(a, b), 0.5), scale(add(c, d), 0.5));
    return turn_size(sub(b, a), sub(d, c), false, l_g, bound_);
  }

  // Eq. 21 between the halves at vertex i and scale rho; NaN when a half is not coherent (turns
  // by more than ~120° within itself) or the arc would run round the whole loop.
  double size_at_scale(Index i, double rho) const {
    const double reach = kDiskRadius * rho;
    if (closed_ && 2.0 * reach >= total_) return std::numeric_limits<double>::quiet_NaN();
    const Half back = half(i, reach, -1), ahead = half(i, reach, +1);
    for (const Half& h : {back, ahead})
      if (!(h.length > 0.0) || !(norm(h.chord) >= kMinCoherence * h.length))
        return std::numeric_limits<double>::quiet_NaN();
    const double l = distance(scale(back.moment, 1.0 / back.length),
                              scale(ahead.moment, 1.0 / ahead.length));
    return turn_size(back.chord, ahead.chord, false, l, bound_);
  }

 private:
  struct Half {
    Point chord{0.0, 0.0, 0.0};   // along the line's direction
    Point moment{0.0, 0.0, 0.0};  // sum of the pieces' midpoints times their lengths
    double length = 0.0;
  };
  // The arc of length `reach` from vertex i backwards (step -1) or forwards (+1).
  Half half(Index i, double reach, int step) const {
    Half h;
    Index at = i;
    while (h.length < reach) {
      if (!closed_ && (step < 0 ? at == 0 : at == segments_)) break;
      Index next = at + step;
      if (closed_) {
        if (next < 0) {  // round the loop's start, backwards
          at = segments_;
          next = segments_ - 1;
        } else if (next > segments_) {  // and forwards
          at = 0;
          next = 1;
        }
      }
      const Point& from = p_[v_[at]];
      const Point& to = p_[v_[next]];
      const double piece = distance(from, to);
      const double share = piece > reach - h.length ? (reach - h.length) / piece : 1.0;
      const Point end = add(from, scale(sub(to, from), share));
      const Point dir = step > 0 ? sub(end, from) : sub(from, end);
      h.chord = add(h.chord, dir);
      h.moment = add(h.moment, scale(add(from, end), 0.5 * share * piece));
      h.length += share * piece;
      at = next;
      if (share < 1.0) break;
    }
    return h;
  }
  const std::vector<Point>& p_;
  const std::vector<Index>& v_;
  bool closed_;
  TurnBound bound_;
  Index segments_ = 0;
  double total_ = 0.0;
};

}  // namespace

absl::StatusOr<std::vector<double>> curvature_point_sizes(const DiscreteSurface& surface,
                                                          const SurfaceFeatures& features,
                                                          double alpha_p_deg, double deviation,
                                                          const SizeField& base,
                                                          Progress& progress,
                                                          std::vector<double>* face_sizes) {
  const std::vector<Point>& p = surface.local_points();
  const std::vector<Triangle>& t = surface.triangles();
  std::vector<double> size(p.size(), std::numeric_limits<double>::infinity());
  if (face_sizes != nullptr)
    face_sizes->assign(t.size(), std::numeric_limits<double>::infinity());
  absl::flat_hash_set<std::pair<Index, Index>> line_edges;
  for (const DiscreteLine& line : features.lines)
    for (std::size_t i = 0; i + 1 < line.vertices.size(); ++i)
      line_edges.insert(edge_key(line.vertices[i], line.vertices[i + 1]));
  LineMask line_mask(t.size(), 0);
  for (Index f = 0; f < surface.face_count(); ++f)
    for (int k = 0; k < 3; ++k)
      if (line_edges.contains(edge_key(t[f][k], t[f][(k + 1) % 3])))
        line_mask[f] |= static_cast<std::uint8_t>(1u << k);
  const TurnBound bound{alpha_p_deg > 0.0
                            ? std::tan(0.5 * alpha_p_deg * std::numbers::pi / 180.0)
                            : std::numeric_limits<double>::infinity(),
                        deviation};
  const EdgeNeighbours& neighbours = surface.neighbours();
  HalfDisks disks(surface, line_mask, bound);
  // Eq. 20–22 over each edge between two faces, once (from its lower face).
  for (Index f = 0; f < surface.face_count(); ++f) {
    if (f % kFacesPerLook == 0 && progress.cancelled())
      return absl::CancelledError("curvature sizes: cancelled");
    for (int k = 0; k < 3; ++k) {
      const Index g = neighbours.across[f][k];
      if (g == kInvalidIndex || g < f || (line_mask[f] >> k & 1)) continue;
      const Index a = t[f][k], b = t[f][(k + 1) % 3];
      const Point& c_f = surface.centroid(FaceId{f});
      const Point& c_g = surface.centroid(FaceId{g});
      const double l_g = distance(c_f, c_g);
      // Eq. 21 between the two faces, over their distance (across the edge with the chord
      // bound); normals of faces that traverse the edge the same way disagree in orientation.
      double l_p = turn_size(surface.normal(FaceId{f}), surface.normal(FaceId{g}),
                             neighbours.same_way[f][k], turn_distance(c_f, c_g, sub(p[b], p[a]), bound),
                             bound);
      // Where that asks for less than the base size, the turn at the element's scale.
      l_p = turn_at_element_scale(
          l_p, l_g,
          [&] { return base.size_at(surface.to_global(scale(add(c_f, c_g), 0.5))); },
          [&](double rho) { return disks.size_across(f, k, g, rho); });
      size[a] = std::min(size[a], l_p);  // eq. 22
      size[b] = std::min(size[b], l_p);
      if (face_sizes != nullptr) {
        (*face_sizes)[f] = std::min((*face_sizes)[f], l_p);
        (*face_sizes)[g] = std::min((*face_sizes)[g], l_p);
      }
    }
  }
  // The lines' own turns (LineTurns; not in the paper), at their vertices, on lines at least
  // kMinTurnLineSizes long.
  for (const DiscreteLine& line : features.lines) {
    if (progress.cancelled()) return absl::CancelledError("curvature sizes: cancelled");
    const LineTurns turns(p, line, bound);
    const Point& middle = p[line.vertices[line.vertices.size() / 2]];
    if (turns.length() < kMinTurnLineSizes * base.size_at(surface.to_global(middle))) continue;
    for (Index i = 0; i < turns.segments(); ++i) {
      if (!turns.inner(i)) continue;
      const Index v = line.vertices[i];
      double l_g = 0.0;
      const double level = turns.between_pieces(i, l_g);
      size[v] = std::min(
          size[v], turn_at_element_scale(
                       level, l_g, [&] { return base.size_at(surface.to_global(p[v])); },
                       [&](double rho) { return turns.size_at_scale(i, rho); }));
    }
  }
  return size;
}

absl::Status grade_point_sizes(const DiscreteSurface& surface, double growth,
                               std::vector<double>& size, Progress& progress) {
  const std::vector<Point>& p = surface.local_points();
  const std::vector<Triangle>& t = surface.triangles();
  // The smallest delta_i + (c_i - 1) |x_j - x_i| over the surface's edges (Dijkstra).
  const double c_i = std::max(growth, 1.0);
  using Item = std::pair<double, Index>;
  // The points with a size, sorted, and a heap of the sizes lowered since: each step settles
  // the smaller of the two fronts (Dijkstra's order over both). On a scan every point has a
  // curvature size and few are lowered, and popping all 0.5M from one heap took 0.6 s, 5% of
  // the job; the sizes are the same (each is the smallest over the paths to it, whatever the
  // order of the steps).
  std::vector<Item> sorted;
  for (Index v = 0; v < static_cast<Index>(size.size()); ++v)
    if (std::isfinite(size[v])) sorted.push_back({size[v], v});
  std::sort(sorted.begin(), sorted.end());
  std::priority_queue<Item, std::vector<Item>, std::greater<>> lowered;
  std::size_t next = 0;
  for (std::int64_t popped = 0; next < sorted.size() || !lowered.empty(); ++popped) {
    if (popped % kPointsPerLook == 0 && progress.cancelled())
      return absl::CancelledError("grading the attached sizes: cancelled");
    Item item;
    if (lowered.empty() || (next < sorted.size() && sorted[next] < lowered.top())) {
      item = sorted[next++];
    } else {
      item = lowered.top();
      lowered.pop();
    }
    const auto [d, v] = item;
    if (d > size[v]) continue;
    for (const Index f : surface.faces_at(v)) {
      for (const Index w : t[f]) {
        // A size grown from d is at least d: a point already as small (settled) is passed over
        // without measuring the edge.
        if (w == v || size[w] <= d) continue;
        const double through = size_grown_over(d, c_i, norm(sub(p[w], p[v])));
        if (through < size[w]) {
          size[w] = through;
          lowered.push({through, w});
        }
      }
    }
  }
  return absl::OkStatus();
}

namespace {

// The grid of CurvatureLimitedSize: about one cell per kFacesPerCell faces of the input. A face
// whose ball meets more than kMaxFaceCells cells (a sliver, whose ball is all of space, or a
// face far larger than the cells) is kept out of the cells and bounds every query instead; a
// query whose reach meets more than kMaxReachCells cells is left to the tree.
constexpr double kFacesPerCell = 2.0;
constexpr std::int64_t kMaxFaceCells = 64;
constexpr std::int64_t kMaxReachCells = 64;
// A closest point whose barycentric coordinate opposite a corner is at most this lies on the
// edge opposite it (a line's points are computed on the input's edges, to rounding).
constexpr double kOnEdgeBarycentric = 1e-9;

std::int64_t cell_count(const std::array<std::array<std::int64_t, 2>, 3>& r) {
  return (r[0][1] - r[0][0] + 1) * (r[1][1] - r[1][0] + 1) * (r[2][1] - r[2][0] + 1);
}

}  // namespace

CurvatureLimitedSize::CurvatureLimitedSize(const SizeField& base, const DiscreteSurface& surface,
                                           std::vector<double> point_sizes,
                                           std::vector<bool> held,
                                           std::vector<double> face_caps)
    : base_(base),
      surface_(surface),
      point_sizes_(std::move(point_sizes)),
      held_(std::move(held)),
      face_caps_(std::move(face_caps)),
      smallest_(std::accumulate(point_sizes_.begin(), point_sizes_.end(),
                                std::numeric_limits<double>::infinity(),
                                [](double a, double b) { return std::min(a, b); })) {
  const double infinity = std::numeric_limits<double>::infinity();
  if (!(smallest_ < infinity)) return;  // size_at never searches
  Box bounds = empty_box();
  for (const Point& p : surface_.local_points()) enclose(bounds, p);
  double largest = 0.0;
  for (int k = 0; k < 3; ++k) largest = std::max(largest, bounds.hi[k] - bounds.lo[k]);
  if (!(largest > 0.0)) return;
  // Cells of equal edges, about face_count / kFacesPerCell of them over the box (a flat box
  // counted a thousandth of its largest extent thick).
  const double wanted = std::max(1.0, surface_.face_count() / kFacesPerCell);
  double volume = 1.0;
  for (int k = 0; k < 3; ++k) volume *= std::max(bounds.hi[k] - bounds.lo[k], 1e-3 * largest);
  const double cell = std::cbrt(volume / wanted);
  origin_ = bounds.lo;
  inverse_cell_ = 1.0 / cell;
  for (int k = 0; k < 3; ++k)
    dims_[k] = static_cast<std::int64_t>(std::floor((bounds.hi[k] - bounds.lo[k]) / cell)) + 1;
  const auto cells = static_cast<std::size_t>(dims_[0] * dims_[1] * dims_[2]);
  cell_smallest_.assign(cells, infinity);
  cell_face_.assign(cells, kInvalidIndex);
  double large = infinity;  // the faces kept out of the cells
  for (Index f = 0; f < surface_.face_count(); ++f) {
    double corner = infinity;  // as size_at takes it
    for (const Index v : surface_.triangle(FaceId{f})) corner = std::min(corner, point_sizes_[v]);
    const Box ball = surface_.ball_box(FaceId{f});
    const CellRange r = cells_of(ball.lo, ball.hi);
    if (cell_count(r) > kMaxFaceCells) {
      large = std::min(large, corner);
    } else {
      for (std::int64_t k = r[2][0]; k <= r[2][1]; ++k)
        for (std::int64_t j = r[1][0]; j <= r[1][1]; ++j)
          for (std::int64_t i = r[0][0]; i <= r[0][1]; ++i) {
            double& smallest = cell_smallest_[cell_index(i, j, k)];
            smallest = std::min(smallest, corner);
          }
    }
    const Point& c = surface_.centroid(FaceId{f});
    const CellRange at = cells_of(c, c);
    Index& face = cell_face_[cell_index(at[0][0], at[1][0], at[2][0])];
    if (face == kInvalidIndex) face = f;
  }
  // The faces kept out bound every cell.
  for (double& smallest : cell_smallest_) smallest = std::min(smallest, large);
}

CurvatureLimitedSize::CellRange CurvatureLimitedSize::cells_of(const Point& lo,
                                                               const Point& hi) const {
  // floor of the scaled coordinate, clamped into the grid: monotone in the coordinate, so boxes
  // that overlap have cell ranges that overlap.
  const auto cell = [&](double x, int axis) -> std::int64_t {
    const double c = std::floor((x - origin_[axis]) * inverse_cell_);
    if (!(c > 0.0)) return 0;  // also NaN
    return std::min(static_cast<std::int64_t>(std::min(c, 9e18)), dims_[axis] - 1);
  };
  CellRange r;
  for (int a = 0; a < 3; ++a) r[a] = {cell(lo[a], a), cell(hi[a], a)};
  return r;
}

FaceId CurvatureLimitedSize::face_near(const Point& x) const {
  if (cell_face_.empty()) return kNoFace;
  const CellRange at = cells_of(x, x);
  return FaceId{cell_face_[cell_index(at[0][0], at[1][0], at[2][0])]};
}

double CurvatureLimitedSize::smallest_near(const Point& x, double squared_distance) const {
  const Box reach = surface_.reach_box(x, squared_distance);
  const CellRange r = cells_of(reach.lo, reach.hi);
  if (cell_count(r) > kMaxReachCells) return -std::numeric_limits<double>::infinity();
  double smallest = std::numeric_limits<double>::infinity();
  for (std::int64_t k = r[2][0]; k <= r[2][1]; ++k)
    for (std::int64_t j = r[1][0]; j <= r[1][1]; ++j)
      for (std::int64_t i = r[0][0]; i <= r[0][1]; ++i)
        smallest = std::min(smallest, cell_smallest_[cell_index(i, j, k)]);
  return smallest;
}

double CurvatureLimitedSize::interpolated(FaceId face, const Point& y) const {
  const Triangle& t = surface_.triangle(face);
  const double d[3] = {point_sizes_[t[0]], point_sizes_[t[1]], point_sizes_[t[2]]};
  const double smallest = std::min({d[0], d[1], d[2]});
  // Grading reaches every point of a component that has a size, so the corners are all finite
  // or all not.
  if (!std::isfinite(std::max({d[0], d[1], d[2]}))) return smallest;
  if (!held_.empty() && (held_[t[0]] || held_[t[1]] || held_[t[2]])) return smallest;
  std::array<double, 3> lambda;
  if (!barycentric(face, y, lambda)) return smallest;
  double weighted = 0.0, total = 0.0;
  for (int k = 0; k < 3; ++k) {
    weighted += std::max(0.0, lambda[k]) * d[k];
    total += std::max(0.0, lambda[k]);
  }
  if (!(total > 0.0)) return smallest;
  const double cap = face_caps_.empty() ? std::numeric_limits<double>::infinity()
                                        : face_caps_[index_of(face)];
  return std::max(smallest, std::min(cap, weighted / total));
}

double CurvatureLimitedSize::size_at(const Point& x) const {
  const double base = base_.size_at(x);
  // min(base, curvature) is base whenever curvature >= smallest_ >= base: the same double.
  if (base <= smallest_) return base;
  // Likewise when curvature >= smallest_near >= base, from a face of x's cell.
  const Point local = surface_.to_local(x);
  if (const FaceId g = face_near(local);
      g != kNoFace &&
      base <= smallest_near(local, surface_.squared_distance_to_face(local, g)))
    return base;
  const Located nearest = surface_.nearest_face(local);
  return std::min(base, at_closest(nearest));
}

bool CurvatureLimitedSize::barycentric(FaceId face, const Point& y,
                                       std::array<double, 3>& lambda) const {
  const Triangle& t = surface_.triangle(face);
  const std::vector<Point>& p = surface_.local_points();
  const Point n = vector_area(p, t);
  const double n2 = squared_norm(n);
  if (!(n2 > 0.0)) return false;
  for (int k = 0; k < 3; ++k)
    lambda[k] =
        dot(cross(sub(p[t[(k + 2) % 3]], p[t[(k + 1) % 3]]), sub(y, p[t[(k + 1) % 3]])), n) / n2;
  return true;
}

double CurvatureLimitedSize::at_closest(const Located& nearest) const {
  const double own = interpolated(nearest.face, nearest.closest);
  const Triangle& t = surface_.triangle(nearest.face);
  std::array<double, 3> lambda;
  if (!barycentric(nearest.face, nearest.closest, lambda)) return own;
  // The corners whose barycentric coordinate at the closest point is (about) zero: the point
  // lies on the edge opposite one, or at the corner opposite two.
  int on = 0, off_corner = -1, on_corner = -1;
  for (int k = 0; k < 3; ++k) {
    if (lambda[k] <= kOnEdgeBarycentric) {
      ++on, on_corner = k;
    } else {
      off_corner = k;
    }
  }
  if (on == 0 || on == 3) return own;
  double smallest = own;
  if (on == 2) {  // at corner t[off_corner]: every face there
    for (const Index f : surface_.faces_at(t[off_corner]))
      smallest = std::min(smallest, interpolated(FaceId{f}, nearest.closest));
    return smallest;
  }
  // On edge (a, b), opposite corner t[on_corner]: the faces at a that have b too.
  const Index a = t[(on_corner + 1) % 3], b = t[(on_corner + 2) % 3];
  for (const Index f : surface_.faces_at(a)) {
    const Triangle& g = surface_.triangle(FaceId{f});
    if (g[0] == b || g[1] == b || g[2] == b)
      smallest = std::min(smallest, interpolated(FaceId{f}, nearest.closest));
  }
  return smallest;
}

}  // namespace afmesh
