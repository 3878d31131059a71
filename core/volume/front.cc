#include "core/volume/front.h"

#include <algorithm>

namespace afmesh {

Front::Front(const std::vector<Point>& points, const Box& domain, double cell_size)
    : points_(points), bins_(domain, cell_size) {}

// The oriented triangle (a, b, c) rotated to start at its smallest index: one key per
// orientation.
absl::uint128 Front::key_of(Index a, Index b, Index c) {
  if (b < a && b < c) {
    std::swap(a, b);  // (b, c, a)
    std::swap(b, c);
  } else if (c < a && c < b) {
    std::swap(a, c);  // (c, a, b)
    std::swap(b, c);
  }
  return (absl::uint128(static_cast<std::uint32_t>(a)) << 64) |
         (absl::uint128(static_cast<std::uint32_t>(b)) << 32) |
         absl::uint128(static_cast<std::uint32_t>(c));
}

Box Front::box_of_face(const Triangle& v) const { return triangle_box(points_, v); }

void Front::point_joins(Index p) {
  if (p >= static_cast<Index>(point_faces_.size())) point_faces_.resize(p + 1, 0);
  if (point_faces_[p]++ == 0) bins_.insert_point(p, points_[p]);
}

void Front::point_leaves(Index p) {
  if (--point_faces_[p] == 0) bins_.erase_point(p, points_[p]);
}

Index Front::add(const Triangle& v, double size, Index env) {
  Index f;
  if (!free_.empty()) {
    f = free_.back();
    free_.pop_back();
  } else {
    f = static_cast<Index>(faces_.size());
    faces_.emplace_back();
    boxes_.emplace_back();
  }
  FrontFace& face = faces_[f];
  face.v = v;
  face.env = env;
  face.attempts = 0;
  face.alive = true;
  ++face.stamp;
  ++live_;
  lookup_[key_of(v[0], v[1], v[2])] = f;
  queue_.push({0, env == 0, size, f, face.stamp});
  boxes_[f] = box_of_face(v);
  bins_.insert_face(f, boxes_[f]);
  for (Index p : v) point_joins(p);
  return f;
}

void Front::remove(Index f) {
  FrontFace& face = faces_[f];
  face.alive = false;
  --live_;
  // A second face with the same orientation (two layers over one lens of crossing sides) may
  // have taken the key; remove only this face's own entry.
  const auto it = lookup_.find(key_of(face.v[0], face.v[1], face.v[2]));
  if (it != lookup_.end() && it->second == f) lookup_.erase(it);
  bins_.erase_face(f, boxes_[f]);
  for (Index p : face.v) point_leaves(p);
  free_.push_back(f);
}

void Front::defer(Index f, double size) {
  FrontFace& face = faces_[f];
  if (face.attempts < 255) ++face.attempts;
  queue_.push({face.attempts, face.env == 0, size, f, face.stamp});
}

void Front::requeue(Index f, double size) {
  FrontFace& face = faces_[f];
  face.attempts = 0;
  ++face.stamp;
  queue_.push({0, face.env == 0, size, f, face.stamp});
}

std::optional<Index> Front::find(Index a, Index b, Index c) const {
  auto it = lookup_.find(key_of(a, b, c));
  if (it == lookup_.end()) return std::nullopt;
  return it->second;
}

std::optional<Index> Front::pop() {
  while (!queue_.empty()) {
    const QueueEntry e = queue_.top();
    queue_.pop();
    const FrontFace& face = faces_[e.face];
    if (face.alive && face.stamp == e.stamp && face.attempts == e.cls) return e.face;
  }
  return std::nullopt;
}

}  // namespace afmesh
