#include "core/volume/front.h"

#include <algorithm>

namespace afmesh {

Front::Front(const std::vector<Point>& points, const Box& domain, double cell_size)
    : points_(points), bins_(domain, cell_size) {}

void FaceLookup::assign(const Triangle& k, Index f) {
  if (2 * (count_ + 1) > slots_.size()) grow();
  std::size_t i = home(k);
  for (; slots_[i].face != kInvalidIndex; i = (i + 1) & mask_) {
    if (slots_[i].key == k) {
      slots_[i].face = f;
      return;
    }
  }
  slots_[i] = {k, f};
  ++count_;
}

void FaceLookup::erase(const Triangle& k) {
  std::size_t i = home(k);
  for (; slots_[i].key != k; i = (i + 1) & mask_)
    if (slots_[i].face == kInvalidIndex) return;  // absent
  if (slots_[i].face == kInvalidIndex) return;  // absent (k is the empty slots' key)
  // Backward shift: move each later slot of the probe run whose home does not lie cyclically
  // in (i, j] into the hole, so every key stays reachable from its home without tombstones.
  for (std::size_t j = (i + 1) & mask_; slots_[j].face != kInvalidIndex; j = (j + 1) & mask_) {
    const std::size_t h = home(slots_[j].key);
    const bool stays = i <= j ? (i < h && h <= j) : (i < h || h <= j);
    if (stays) continue;
    slots_[i] = slots_[j];
    i = j;
  }
  slots_[i] = Slot{};
  --count_;
}

void FaceLookup::grow() {
  std::vector<Slot> old = std::move(slots_);
  slots_.assign(old.size() * 2, Slot{});
  mask_ = slots_.size() - 1;
  for (const Slot& s : old) {
    if (s.face == kInvalidIndex) continue;
    std::size_t i = home(s.key);
    while (slots_[i].face != kInvalidIndex) i = (i + 1) & mask_;
    slots_[i] = s;
  }
}

void Front::Queue::push(const QueueEntry& e) {
  std::size_t i = heap_.size();
  heap_.push_back(e);
  while (i > 0) {  // sift up
    const std::size_t parent = (i - 1) / 4;
    if (!e.before(heap_[parent])) break;
    heap_[i] = heap_[parent];
    i = parent;
  }
  heap_[i] = e;
}

Front::QueueEntry Front::Queue::pop() {
  const QueueEntry top = heap_.front();
  const QueueEntry last = heap_.back();
  heap_.pop_back();
  const std::size_t n = heap_.size();
  if (n == 0) return top;
  std::size_t i = 0;
  for (;;) {  // sift `last` down from the root
    const std::size_t first = 4 * i + 1;
    if (first >= n) break;
    std::size_t best = first;
    const std::size_t end = std::min(first + 4, n);
    for (std::size_t c = first + 1; c < end; ++c)
      if (heap_[c].before(heap_[best])) best = c;
    if (!heap_[best].before(last)) break;
    heap_[i] = heap_[best];
    i = best;
  }
  heap_[i] = last;
  return top;
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
  lookup_.assign(key_of(v[0], v[1], v[2]), f);
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
  lookup_.erase(key_of(face.v[0], face.v[1], face.v[2]));
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
  // A live face's corners are on the front; most calls ask about a new point, which is not, and
  // skip the table (a cache miss on a large front).
  if (!on_front(a) || !on_front(b) || !on_front(c)) return std::nullopt;
  const Index f = lookup_.find(key_of(a, b, c));
  if (f == kInvalidIndex) return std::nullopt;
  return f;
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
