// Edge removal and 2-3 flips: the topological steps of the optimiser (optimise_steps.h).
#include <algorithm>

#include "core/geometry/predicates.h"
#include "core/quality/mesh_topology.h"
#include "core/quality/optimise_steps.h"
#include "core/quality/ring_triangulation.h"

namespace afmesh {
namespace {

constexpr double kUnusable = -std::numeric_limits<double>::infinity();

// The quality of tet k, or kUnusable when it is not positive by exact orient3d.
double positive_quality(const std::vector<Point>& p, const Tet& k) {
  if (orient3d(p[k[0]], p[k[1]], p[k[2]], p[k[3]]) <= 0) return kUnusable;
  return tet_min_sine(p, k);
}

}  // namespace

bool propose_edge_removal(const TetComplex& c, Index t, Index a, Index b, int max_ring,
                          EdgeRing& ring, TopologyChange& out) {
  if (!c.edge_ring(t, a, b, std::min(max_ring, kMaxRingSize), ring)) return false;
  const std::vector<Point>& p = c.mesh().points;
  double worst = std::numeric_limits<double>::infinity();
  for (Index s : ring.tets) worst = std::min(worst, tet_min_sine(p, c.tet(s)));
  const std::vector<Index>& r = ring.ring;
  // Triangle (r_i, r_j, r_k), i < j < k, runs counter-clockwise seen from b (the ring turns
  // positively around the directed edge a -> b), so it makes the positive tets (r_i, r_j, r_k, b)
  // and (r_j, r_i, r_k, a).
  const RingTriangulation best =
      best_ring_triangulation(static_cast<int>(r.size()), [&](int i, int j, int k) {
        const double qb = positive_quality(p, {r[i], r[j], r[k], b});
        if (!(qb > worst)) return kUnusable;
        return std::min(qb, positive_quality(p, {r[j], r[i], r[k], a}));
      });
  if (!(best.quality > worst)) return false;
  out.old = ring.tets;
  out.fresh.clear();
  for (const auto& [i, j, k] : best.triangles) {
    out.fresh.push_back({r[i], r[j], r[k], b});
    out.fresh.push_back({r[j], r[i], r[k], a});
  }
  out.quality = best.quality;
  return true;
}

bool propose_face_removal(const TetComplex& c, Index t, int corner, TopologyChange& out) {
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
  const double worst = std::min(tet_min_sine(p, c.tet(t)), tet_min_sine(p, c.tet(u)));
  double q = std::numeric_limits<double>::infinity();
  for (const Tet& k : fresh) q = std::min(q, positive_quality(p, k));
  if (!(q > worst)) return false;
  out.old = {t, u};
  out.fresh.assign(fresh, fresh + 3);
  out.quality = q;
  return true;
}

}  // namespace afmesh
