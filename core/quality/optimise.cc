#include "core/quality/optimise.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <utility>
#include <vector>

#include "core/geometry/predicates.h"
#include "core/geometry/vec.h"

namespace afmesh {

double tet_min_sine(const Point& a, const Point& b, const Point& c, const Point& d) {
  // n[i]: twice the area of the face opposite corner i. The sine of the dihedral angle at edge
  // (i, j), between the faces opposite k and l, is det · |e_ij| / (n[k] n[l]).
  const double n[4] = {norm(cross(sub(c, b), sub(d, b))), norm(cross(sub(c, a), sub(d, a))),
                       norm(cross(sub(b, a), sub(d, a))), norm(cross(sub(b, a), sub(c, a)))};
  const double det = dot(cross(sub(b, a), sub(c, a)), sub(d, a));
  if (!(n[0] > 0 && n[1] > 0 && n[2] > 0 && n[3] > 0)) return 0.0;
  const double r[6] = {distance(a, b) / (n[2] * n[3]), distance(a, c) / (n[1] * n[3]),
                       distance(a, d) / (n[1] * n[2]), distance(b, c) / (n[0] * n[3]),
                       distance(b, d) / (n[0] * n[2]), distance(c, d) / (n[0] * n[1])};
  const auto [lo, hi] = std::minmax_element(r, r + 6);
  return det >= 0 ? det * *lo : det * *hi;
}

namespace {

// Local operations on a tet mesh with its point-to-tet incidence kept up to date.
class TetOptimiser {
 public:
  TetOptimiser(Mesh& mesh, Index fixed_points) : m_(mesh), fixed_(fixed_points) {
    ball_.resize(m_.points.size());
    for (Index t = 0; t < static_cast<Index>(m_.tets.size()); ++t)
      for (Index p : m_.tets[t]) ball_[p].push_back(t);
  }

  double quality(Index t) const {
    const Tet& k = m_.tets[t];
    return tet_min_sine(m_.points[k[0]], m_.points[k[1]], m_.points[k[2]], m_.points[k[3]]);
  }
  bool alive(Index t) const { return m_.tets[t][0] != kInvalidIndex; }

  // 3-2 flip of edge (a, b): see optimise.h.
  bool remove_edge(Index a, Index b);
  // 2-3 flip of the face of tet t opposite its corner k.
  bool flip_face(Index t, int k);
  // Moves point v toward the centroid of its neighbours when that raises its ball's worst tet.
  bool smooth(Index v);

  // Drops deleted tets.
  void compact();

  OptimiseStats stats;

 private:
  Index add_tet(const Tet& tet);
  void remove_tet(Index t);
  double worst(const std::vector<Index>& tets) const {
    double q = 2.0;
    for (Index t : tets) q = std::min(q, quality(t));
    return q;
  }
  double worst_of(std::initializer_list<Tet> tets) const {
    double q = 2.0;
    for (const Tet& k : tets)
      q = std::min(q, tet_min_sine(m_.points[k[0]], m_.points[k[1]], m_.points[k[2]],
                                   m_.points[k[3]]));
    return q;
  }
  bool positive(const Tet& k) const {
    return orient3d(m_.points[k[0]], m_.points[k[1]], m_.points[k[2]], m_.points[k[3]]) > 0;
  }

  Mesh& m_;
  Index fixed_;
  std::vector<std::vector<Index>> ball_;  // per point: the live tets using it
  std::vector<Index> free_;               // deleted tet slots, reused by add_tet
  std::vector<Index> scratch_;
};

Index TetOptimiser::add_tet(const Tet& tet) {
  Index t;
  if (!free_.empty()) {
    t = free_.back();
    free_.pop_back();
    m_.tets[t] = tet;
    m_.tet_tags[t] = 0;
  } else {
    t = static_cast<Index>(m_.tets.size());
    m_.tets.push_back(tet);
    m_.tet_tags.push_back(0);
  }
  for (Index p : tet) ball_[p].push_back(t);
  return t;
}

void TetOptimiser::remove_tet(Index t) {
  for (Index p : m_.tets[t]) {
    std::vector<Index>& b = ball_[p];
    *std::find(b.begin(), b.end(), t) = b.back();
    b.pop_back();
  }
  m_.tets[t][0] = kInvalidIndex;
  free_.push_back(t);
}

bool TetOptimiser::remove_edge(Index a, Index b) {
  std::vector<Index>& around = scratch_;
  around.clear();
  for (Index t : ball_[a]) {
    const Tet& k = m_.tets[t];
    if (k[0] == b || k[1] == b || k[2] == b || k[3] == b) around.push_back(t);
  }
  if (around.size() != 3) return false;
  // The ring: the three other corners, each in exactly two of the tets (a closed ring, so the
  // edge is interior).
  Index ring[6];
  int n = 0;
  for (Index t : around)
    for (Index p : m_.tets[t])
      if (p != a && p != b) ring[n++] = p;
  std::sort(ring, ring + 6);
  if (!(ring[0] == ring[1] && ring[2] == ring[3] && ring[4] == ring[5] && ring[1] != ring[2] &&
        ring[3] != ring[4]))
    return false;
  Index p = ring[0], q = ring[2], r = ring[4];
  const int side_a = orient3d(m_.points[p], m_.points[q], m_.points[r], m_.points[a]);
  if (side_a == 0) return false;
  if (side_a < 0) std::swap(p, q);
  const Tet t1{p, q, r, a}, t2{q, p, r, b};
  if (!positive(t2)) return false;  // the triangle pqr must separate a from b
  if (worst_of({t1, t2}) <= worst(around)) return false;
  const std::vector<Index> old = around;
  for (Index t : old) remove_tet(t);
  add_tet(t1);
  add_tet(t2);
  ++stats.flips_32;
  return true;
}

bool TetOptimiser::flip_face(Index t, int k) {
  const Tet tet = m_.tets[t];
  const Index a = tet[k];
  Index face[3];
  for (int i = 0, n = 0; i < 4; ++i)
    if (i != k) face[n++] = tet[i];
  Index u = kInvalidIndex;  // the tet on the other side of the face
  for (Index s : ball_[face[0]]) {
    if (s == t) continue;
    const Tet& w = m_.tets[s];
    int shared = 0;
    for (Index p : w) shared += (p == face[1] || p == face[2]);
    if (shared == 2) {
      u = s;
      break;
    }
  }
  if (u == kInvalidIndex) return false;  // a boundary face stays
  Index b = kInvalidIndex;
  for (Index p : m_.tets[u])
    if (p != face[0] && p != face[1] && p != face[2]) b = p;
  Index p = face[0], q = face[1], r = face[2];
  if (orient3d(m_.points[p], m_.points[q], m_.points[r], m_.points[a]) < 0) std::swap(p, q);
  // Around the new edge ab, one tet per edge (x, y) of the face: (y, x, a, b).
  const Tet n1{q, p, a, b}, n2{r, q, a, b}, n3{p, r, a, b};
  if (!positive(n1) || !positive(n2) || !positive(n3)) return false;
  if (worst_of({n1, n2, n3}) <= std::min(quality(t), quality(u))) return false;
  remove_tet(t);
  remove_tet(u);
  add_tet(n1);
  add_tet(n2);
  add_tet(n3);
  ++stats.flips_23;
  return true;
}

bool TetOptimiser::smooth(Index v) {
  if (v < fixed_ || ball_[v].empty()) return false;
  Point centroid{0, 0, 0};
  int count = 0;
  for (Index t : ball_[v])
    for (Index p : m_.tets[t])
      if (p != v) centroid = add(centroid, m_.points[p]), ++count;
  centroid = scale(centroid, 1.0 / count);
  const Point old = m_.points[v];
  const double before = worst(ball_[v]);
  for (double step : {1.0, 0.5, 0.25}) {
    m_.points[v] = lerp(old, centroid, step);
    bool valid = true;
    for (Index t : ball_[v]) valid = valid && positive(m_.tets[t]);
    if (valid && worst(ball_[v]) > before) {
      ++stats.points_moved;
      return true;
    }
  }
  m_.points[v] = old;
  return false;
}

void TetOptimiser::compact() {
  std::size_t n = 0;
  for (std::size_t t = 0; t < m_.tets.size(); ++t) {
    if (m_.tets[t][0] == kInvalidIndex) continue;
    m_.tets[n] = m_.tets[t];
    m_.tet_tags[n] = m_.tet_tags[t];
    ++n;
  }
  m_.tets.resize(n);
  m_.tet_tags.resize(n);
}

// One pass over the tets below the threshold, worst first.
absl::Status improve_bad_tets(TetOptimiser& opt, const Mesh& m, double threshold,
                              Progress& progress) {
  std::vector<std::pair<double, Index>> bad;
  for (Index t = 0; t < static_cast<Index>(m.tets.size()); ++t) {
    if (!opt.alive(t)) continue;
    const double q = opt.quality(t);
    if (q < threshold) bad.emplace_back(q, t);
  }
  std::sort(bad.begin(), bad.end());
  std::int64_t visited = 0;
  for (const auto& [q0, t] : bad) {
    if ((++visited & 1023) == 0 && progress.cancelled())
      return absl::CancelledError("mesh optimisation cancelled");
    if (!opt.alive(t) || opt.quality(t) >= threshold) continue;
    const Tet k = m.tets[t];
    bool done = false;
    static constexpr int kEdges[6][2] = {{0, 1}, {0, 2}, {0, 3}, {1, 2}, {1, 3}, {2, 3}};
    for (const auto& e : kEdges)
      if (!done) done = opt.remove_edge(k[e[0]], k[e[1]]);
    for (int f = 0; f < 4 && !done; ++f) done = opt.flip_face(t, f);
    for (int i = 0; i < 4 && !done; ++i) done = opt.smooth(k[i]);
  }
  return absl::OkStatus();
}

}  // namespace

absl::StatusOr<OptimiseStats> optimise_tets(Mesh& mesh, Index fixed_points,
                                            const OptimiseParams& params, Progress& progress) {
  mesh.tet_tags.resize(mesh.tets.size(), 0);
  TetOptimiser opt(mesh, fixed_points);
  const double threshold = std::sin(params.target_min_dihedral_deg * std::numbers::pi / 180.0);
  absl::Status status;
  for (int sweep = 0; sweep < params.smoothing_sweeps && status.ok(); ++sweep) {
    for (Index v = fixed_points; v < static_cast<Index>(mesh.points.size()); ++v) {
      if ((v & 4095) == 0 && progress.cancelled()) {
        status = absl::CancelledError("mesh optimisation cancelled");
        break;
      }
      opt.smooth(v);
    }
  }
  for (int pass = 0; pass < params.passes && status.ok(); ++pass)
    status = improve_bad_tets(opt, mesh, threshold, progress);
  opt.compact();
  if (!status.ok()) return status;
  return opt.stats;
}

}  // namespace afmesh
