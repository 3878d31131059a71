#include "core/shapes/graded_surface.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <queue>
#include <utility>

#include "absl/container/flat_hash_map.h"
#include "absl/strings/str_cat.h"
#include "core/geometry/vec.h"

namespace afmesh {
namespace {

// An undirected edge: its two point indices, the smaller in the high half.
using EdgeKey = std::uint64_t;

EdgeKey edge_key(Index a, Index b) {
  const auto lo = static_cast<std::uint32_t>(std::min(a, b));
  const auto hi = static_cast<std::uint32_t>(std::max(a, b));
  return (std::uint64_t{lo} << 32) | hi;
}

Index key_lo(EdgeKey key) { return static_cast<Index>(key >> 32); }
Index key_hi(EdgeKey key) { return static_cast<Index>(key & 0xffffffffu); }

// An edge waiting to be split; the queue gives the longest first, ties by key.
struct QueuedEdge {
  double length2 = 0.0;
  EdgeKey key = 0;
  bool operator<(const QueuedEdge& other) const {
    return length2 != other.length2 ? length2 < other.length2 : key < other.key;
  }
};

// The two triangles on an edge (kInvalidIndex when the edge is on an open boundary).
using EdgeTriangles = std::array<Index, 2>;

class SurfaceRefiner {
 public:
  SurfaceRefiner(const SizeField& size, const GradedSurfaceParams& params)
      : size_(size), params_(params) {}

  absl::Status start(const Mesh& surface) {
    mesh_.points = surface.points;
    for (std::size_t p = 0; p < mesh_.points.size(); ++p) {
      const Point& x = mesh_.points[p];
      if (!std::isfinite(x[0]) || !std::isfinite(x[1]) || !std::isfinite(x[2])) {
        return absl::InvalidArgumentError(absl::StrCat("point ", p, " is not finite"));
      }
    }
    for (std::size_t t = 0; t < surface.triangles.size(); ++t) {
      const Triangle& tri = surface.triangles[t];
      for (const Index v : tri) {
        if (v < 0 || static_cast<std::size_t>(v) >= mesh_.points.size()) {
          return absl::InvalidArgumentError(absl::StrCat("triangle ", t, " refers to point ", v,
                                                         ", but there are ", mesh_.points.size(),
                                                         " points"));
        }
      }
      if (tri[0] == tri[1] || tri[1] == tri[2] || tri[2] == tri[0]) {
        return absl::InvalidArgumentError(absl::StrCat("triangle ", t, " repeats a point (", tri[0],
                                                       ", ", tri[1], ", ", tri[2], ")"));
      }
      const auto slot = static_cast<Index>(t);
      mesh_.triangles.push_back(tri);
      mesh_.triangle_tags.push_back(t < surface.triangle_tags.size() ? surface.triangle_tags[t]
                                                                     : 0);
      for (int k = 0; k < 3; ++k) {
        if (!attach(edge_key(tri[k], tri[(k + 1) % 3]), slot)) {
          return absl::InvalidArgumentError(
              absl::StrCat("the edge (", tri[k], ", ", tri[(k + 1) % 3], ") of triangle ", t,
                           " is in more than two triangles: the surface must be a manifold"));
        }
      }
    }
    // The queue orders edges totally by (length, key): the order they enter it does not matter.
    for (const auto& [key, triangles] : edges_) queue_if_too_long(key);
    return absl::OkStatus();
  }

  // Splits the longest too-long edge, through its longest-edge propagation path, until none is
  // left.
  absl::Status refine() {
    while (!queue_.empty()) {
      const EdgeKey wanted = queue_.top().key;
      if (!edges_.contains(wanted)) {  // split already, on the path of another edge
        queue_.pop();
        continue;
      }
      const EdgeKey terminal = terminal_edge(wanted);
      if (terminal == wanted) queue_.pop();  // else `wanted` stays queued for a later round
      split(terminal);
      if (mesh_.triangles.size() > params_.max_triangles) {
        return absl::ResourceExhaustedError(absl::StrCat(
            "grading the surface needs more than ", params_.max_triangles,
            " triangles (GradedSurfaceParams::max_triangles); is the size field too small?"));
      }
    }
    return absl::OkStatus();
  }

  Mesh take() { return std::move(mesh_); }

 private:
  double length2(EdgeKey key) const {
    return squared_distance(mesh_.points[key_lo(key)], mesh_.points[key_hi(key)]);
  }

  // (length, key) order: the longer edge, ties by key.
  bool longer(EdgeKey a, EdgeKey b) const {
    return QueuedEdge{length2(b), b} < QueuedEdge{length2(a), a};
  }

  void queue_if_too_long(EdgeKey key) {
    const Point& a = mesh_.points[key_lo(key)];
    const Point& b = mesh_.points[key_hi(key)];
    const double limit = params_.max_ratio * size_.size_at(lerp(a, b, 0.5));
    const double l2 = squared_distance(a, b);
    if (l2 > limit * limit) queue_.push({l2, key});
  }

  // Adds triangle t to the edge; false when the edge has two triangles already.
  bool attach(EdgeKey key, Index t) {
    EdgeTriangles& triangles =
        edges_.try_emplace(key, EdgeTriangles{kInvalidIndex, kInvalidIndex}).first->second;
    if (triangles[0] == kInvalidIndex) {
      triangles[0] = t;
    } else if (triangles[1] == kInvalidIndex) {
      triangles[1] = t;
    } else {
      return false;
    }
    return true;
  }

  void replace(EdgeKey key, Index from, Index to) {
    for (Index& t : edges_.at(key)) {
      if (t == from) t = to;
    }
  }

  EdgeKey longest_edge(Index t) const {
    const Triangle& tri = mesh_.triangles[t];
    EdgeKey best = edge_key(tri[0], tri[1]);
    for (const EdgeKey key : {edge_key(tri[1], tri[2]), edge_key(tri[2], tri[0])}) {
      if (longer(key, best)) best = key;
    }
    return best;
  }

  // The end of the longest-edge propagation path from `key`: an edge that is the longest of each
  // of its triangles. Lengths grow strictly along the path, so it ends.
  EdgeKey terminal_edge(EdgeKey key) const {
    for (;;) {
      EdgeKey next = key;
      for (const Index t : edges_.at(key)) {
        if (t == kInvalidIndex) continue;
        const EdgeKey candidate = longest_edge(t);
        if (longer(candidate, next)) next = candidate;
      }
      if (next == key) return key;
      key = next;
    }
  }

  // Bisects triangle t across its edge {a, b} at the new point m: t keeps the half at a, the
  // half at b is appended; both keep t's orientation and tag. Returns t's third point.
  Index split_triangle(Index t, Index a, Index b, Index m) {
    Triangle tri = mesh_.triangles[t];
    while (!((tri[0] == a && tri[1] == b) || (tri[0] == b && tri[1] == a))) {
      tri = {tri[1], tri[2], tri[0]};
    }
    const Index u = tri[0], v = tri[1], w = tri[2];
    const auto n = static_cast<Index>(mesh_.triangles.size());
    mesh_.triangles[t] = {u, m, w};
    mesh_.triangles.push_back({m, v, w});
    mesh_.triangle_tags.push_back(mesh_.triangle_tags[t]);
    attach(edge_key(u, m), t);
    attach(edge_key(m, v), n);
    attach(edge_key(m, w), t);
    attach(edge_key(m, w), n);
    replace(edge_key(v, w), t, n);
    return w;
  }

  // Splits `key` at its midpoint in both of its triangles and queues the new edges that are
  // too long.
  void split(EdgeKey key) {
    const Index a = key_lo(key), b = key_hi(key);
    const auto m = static_cast<Index>(mesh_.points.size());
    mesh_.points.push_back(lerp(mesh_.points[a], mesh_.points[b], 0.5));
    const EdgeTriangles triangles = edges_.at(key);
    edges_.erase(key);
    queue_if_too_long(edge_key(a, m));
    queue_if_too_long(edge_key(m, b));
    for (const Index t : triangles) {
      if (t != kInvalidIndex) queue_if_too_long(edge_key(m, split_triangle(t, a, b, m)));
    }
  }

  const SizeField& size_;
  const GradedSurfaceParams& params_;
  Mesh mesh_;
  absl::flat_hash_map<EdgeKey, EdgeTriangles> edges_;
  std::priority_queue<QueuedEdge> queue_;
};

}  // namespace

absl::StatusOr<Mesh> grade_surface(const Mesh& surface, const SizeField& size,
                                   const GradedSurfaceParams& params) {
  if (!(params.max_ratio > 0.0) || !std::isfinite(params.max_ratio)) {
    return absl::InvalidArgumentError(
        absl::StrCat("max_ratio must be finite and > 0, got ", params.max_ratio));
  }
  SurfaceRefiner refiner(size, params);
  if (absl::Status status = refiner.start(surface); !status.ok()) return status;
  if (absl::Status status = refiner.refine(); !status.ok()) return status;
  return refiner.take();
}

}  // namespace afmesh
