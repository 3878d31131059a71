// Greedy flip-based recovery of prescribed triangles (recover_faces.h).
#include "core/delaunay/recover_faces.h"

#include <algorithm>
#include <array>
#include <utility>

#include "absl/container/flat_hash_map.h"
#include "absl/container/flat_hash_set.h"
#include "core/geometry/intersect.h"
#include "core/geometry/predicates.h"
#include "core/quality/mesh_topology.h"

namespace afmesh {
namespace {

using FaceKey = Triangle;  // sorted: an unoriented face

FaceKey key_of(Index a, Index b, Index c) { return sorted_triangle({a, b, c}); }

// The face of tet t opposite its corner k, unoriented.
FaceKey face_of(const Tet& t, int k) { return sorted_triangle(tet_face(t, k)); }

// A tetrahedralisation that flips: its live elements, the elements on each face (one on the
// hull) and the elements on each vertex.
class FlipComplex {
 public:
  FlipComplex(std::span<const Point> x, const std::vector<Tet>& tets) : x_(x) {
    Index top = 0;
    for (const Tet& t : tets)
      for (Index v : t) top = std::max(top, v);
    of_vertex_.resize(static_cast<std::size_t>(top) + 1);
    for (const Tet& t : tets) add(t);
  }

  const Point& at(Index v) const { return x_[static_cast<std::size_t>(v)]; }
  const Tet& tet(Index t) const { return tets_[static_cast<std::size_t>(t)]; }
  bool has_face(const FaceKey& k) const { return faces_.contains(k); }

  // The element across tet t's face opposite corner k, or kInvalidIndex on the hull.
  Index across(Index t, int k) const {
    const auto it = faces_.find(face_of(tet(t), k));
    if (it == faces_.end()) return kInvalidIndex;
    return it->second[0] == t ? it->second[1] : it->second[0];
  }

  // The live elements on edge (a, b).
  void edge_ring(Index a, Index b, std::vector<Index>& out) const {
    out.clear();
    for (Index t : of_vertex_[static_cast<std::size_t>(a)])
      if (has_corner(tet(t), b)) out.push_back(t);
  }
  const std::vector<Index>& elements_of(Index v) const {
    return of_vertex_[static_cast<std::size_t>(v)];
  }

  // Replaces the elements `old` by `fresh` (each positive).
  void replace(const std::vector<Index>& old, const std::vector<Tet>& fresh) {
    for (Index t : old) remove(t);
    for (const Tet& t : fresh) add(t);
  }

  std::vector<Tet> live() const {
    std::vector<Tet> out;
    for (std::size_t t = 0; t < tets_.size(); ++t)
      if (alive_[t]) out.push_back(tets_[t]);
    return out;
  }

 private:
  void add(const Tet& v) {
    Index t;
    if (!free_.empty()) {
      t = free_.back();
      free_.pop_back();
      tets_[static_cast<std::size_t>(t)] = v;
      alive_[static_cast<std::size_t>(t)] = true;
    } else {
      t = static_cast<Index>(tets_.size());
      tets_.push_back(v);
      alive_.push_back(true);
    }
    for (int k = 0; k < 4; ++k) {
      auto [it, fresh] = faces_.try_emplace(face_of(v, k), std::array<Index, 2>{t, kInvalidIndex});
      if (!fresh) it->second[1] = t;
      of_vertex_[static_cast<std::size_t>(v[k])].push_back(t);
    }
  }
  void remove(Index t) {
    const Tet v = tet(t);
    alive_[static_cast<std::size_t>(t)] = false;
    free_.push_back(t);
    for (int k = 0; k < 4; ++k) {
      const auto it = faces_.find(face_of(v, k));
      std::array<Index, 2>& on = it->second;
      if (on[0] == t) std::swap(on[0], on[1]);
      on[1] = kInvalidIndex;
      if (on[0] == kInvalidIndex) faces_.erase(it);
      std::erase(of_vertex_[static_cast<std::size_t>(v[k])], t);
    }
  }

  std::span<const Point> x_;
  std::vector<Tet> tets_;
  std::vector<bool> alive_;
  std::vector<Index> free_;
  absl::flat_hash_map<FaceKey, std::array<Index, 2>> faces_;
  std::vector<std::vector<Index>> of_vertex_;
};

// The positive element on four points, or nothing (kInvalidIndex first) when they are coplanar.
Tet positive(const FlipComplex& c, Index a, Index b, Index d, Index e) {
  const int o = orient3d(c.at(a), c.at(b), c.at(d), c.at(e));
  if (o > 0) return {a, b, d, e};
  if (o < 0) return {b, a, d, e};
  return {kInvalidIndex, kInvalidIndex, kInvalidIndex, kInvalidIndex};
}

// A flip: the elements it removes and those it makes in their place.
struct Flip {
  std::vector<Index> old;
  std::vector<Tet> fresh;
};

// 2-3: elements t and u sharing the face opposite t's corner k, replaced by three around the
// edge joining their far corners, when that edge crosses the shared face's interior.
bool flip_23(const FlipComplex& c, Index t, int k, Flip& flip) {
  const Index u = c.across(t, k);
  if (u == kInvalidIndex) return false;
  const Tet& a = c.tet(t);
  const Tet& b = c.tet(u);
  const Index p = a[k];
  Index q = kInvalidIndex;
  for (Index v : b)
    if (!has_corner(a, v)) q = v;
  const FaceKey f = face_of(a, k);
  int sign = 0;
  for (int i = 0; i < 3; ++i) {
    const int o = orient3d(c.at(p), c.at(q), c.at(f[i]), c.at(f[(i + 1) % 3]));
    if (o == 0 || (sign != 0 && o != sign)) return false;
    sign = o;
  }
  flip.old = {t, u};
  flip.fresh.clear();
  for (int i = 0; i < 3; ++i) flip.fresh.push_back(positive(c, f[i], f[(i + 1) % 3], p, q));
  return true;
}

// 3-2, 4-4 and 2-2 about edge (a, b). 3-2: the edge has three elements around it and crosses
// the interior of the triangle of their other corners; they are replaced by the two elements on
// that triangle. 4-4: the edge has four elements around it, and it and two opposite corners of
// their ring make a convex quadrilateral in one plane (two coplanar faces inside, such as a
// planar CAD face's two triangles); the edge is turned to the quadrilateral's other diagonal.
// 2-2 on the hull: the edge has two elements, whose faces on the edge that no other element
// shares are coplanar and make a convex quadrilateral; the edge is turned likewise.
bool flip_about_edge(const FlipComplex& c, Index a, Index b, std::vector<Index>& ring,
                     Flip& flip) {
  c.edge_ring(a, b, ring);
  std::vector<Index> others;
  for (Index t : ring)
    for (Index v : c.tet(t))
      if (v != a && v != b && std::find(others.begin(), others.end(), v) == others.end())
        others.push_back(v);
  if (ring.size() == 3 && others.size() == 3) {
    const Index d = others[0], e = others[1], g = others[2];
    const int sa = orient3d(c.at(d), c.at(e), c.at(g), c.at(a));
    const int sb = orient3d(c.at(d), c.at(e), c.at(g), c.at(b));
    if (sa == 0 || sb == 0 || sa == sb) return false;
    const int s1 = orient3d(c.at(a), c.at(b), c.at(d), c.at(e));
    const int s2 = orient3d(c.at(a), c.at(b), c.at(e), c.at(g));
    const int s3 = orient3d(c.at(a), c.at(b), c.at(g), c.at(d));
    if (s1 == 0 || s1 != s2 || s2 != s3) return false;
    flip.old = ring;
    flip.fresh = {positive(c, d, e, g, a), positive(c, d, e, g, b)};
    return true;
  }
  if (ring.size() == 4 && others.size() == 4) {
    // 4-4: a, b and two opposite ring corners u, w (no element holds both) coplanar, the
    // segments a-b and u-w crossing: the edge is turned to u-w.
    for (int i = 0; i < 4; ++i)
      for (int j = i + 1; j < 4; ++j) {
        const Index u = others[i], w = others[j];
        bool together = false;
        for (Index t : ring)
          together = together || (has_corner(c.tet(t), u) && has_corner(c.tet(t), w));
        if (together) continue;
        if (orient3d(c.at(a), c.at(b), c.at(u), c.at(w)) != 0) continue;
        Index v0 = kInvalidIndex, v1 = kInvalidIndex;  // the other two ring corners
        for (Index v : others)
          if (v != u && v != w) (v0 == kInvalidIndex ? v0 : v1) = v;
        const int su = orient3d(c.at(a), c.at(b), c.at(v0), c.at(u));
        const int sw = orient3d(c.at(a), c.at(b), c.at(v0), c.at(w));
        const int sa = orient3d(c.at(u), c.at(w), c.at(v0), c.at(a));
        const int sb = orient3d(c.at(u), c.at(w), c.at(v0), c.at(b));
        if (su == 0 || sw == 0 || su == sw || sa == 0 || sb == 0 || sa == sb) continue;
        flip.old = ring;
        flip.fresh = {positive(c, u, w, v0, a), positive(c, u, w, v0, b),
                      positive(c, u, w, v1, a), positive(c, u, w, v1, b)};
        return true;
      }
    return false;
  }
  if (ring.size() == 2 && others.size() == 3) {
    // The corner both elements share besides a and b is p; the hull faces are (a, b, x), (a, b, y).
    Index p = kInvalidIndex;
    for (Index v : others)
      if (has_corner(c.tet(ring[0]), v) && has_corner(c.tet(ring[1]), v)) p = v;
    if (p == kInvalidIndex) return false;
    Index x = kInvalidIndex, y = kInvalidIndex;
    for (Index v : c.tet(ring[0]))
      if (v != a && v != b && v != p) x = v;
    for (Index v : c.tet(ring[1]))
      if (v != a && v != b && v != p) y = v;
    // Both outer faces must be on the hull (one element each) and coplanar.
    const auto on_hull = [&](Index t, Index o) {
      const Tet& v = c.tet(t);
      for (int k = 0; k < 4; ++k)
        if (v[k] == p) return c.across(t, k) == kInvalidIndex && o != kInvalidIndex;
      return false;
    };
    if (!on_hull(ring[0], x) || !on_hull(ring[1], y)) return false;
    if (orient3d(c.at(a), c.at(b), c.at(x), c.at(y)) != 0) return false;
    // Convex: a and b on opposite sides of the plane (x, y, p), x and y of the plane (a, b, p).
    const int sa = orient3d(c.at(x), c.at(y), c.at(p), c.at(a));
    const int sb = orient3d(c.at(x), c.at(y), c.at(p), c.at(b));
    if (sa == 0 || sb == 0 || sa == sb) return false;
    flip.old = ring;
    flip.fresh = {positive(c, x, y, p, a), positive(c, x, y, p, b)};
    return true;
  }
  return false;
}

// The live elements that meet triangle f improperly (tet_triangle_intersect_improperly): a flood
// through faces from the elements on f's corners.
void elements_meeting(const FlipComplex& c, std::span<const Point> x, const Triangle& f,
                      std::vector<Index>& out, std::int64_t& tests) {
  out.clear();
  absl::flat_hash_set<Index> seen;
  std::vector<Index> todo;
  for (Index v : f)
    for (Index t : c.elements_of(v))
      if (seen.insert(t).second) todo.push_back(t);
  while (!todo.empty()) {
    const Index t = todo.back();
    todo.pop_back();
    ++tests;
    if (!tet_triangle_intersect_improperly(x, c.tet(t), f)) continue;
    out.push_back(t);
    for (int k = 0; k < 4; ++k) {
      const Index u = c.across(t, k);
      if (u != kInvalidIndex && seen.insert(u).second) todo.push_back(u);
    }
  }
}

}  // namespace

std::vector<Index> recover_faces_by_flips(std::span<const Point> points, std::vector<Tet>& tets,
                                         std::span<const Triangle> faces,
                                         std::int64_t max_tests, CancelCheck* stop) {
  FlipComplex c(points, tets);
  absl::flat_hash_set<FaceKey> prescribed;
  for (const Triangle& f : faces) prescribed.insert(key_of(f[0], f[1], f[2]));
  // A flip may not remove a prescribed triangle that is a face now.
  const auto keeps_prescribed = [&](const Flip& flip) {
    for (Index t : flip.old)
      for (int k = 0; k < 4; ++k) {
        const FaceKey f = face_of(c.tet(t), k);
        if (!prescribed.contains(f)) continue;
        bool kept = false;
        for (const Tet& n : flip.fresh)
          for (int j = 0; j < 4 && !kept; ++j) kept = face_of(n, j) == f;
        if (!kept) return false;
      }
    return true;
  };
  std::int64_t tests = 0;  // tet-triangle tests, the work bounded by max_tests
  std::vector<Index> meeting, ring;
  Flip flip, best;
  for (bool progress = true; progress && tests < max_tests;) {
    progress = false;
    for (const Triangle& f : faces) {
      while (!c.has_face(key_of(f[0], f[1], f[2])) && tests < max_tests) {
        if (stop != nullptr && stop->due()) {
          tests = max_tests;
          break;
        }
        elements_meeting(c, points, f, meeting, tests);
        int best_gain = 0;
        const auto consider = [&](const Flip& candidate) {
          for (const Tet& n : candidate.fresh)
            if (n[0] == kInvalidIndex) return;
          int gain = 0;
          for (Index t : candidate.old)
            gain += tet_triangle_intersect_improperly(points, c.tet(t), f) ? 1 : 0;
          for (const Tet& n : candidate.fresh)
            gain -= tet_triangle_intersect_improperly(points, n, f) ? 1 : 0;
          tests += static_cast<std::int64_t>(candidate.old.size() + candidate.fresh.size());
          if (gain > best_gain && keeps_prescribed(candidate)) {
            best_gain = gain;
            best = candidate;
          }
        };
        for (Index t : meeting) {
          for (int k = 0; k < 4; ++k)
            if (flip_23(c, t, k, flip)) consider(flip);
          const Tet v = c.tet(t);
          for (int i = 0; i < 4; ++i)
            for (int j = i + 1; j < 4; ++j)
              if (flip_about_edge(c, v[i], v[j], ring, flip)) consider(flip);
        }
        if (best_gain == 0) break;
        c.replace(best.old, best.fresh);
        progress = true;
      }
    }
  }
  tets = c.live();
  std::vector<Index> missing;
  for (std::size_t i = 0; i < faces.size(); ++i)
    if (!c.has_face(sorted_triangle(faces[i]))) missing.push_back(static_cast<Index>(i));
  return missing;
}

}  // namespace afmesh
