#include "core/volume/front.h"

#include <algorithm>

namespace afmesh {

Front::Front(const std::vector<Point>& points, const Box& domain, double cell_size)
    : points_(points), bins_(domain, cell_size) {}

void Front::Queue::push(const QueueEntry& e) {
  const std::size_t g = 2 * std::size_t{e.cls} + (e.unmarked ? 1 : 0);
  if (g >= groups_.size()) groups_.resize(g + 1);
  std::vector<Item>& heap = groups_[g];
  const Item item{e.size, e.face, e.stamp};
  std::size_t i = heap.size();
  heap.push_back(item);
  while (i > 0) {  // sift up
    const std::size_t parent = (i - 1) / 4;
    if (!item.before(heap[parent])) break;
    heap[i] = heap[parent];
    i = parent;
  }
  heap[i] = item;
  lowest_ = std::min(lowest_, g);
  ++count_;
}

Front::QueueEntry Front::Queue::pop() {
  while (groups_[lowest_].empty()) ++lowest_;
  const std::size_t g = lowest_;
  std::vector<Item>& heap = groups_[g];
  const Item top = heap.front();
  const Item last = heap.back();
  heap.pop_back();
  --count_;
  const std::size_t n = heap.size();
  if (n > 0) {
    std::size_t i = 0;
    for (;;) {  // sift `last` down from the root
      const std::size_t first = 4 * i + 1;
      if (first >= n) break;
      std::size_t best = first;
      const std::size_t end = std::min(first + 4, n);
      for (std::size_t c = first + 1; c < end; ++c)
        if (heap[c].before(heap[best])) best = c;
      if (!heap[best].before(last)) break;
      heap[i] = heap[best];
      i = best;
    }
    heap[i] = last;
  }
  return {static_cast<std::uint32_t>(g / 2), g % 2 == 1, top.size, top.face, top.stamp};
}

Box Front::box_of_face(const Triangle& v) const { return triangle_box(points_, v); }

namespace {

int corner_of(const Triangle& v, Index p) { return v[0] == p ? 0 : v[1] == p ? 1 : 2; }

}  // namespace

void Front::point_joins(Index f, int k) {
  const Index p = faces_[f].v[k];
  if (p >= static_cast<Index>(first_face_.size())) first_face_.resize(p + 1, kInvalidIndex);
  if (first_face_[p] == kInvalidIndex) bins_.insert_point(p, points_[p]);
  faces_[f].next[k] = first_face_[p];
  first_face_[p] = f;
}

void Front::point_leaves(Index f, int k) {
  const Index p = faces_[f].v[k];
  Index* link = &first_face_[p];
  while (*link != f) {
    FrontFace& g = faces_[*link];
    link = &g.next[corner_of(g.v, p)];
  }
  *link = faces_[f].next[k];
  if (first_face_[p] == kInvalidIndex) bins_.erase_point(p, points_[p]);
}

Index Front::add(const Triangle& v, double size, Index env) {
  Index f;
  if (!free_.empty()) {
    f = free_.back();
    free_.pop_back();
  } else {
    f = static_cast<Index>(faces_.size());
    faces_.emplace_back();
  }
  FrontFace& face = faces_[f];
  face.v = v;
  face.env = env;
  face.attempts = 0;
  face.alive = true;
  ++face.stamp;
  ++live_;
  queue_.push({0, env == 0, size, f, face.stamp});
  bins_.insert_face(f, box_of_face(v));
  for (int k = 0; k < 3; ++k) point_joins(f, k);
  return f;
}

void Front::remove(Index f) {
  FrontFace& face = faces_[f];
  face.alive = false;
  --live_;
  bins_.erase_face(f, box_of_face(face.v));  // the points never move: the box it went in with
  for (int k = 0; k < 3; ++k) point_leaves(f, k);
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
  if (!on_front(a) || !on_front(b) || !on_front(c)) return std::nullopt;
  for (Index g = first_face_[a]; g != kInvalidIndex;) {
    const FrontFace& face = faces_[g];
    const Triangle& w = face.v;
    const int k = corner_of(w, a);
    if (w[(k + 1) % 3] == b && w[(k + 2) % 3] == c) return g;  // (a, b, c) up to rotation
    g = face.next[k];
  }
  return std::nullopt;
}

std::optional<Index> Front::pop() {
  while (!queue_.empty()) {
    const QueueEntry e = queue_.pop();
    const FrontFace& face = faces_[e.face];
    if (face.alive && face.stamp == e.stamp && face.attempts == e.cls) return e.face;
  }
  return std::nullopt;
}

}  // namespace afmesh
