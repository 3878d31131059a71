#include "core/surface/discrete_surface.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numeric>
#include <utility>

#include "absl/status/status.h"
#include "absl/strings/str_format.h"
#include "core/geometry/closest_points.h"
#include "core/geometry/vec.h"
#include "core/spatial/box.h"

namespace afmesh {
namespace {

absl::Status check_input(const Mesh& mesh) {
  if (mesh.triangles.empty()) {
    return absl::InvalidArgumentError("discrete surface: the mesh has no triangles");
  }
  if (!mesh.triangle_tags.empty() && mesh.triangle_tags.size() != mesh.triangles.size()) {
    return absl::InvalidArgumentError(
        absl::StrFormat("discrete surface: %d triangle tags for %d triangles",
                        mesh.triangle_tags.size(), mesh.triangles.size()));
  }
  for (std::size_t i = 0; i < mesh.points.size(); ++i) {
    for (double c : mesh.points[i]) {
      if (!std::isfinite(c)) {
        return absl::InvalidArgumentError(
            absl::StrFormat("discrete surface: point %d has a non-finite coordinate", i));
      }
    }
  }
  const auto n = static_cast<Index>(mesh.points.size());
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    for (Index v : mesh.triangles[t]) {
      if (v < 0 || v >= n) {
        return absl::InvalidArgumentError(absl::StrFormat(
            "discrete surface: triangle %d uses point %d, outside [0, %d)", t, v, n));
      }
    }
    if (!has_distinct_indices(mesh.triangles[t])) {
      return absl::InvalidArgumentError(
          absl::StrFormat("discrete surface: triangle %d repeats a point", t));
    }
  }
  return absl::OkStatus();
}

// The face the walk moves to next: the best offered that is strictly nearer to x than where the
// walk stands, ties between offers to the smaller id (so the walk does not depend on the order in
// which faces are looked at).
struct Move {
  FaceId face = kNoFace;
  Point closest{0.0, 0.0, 0.0};
  double squared_distance = 0.0;  // start: the distance where the walk stands

  void offer(FaceId g, const Point& g_closest, double d) {
    if (d < squared_distance || (d == squared_distance && face != kNoFace && g < face)) {
      face = g;
      closest = g_closest;
      squared_distance = d;
    }
  }
  // Moves `at` to the face found; false when none was nearer.
  bool apply(Located& at) const {
    if (face == kNoFace) return false;
    at.face = face;
    at.closest = closest;
    at.squared_distance = squared_distance;
    return true;
  }
};

// cannot_be_nearer: faces whose doubled area is under this times their ball's squared radius (an
// equilateral face has 2.6; this is a face ~130 times flatter) get no ball.
constexpr double kBallShape = 0.02;

}  // namespace

absl::StatusOr<DiscreteSurface> DiscreteSurface::build(const Mesh& mesh,
                                                       const DiscreteSurfaceParams& params,
                                                       Progress& progress,
                                                       EdgeNeighbours neighbours) {
  CancelCheck cancel(progress);
  const auto cancelled = [] { return absl::CancelledError("surface model: cancelled"); };
  if (absl::Status status = check_input(mesh); !status.ok()) return status;
  DiscreteSurface s;
  s.params_ = params;
  Box bounds = empty_box();
  for (const Point& p : mesh.points) enclose(bounds, p);
  for (int k = 0; k < 3; ++k) s.origin_[k] = 0.5 * bounds.lo[k] + 0.5 * bounds.hi[k];
  s.points_.reserve(mesh.points.size());
  for (const Point& p : mesh.points) s.points_.push_back(s.to_local(p));
  s.size_ = distance(bounds.lo, bounds.hi);
  s.triangles_ = mesh.triangles;
  s.tags_ = mesh.triangle_tags.empty() ? std::vector<Index>(mesh.triangles.size(), 0)
                                       : mesh.triangle_tags;

  if (cancel.look()) return cancelled();
  s.normals_.reserve(s.triangles_.size());
  for (const Triangle& t : s.triangles_) {
    const Point n = unit_normal(s.points_[t[0]], s.points_[t[1]], s.points_[t[2]]);
    s.normals_.push_back(n);
    if (n == Point{0.0, 0.0, 0.0}) ++s.degenerate_faces_;
  }
  if (cancel.look()) return cancelled();
  s.balls_.reserve(s.triangles_.size());
  for (const Triangle& t : s.triangles_) {
    const Point c =
        scale(add(s.points_[t[0]], add(s.points_[t[1]], s.points_[t[2]])), 1.0 / 3.0);
    double radius = 0.0;
    for (const Index v : t) radius = std::max(radius, distance(c, s.points_[v]));
    // A sliver's closest point (barycentric coordinates from nearly cancelling areas) can round
    // far off the face, out of its ball: no ball for it, cannot_be_nearer is never true there.
    const Point& a = s.points_[t[0]];
    if (!(norm(cross(sub(s.points_[t[1]], a), sub(s.points_[t[2]], a))) >=
          kBallShape * radius * radius))
      radius = std::numeric_limits<double>::infinity();
    s.balls_.push_back({c, radius});
  }
  if (cancel.look()) return cancelled();
  if (neighbours.across.size() == s.triangles_.size() &&
      neighbours.same_way.size() == s.triangles_.size() && !s.triangles_.empty()) {
    s.neighbours_ = std::move(neighbours);
  } else {
    s.neighbours_ = triangle_edge_neighbours(s.triangles_, &cancel);
    if (cancel.stopped()) return cancelled();
  }

  if (cancel.look()) return cancelled();
  // Faces by vertex (a counting sort: ascending face ids in each bucket).
  s.face_offsets_.assign(s.points_.size() + 1, 0);
  for (const Triangle& t : s.triangles_) {
    for (Index v : t) ++s.face_offsets_[v + 1];
  }
  std::partial_sum(s.face_offsets_.begin(), s.face_offsets_.end(), s.face_offsets_.begin());
  s.vertex_faces_.resize(3 * s.triangles_.size());
  std::vector<Index> next(s.face_offsets_.begin(), s.face_offsets_.end() - 1);
  for (Index f = 0; f < s.face_count(); ++f) {
    for (Index v : s.triangles_[f]) s.vertex_faces_[next[v]++] = f;
  }

  if (cancel.look()) return cancelled();
  if (params.tree) s.build_tree(&cancel);
  if (cancel.look()) return cancelled();
  return s;
}

void DiscreteSurface::for_each_face_overlapping(const Box& box,
                                                absl::FunctionRef<void(FaceId)> visit) const {
  tree_.for_each_overlap(box, [&](Index f) { visit(FaceId{f}); });
}

void DiscreteSurface::build_tree(CancelCheck* cancel) {
  tree_ = AabbTree(triangle_boxes(points_, triangles_), AabbTree::kDefaultLeafSize, cancel);
}

Point DiscreteSurface::to_local(const Point& global) const { return sub(global, origin_); }

Point DiscreteSurface::to_global(const Point& local) const { return add(local, origin_); }

std::span<const Index> DiscreteSurface::faces_at(Index vertex) const {
  return std::span<const Index>(vertex_faces_)
      .subspan(face_offsets_[vertex], face_offsets_[vertex + 1] - face_offsets_[vertex]);
}

void DiscreteSurface::faces_at_edge(Index a, Index b, std::vector<Index>& forward,
                                    std::vector<Index>& backward) const {
  forward.clear();
  backward.clear();
  for (const Index f : faces_at(a)) {
    const Triangle& t = triangles_[f];
    for (int k = 0; k < 3; ++k) {
      if (t[k] == a && t[(k + 1) % 3] == b) forward.push_back(f);
      if (t[k] == b && t[(k + 1) % 3] == a) backward.push_back(f);
    }
  }
}

FaceId DiscreteSurface::face_at_edge(Index a, Index b) const {
  FaceId backward = kNoFace;
  for (const Index f : faces_at(a)) {
    const Triangle& t = triangles_[f];
    for (int k = 0; k < 3; ++k) {
      if (t[k] == a && t[(k + 1) % 3] == b) return FaceId{f};
      if (t[k] == b && t[(k + 1) % 3] == a && backward == kNoFace) backward = FaceId{f};
    }
  }
  return backward;
}

double DiscreteSurface::squared_distance_to(const Point& x, FaceId f, Point& closest,
                                            Located& at) const {
  ++at.evaluations;
  const Triangle& t = triangle(f);
  closest = closest_point_on_triangle(x, points_[t[0]], points_[t[1]], points_[t[2]]);
  return squared_distance(x, closest);
}

double DiscreteSurface::squared_distance_to_face(const Point& x, FaceId f) const {
  Point closest;
  return squared_distance_to_face(x, f, closest);
}

double DiscreteSurface::squared_distance_to_face(const Point& x, FaceId f, Point& closest) const {
  Located unused;
  return squared_distance_to(x, f, closest, unused);
}

Box DiscreteSurface::ball_box(FaceId f) const {
  const Ball& ball = balls_[index_of(f)];
  return grown(Box{ball.centroid, ball.centroid}, ball.radius);
}

// cannot_be_nearer is false only where the gap from x to the ball is at most
// sqrt(squared_distance / (1 - 1e-9)) (or not positive): the ball then comes within
// sqrt(squared_distance) (1 + 1e-9) + the margin of x, which the box's half-width exceeds by
// far more than the roundings of the gap's few operations.
Box DiscreteSurface::reach_box(const Point& x, double squared_distance) const {
  const double reach = std::sqrt(squared_distance) * (1.0 + 1e-6) + 2.0 * ball_margin(x);
  return grown(Box{x, x}, reach);
}

Located DiscreteSurface::nearest_face(const Point& x) const {
  Located at;
  AabbTree::Nearest found{kInvalidIndex, std::numeric_limits<double>::infinity()};
  if (has_tree()) {
    found = tree_.nearest(x, [&](Index f) {
      Point closest;
      return squared_distance_to(x, FaceId{f}, closest, at);
    });
  } else {
    // Every face in id order, the strictly nearer kept: the tree's answer, ties to the smaller
    // id. A face whose ball is farther than the best so far is passed over, as in the walk.
    const double margin = ball_margin(x);
    for (Index f = 0; f < face_count(); ++f) {
      if (cannot_be_nearer(x, margin, FaceId{f}, found.squared_distance)) continue;
      Point closest;
      const double d = squared_distance_to(x, FaceId{f}, closest, at);
      if (d < found.squared_distance) found = {f, d};
    }
  }
  at.face = FaceId{found.id};
  at.squared_distance = squared_distance_to(x, at.face, at.closest, at);
  at.used_tree = true;
  return at;
}

bool DiscreteSurface::step_around_vertices(const Point& x, Located& at) const {
  // Which corners of the face to look around: the closest point itself when it is a corner
  // (closest_point_on_triangle returns the corner bit for bit in its region), and both ends of
  // an edge without a single neighbour. Elsewhere (closest point inside the face, or inside an
  // edge whose neighbour was just found no nearer) the face is a local minimum already.
  const Triangle& t = triangle(at.face);
  const std::array<Index, 3>& across = neighbours_.across[index_of(at.face)];
  std::array<bool, 3> look{};
  for (int k = 0; k < 3; ++k) {
    if (at.closest == points_[t[k]]) look[k] = true;
    if (across[k] == kInvalidIndex) look[k] = look[(k + 1) % 3] = true;
  }
  Move move{kNoFace, {}, at.squared_distance};
  const double margin = ball_margin(x);
  for (int k = 0; k < 3; ++k) {
    if (!look[k]) continue;
    for (Index g : faces_at(t[k])) {
      if (FaceId{g} == at.face || cannot_be_nearer(x, margin, FaceId{g}, move.squared_distance))
        continue;
      Point closest;
      const double d = squared_distance_to(x, FaceId{g}, closest, at);
      move.offer(FaceId{g}, closest, d);
    }
  }
  return move.apply(at);
}

bool DiscreteSurface::walk(const Point& x, Located& at) const {
  FaceId previous = kNoFace;  // strictly farther than at.face: not worth a look
  const double margin = ball_margin(x);
  while (true) {
    // Across the edges: the strictly nearest neighbour.
    Move move{kNoFace, {}, at.squared_distance};
    for (Index g : neighbours_.across[index_of(at.face)]) {
      if (g == kInvalidIndex || FaceId{g} == previous ||
          cannot_be_nearer(x, margin, FaceId{g}, move.squared_distance))
        continue;  // no nearer than where the walk is, or the best offer: Move would not take it
      Point closest;
      const double d = squared_distance_to(x, FaceId{g}, closest, at);
      move.offer(FaceId{g}, closest, d);
    }
    previous = at.face;
    if (!move.apply(at) && !step_around_vertices(x, at)) {
      return true;  // a local minimum of the distance to x
    }
    if (++at.walk_steps > params_.max_walk_steps) return false;
  }
}

Located DiscreteSurface::locate(const Point& x, FaceId hint) const {
  if (hint == kNoFace || index_of(hint) < 0 || index_of(hint) >= face_count()) {
    return nearest_face(x);
  }
  Located at;
  at.face = hint;
  at.squared_distance = squared_distance_to(x, hint, at.closest, at);
  if (walk(x, at)) return at;
  Located found = nearest_face(x);
  found.walk_steps = at.walk_steps;
  found.evaluations += at.evaluations;
  return found;
}

}  // namespace afmesh
