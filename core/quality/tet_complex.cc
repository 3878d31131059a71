#include "core/quality/tet_complex.h"

#include <algorithm>
#include <limits>
#include <utility>

#include "absl/strings/str_format.h"
#include "core/quality/mesh_topology.h"

namespace afmesh {
namespace {

// +1 when (t[i0], t[i1], t[i2], t[i3]) is an even permutation of t, -1 when odd.
int permutation_sign(int i0, int i1, int i2, int i3) {
  const int p[4] = {i0, i1, i2, i3};
  int inversions = 0;
  for (int i = 0; i < 4; ++i)
    for (int j = i + 1; j < 4; ++j) inversions += p[i] > p[j];
  return inversions % 2 == 0 ? 1 : -1;
}

Triangle reversed(const Triangle& f) { return {f[0], f[2], f[1]}; }

}  // namespace

absl::StatusOr<TetComplex> TetComplex::build(Mesh& mesh, Progress& progress) {
  const auto n = static_cast<Index>(mesh.points.size());
  const auto k = static_cast<Index>(mesh.tets.size());
  for (Index t = 0; t < k; ++t) {
    const Tet& q = mesh.tets[t];
    for (int i = 0; i < 4; ++i) {
      if (q[i] < 0 || q[i] >= n)
        return absl::InvalidArgumentError(
            absl::StrFormat("tet %d: point index %d out of range [0, %d)", t, q[i], n));
      for (int j = 0; j < i; ++j)
        if (q[i] == q[j])
          return absl::InvalidArgumentError(
              absl::StrFormat("tet %d repeats point %d", t, q[i]));
    }
  }
  mesh.tet_tags.resize(mesh.tets.size(), 0);
  TetComplex c(mesh);
  c.adjacent_.assign(mesh.tets.size(), {kInvalidIndex, kInvalidIndex, kInvalidIndex, kInvalidIndex});
  c.point_tet_.assign(mesh.points.size(), kInvalidIndex);
  // The faces shared by two tets make them neighbours across those corners.
  std::vector<Index> ids(mesh.tets.size());
  for (Index t = 0; t < k; ++t) ids[t] = t;
  absl::Status shared_by_more;
  CancelCheck stop(progress);
  for_each_tet_face(mesh.tets, ids, [&](std::span<const FaceUse> uses) {
    if (uses.size() > 2 && shared_by_more.ok()) {
      shared_by_more = absl::InvalidArgumentError(absl::StrFormat(
          "face (%d, %d, %d) is in more than two tets (%d, %d, %d)", uses[0].key[0],
          uses[0].key[1], uses[0].key[2], uses[0].tet, uses[1].tet, uses[2].tet));
    }
    if (uses.size() == 2) {
      c.adjacent_[uses[0].tet][uses[0].corner] = uses[1].tet;
      c.adjacent_[uses[1].tet][uses[1].corner] = uses[0].tet;
    }
  }, &stop);
  if (stop.stopped()) return absl::CancelledError("mesh optimisation cancelled");
  if (!shared_by_more.ok()) return shared_by_more;
  for (Index t = 0; t < k; ++t)
    for (Index p : mesh.tets[t]) c.point_tet_[p] = t;
  return c;
}

int TetComplex::corner_of(Index t, Index p) const {
  const Tet& q = m_->tets[t];
  for (int i = 0; i < 4; ++i)
    if (q[i] == p) return i;
  return -1;
}

bool TetComplex::start_around(Index t, Index a, Index b, EdgeRing& out, Index& u,
                              Index& v) const {
  out.a = a;
  out.b = b;
  out.tets.clear();
  out.ring.clear();
  const int ia = corner_of(t, a), ib = corner_of(t, b);
  if (ia < 0 || ib < 0 || ia == ib) return false;
  int rest[2], n = 0;
  for (int i = 0; i < 4; ++i)
    if (i != ia && i != ib) rest[n++] = i;
  if (permutation_sign(ia, ib, rest[0], rest[1]) < 0) std::swap(rest[0], rest[1]);
  u = m_->tets[t][rest[0]];
  v = m_->tets[t][rest[1]];
  return true;
}

Index TetComplex::other_corner(Index t, Index a, Index b, Index c) const {
  for (Index p : m_->tets[t])
    if (p != a && p != b && p != c) return p;
  return kInvalidIndex;
}

bool TetComplex::edge_ring(Index t, Index a, Index b, int max_tets, EdgeRing& out) const {
  // Invariant: cur = (a, b, u, v) up to an even permutation.
  Index u, v, cur = t;
  if (!start_around(t, a, b, out, u, v)) return false;
  out.ring.push_back(u);
  out.tets.push_back(t);
  while (true) {
    const Index next = adjacent_[cur][corner_of(cur, u)];  // across face (a, b, v)
    if (next == kInvalidIndex) return false;
    if (next == t) break;
    if (static_cast<int>(out.tets.size()) >= max_tets) return false;
    out.ring.push_back(v);
    out.tets.push_back(next);
    u = std::exchange(v, other_corner(next, a, b, v));
    cur = next;
  }
  return true;
}

bool TetComplex::edge_fan(Index t, Index a, Index b, int max_tets, EdgeRing& out) const {
  // Back to the first tet of the fan: cur = (a, b, u, v) up to an even permutation; the tet
  // before it is across face (a, b, u).
  Index u, v, cur = t;
  if (!start_around(t, a, b, out, u, v)) return false;
  for (int steps = 0;; ++steps) {
    const Index prev = adjacent_[cur][corner_of(cur, v)];
    if (prev == kInvalidIndex) break;
    if (prev == t || steps >= max_tets) return false;  // closed: an interior edge
    v = std::exchange(u, other_corner(prev, a, b, u));
    cur = prev;
  }
  out.ring.push_back(u);
  while (true) {
    if (static_cast<int>(out.tets.size()) >= max_tets) return false;
    out.tets.push_back(cur);
    out.ring.push_back(v);
    const Index next = adjacent_[cur][corner_of(cur, u)];  // across face (a, b, v)
    if (next == kInvalidIndex) return true;
    u = std::exchange(v, other_corner(next, a, b, v));
    cur = next;
  }
}

void TetComplex::ball(Index p, std::vector<Index>& out) const {
  out.clear();
  const Index start = point_tet_[p];
  if (start == kInvalidIndex) return;
  out.push_back(start);
  // Breadth first through the faces at p. A ball has a few dozen tets: a linear membership test
  // is cheaper than any per-tet mark.
  for (std::size_t i = 0; i < out.size(); ++i) {
    const Index t = out[i];
    const int own = corner_of(t, p);
    for (int c = 0; c < 4; ++c) {
      const Index s = adjacent_[t][c];
      if (c != own && s != kInvalidIndex && std::find(out.begin(), out.end(), s) == out.end())
        out.push_back(s);
    }
  }
}

Index TetComplex::new_slot() {
  if (!free_.empty()) {
    const Index t = free_.back();
    free_.pop_back();
    return t;
  }
  m_->tets.push_back({kInvalidIndex, kInvalidIndex, kInvalidIndex, kInvalidIndex});
  m_->tet_tags.push_back(0);
  adjacent_.push_back({kInvalidIndex, kInvalidIndex, kInvalidIndex, kInvalidIndex});
  return static_cast<Index>(m_->tets.size()) - 1;
}

bool TetComplex::replace(absl::Span<const Index> old, absl::Span<const Tet> fresh,
                         std::vector<Index>& created, bool boundary_may_change,
                         Index dropped) {
  constexpr int kNewBoundary = std::numeric_limits<int>::min();
  // The cavity's outside faces, oriented outward, each with the tet beyond it.
  struct Outer {
    Triangle face;
    Index beyond;
    bool used;
  };
  std::vector<Outer> outer;
  outer.reserve(4 * old.size());
  for (Index o : old)
    for (int i = 0; i < 4; ++i)
      if (std::find(old.begin(), old.end(), adjacent_[o][i]) == old.end())
        outer.push_back({canonical_rotation(tet_face(m_->tets[o], i)), adjacent_[o][i], false});
  std::vector<Index> unused;  // points of old that no fresh tet uses
  for (Index o : old)
    for (Index p : m_->tets[o]) {
      bool used = false;
      for (const Tet& f : fresh) used = used || has_corner(f, p);
      if (used || std::find(unused.begin(), unused.end(), p) != unused.end()) continue;
      if (!boundary_may_change && p != dropped) return false;
      unused.push_back(p);
    }
  if (dropped != kInvalidIndex && std::find(unused.begin(), unused.end(), dropped) == unused.end())
    return false;
  // link[4 f + i]: the fresh face (4 g + j) glued to face i of fresh[f], -(k + 1) for the
  // outside face outer[k], or kNewBoundary for a new boundary face.
  std::vector<int> link(4 * fresh.size(), 0);
  for (std::size_t f = 0; f < fresh.size(); ++f) {
    for (int i = 0; i < 4; ++i) {
      const Triangle face = canonical_rotation(tet_face(fresh[f], i));
      const Triangle back = canonical_rotation(reversed(face));
      int found = -1;
      for (std::size_t k = 0; k < outer.size() && found < 0; ++k)
        if (!outer[k].used && outer[k].face == face) {
          outer[k].used = true;
          link[4 * f + i] = -static_cast<int>(k) - 1;
          found = 0;
        }
      for (std::size_t g = 0; g < fresh.size() && found < 0; ++g)
        for (int j = 0; j < 4 && found < 0; ++j)
          if (g != f && canonical_rotation(tet_face(fresh[g], j)) == back) {
            link[4 * f + i] = static_cast<int>(4 * g + j);
            found = 0;
          }
      if (found < 0 && !boundary_may_change) return false;
      if (found < 0) link[4 * f + i] = kNewBoundary;
    }
  }
  for (const Outer& o : outer)
    if (!o.used && !boundary_may_change) return false;
  for (std::size_t e = 0; e < link.size(); ++e)
    if (link[e] >= 0 && link[link[e]] != static_cast<int>(e)) return false;

  for (Index o : old) {
    m_->tets[o][0] = kInvalidIndex;
    free_.push_back(o);
  }
  const std::size_t first = created.size();
  for (const Tet& f : fresh) {
    const Index t = new_slot();
    m_->tets[t] = f;
    m_->tet_tags[t] = 0;
    for (Index p : f) point_tet_[p] = t;
    created.push_back(t);
  }
  // Left out: the tets beyond lose their neighbour there, and a point no fresh tet uses is
  // found again in a tet beyond (or in none).
  for (const Outer& o : outer) {
    if (o.used || o.beyond == kInvalidIndex) continue;
    for (int j = 0; j < 4; ++j) {
      const Index p = m_->tets[o.beyond][j];
      if (p != o.face[0] && p != o.face[1] && p != o.face[2])
        adjacent_[o.beyond][j] = kInvalidIndex;
    }
  }
  if (dropped != kInvalidIndex) dropped_.push_back(dropped);
  for (Index p : unused) {
    point_tet_[p] = kInvalidIndex;
    for (const Outer& o : outer)
      if (o.beyond != kInvalidIndex && has_corner(m_->tets[o.beyond], p)) point_tet_[p] = o.beyond;
  }
  for (std::size_t f = 0; f < fresh.size(); ++f) {
    const Index t = created[first + f];
    for (int i = 0; i < 4; ++i) {
      const int l = link[4 * f + i];
      if (l == kNewBoundary) {
        adjacent_[t][i] = kInvalidIndex;
        continue;
      }
      if (l >= 0) {
        adjacent_[t][i] = created[first + l / 4];
        continue;
      }
      const Outer& o = outer[-l - 1];
      adjacent_[t][i] = o.beyond;
      if (o.beyond == kInvalidIndex) continue;
      for (int j = 0; j < 4; ++j) {
        const Index p = m_->tets[o.beyond][j];
        if (p != o.face[0] && p != o.face[1] && p != o.face[2]) adjacent_[o.beyond][j] = t;
      }
    }
  }
  return true;
}

Index TetComplex::add_point(const Point& x) {
  m_->points.push_back(x);
  point_tet_.push_back(kInvalidIndex);
  return static_cast<Index>(m_->points.size()) - 1;
}

void TetComplex::drop_last_point() {
  m_->points.pop_back();
  point_tet_.pop_back();
}

void TetComplex::compact() {
  std::size_t n = 0;
  for (std::size_t t = 0; t < m_->tets.size(); ++t) {
    if (m_->tets[t][0] == kInvalidIndex) continue;
    m_->tets[n] = m_->tets[t];
    m_->tet_tags[n] = m_->tet_tags[t];
    ++n;
  }
  m_->tets.resize(n);
  m_->tet_tags.resize(n);
  if (!dropped_.empty()) {
    std::vector<Index> renumbered(m_->points.size(), 0);
    for (Index p : dropped_) renumbered[p] = kInvalidIndex;
    Index kept = 0;
    for (std::size_t p = 0; p < m_->points.size(); ++p) {
      if (renumbered[p] == kInvalidIndex) continue;
      renumbered[p] = kept;
      m_->points[kept++] = m_->points[p];
    }
    m_->points.resize(kept);
    for (Tet& k : m_->tets)
      for (Index& p : k) p = renumbered[p];
  }
  adjacent_.clear();
  point_tet_.clear();
  free_.clear();
  dropped_.clear();
}

}  // namespace afmesh
