// Edge removal, 2-3 flips and edge contraction: the topological steps of the optimiser
// (optimise_steps.h).
#include <algorithm>

#include "core/geometry/predicates.h"
#include "core/quality/mesh_topology.h"
#include "core/quality/optimise_steps.h"
#include "core/quality/ring_triangulation.h"

namespace afmesh {
namespace {

constexpr double kUnusable = -std::numeric_limits<double>::infinity();

// The score of tet k by `criterion`, or kUnusable when it is not positive by exact orient3d.
double positive_score(const std::vector<Point>& p, const Tet& k, TetCriterion criterion) {
  if (orient3d(p[k[0]], p[k[1]], p[k[2]], p[k[3]]) <= 0) return kUnusable;
  return criterion(k);
}

// The worst of the tets `tets` of c by tet_min_sine.
double worst_sine(const TetComplex& c, absl::Span<const Index> tets) {
  double worst = std::numeric_limits<double>::infinity();
  for (Index s : tets) worst = std::min(worst, tet_min_sine(c.mesh().points, c.tet(s)));
  return worst;
}

}  // namespace

bool propose_edge_removal(const TetComplex& c, const EdgeRing& ring, TetCriterion criterion,
                          double floor, TopologyChange& out) {
  const Index a = ring.a, b = ring.b;
  const std::vector<Point>& p = c.mesh().points;
  const std::vector<Index>& r = ring.ring;
  // Triangle (r_i, r_j, r_k), i < j < k, runs counter-clockwise seen from b (the ring turns
  // positively around the directed edge a -> b), so it makes the positive tets (r_i, r_j, r_k, b)
  // and (r_j, r_i, r_k, a).
  const RingTriangulation best =
      best_ring_triangulation(static_cast<int>(r.size()), [&](int i, int j, int k) {
        const double qb = positive_score(p, {r[i], r[j], r[k], b}, criterion);
        if (!(qb > floor)) return kUnusable;
        return std::min(qb, positive_score(p, {r[j], r[i], r[k], a}, criterion));
      });
  if (!(best.quality > floor)) return false;
  out.old = ring.tets;
  out.fresh.clear();
  for (const auto& [i, j, k] : best.triangles) {
    out.fresh.push_back({r[i], r[j], r[k], b});
    out.fresh.push_back({r[j], r[i], r[k], a});
  }
  out.quality = best.quality;
  return true;
}

bool propose_boundary_edge_removal(const TetComplex& c, const EdgeRing& fan,
                                   TetCriterion criterion, TopologyChange& out) {
  const Index a = fan.a, b = fan.b;
  const std::vector<Index>& r = fan.ring;
  const int n = static_cast<int>(r.size());
  if (n < 3 || n > kMaxRingSize) return false;
  const std::vector<Point>& p = c.mesh().points;
  const Point& first = p[r.front()];
  const Point& last = p[r.back()];
  // The boundary faces (a, b, r_0) and (a, b, r_n) in one plane, r_0 and r_n on either side of
  // the line ab in it (seen against r_1, off the plane).
  if (orient3d(p[a], p[b], first, last) != 0) return false;
  const int s0 = orient3d(p[a], p[b], first, p[r[1]]);
  const int sn = orient3d(p[a], p[b], last, p[r[1]]);
  if (s0 == 0 || sn == 0 || s0 == sn) return false;
  // The fan's polygon closed by the side (r_n, r_0), the new diagonal.
  return propose_edge_removal(c, fan, criterion, kUnusable, out);
}

bool propose_face_removal(const TetComplex& c, Index t, int corner, TetCriterion criterion,
                          double floor, TopologyChange& out) {
  const Index u = c.neighbour(t, corner);
  if (u == kInvalidIndex) return false;  // a boundary face stays
  const std::vector<Point>& p = c.mesh().points;
  const Index a = c.tet(t)[corner];
  const Triangle f = tet_face(c.tet(t), corner);  // outward from t: a lies below it
  Index b = kInvalidIndex;
  for (Index x : c.tet(u))
    if (x != f[0] && x != f[1] && x != f[2]) b = x;
  // Around the new edge a -> b, one tet per edge (x, y) of the face as seen from a.
  const Tet fresh[3] = {{f[0], f[1], a, b}, {f[1], f[2], a, b}, {f[2], f[0], a, b}};
  double q = std::numeric_limits<double>::infinity();
  for (const Tet& k : fresh) q = std::min(q, positive_score(p, k, criterion));
  if (!(q > floor)) return false;
  out.old = {t, u};
  out.fresh.assign(fresh, fresh + 3);
  out.quality = q;
  return true;
}

bool propose_edge_removal(const TetComplex& c, Index t, Index a, Index b, int max_ring,
                          EdgeRing& ring, TopologyChange& out) {
  if (!c.edge_ring(t, a, b, std::min(max_ring, kMaxRingSize), ring)) return false;
  const std::vector<Point>& p = c.mesh().points;
  return propose_edge_removal(c, ring, [&](const Tet& k) { return tet_min_sine(p, k); },
                              worst_sine(c, ring.tets), out);
}

bool propose_face_removal(const TetComplex& c, Index t, int corner, TopologyChange& out) {
  const Index u = c.neighbour(t, corner);
  if (u == kInvalidIndex) return false;
  const std::vector<Point>& p = c.mesh().points;
  const Index pair[2] = {t, u};
  return propose_face_removal(c, t, corner, [&](const Tet& k) { return tet_min_sine(p, k); },
                              worst_sine(c, pair), out);
}

bool propose_edge_contraction(const TetComplex& c, Index t, Index a, Index b, Index fixed_points,
                              std::vector<Index>& ball, TopologyChange& out) {
  if (b < fixed_points || c.corner_of(t, a) < 0 || c.corner_of(t, b) < 0) return false;
  c.ball(b, ball);
  const std::vector<Point>& p = c.mesh().points;
  out.fresh.clear();
  double q = std::numeric_limits<double>::infinity();
  for (Index s : ball) {
    Tet k = c.tet(s);
    if (has_corner(k, a)) continue;  // around the edge: it vanishes
    for (Index& x : k)
      if (x == b) x = a;
    q = std::min(q, positive_score(p, k, [&](const Tet& m) { return tet_min_sine(p, m); }));
    if (q == kUnusable) return false;
    out.fresh.push_back(k);
  }
  if (!(q > worst_sine(c, ball))) return false;
  out.old = ball;
  out.quality = q;
  return true;
}

}  // namespace afmesh
