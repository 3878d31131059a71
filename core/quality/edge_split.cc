// Edge split by insertion: the step of the optimiser that adds a point (optimise_steps.h).
#include <algorithm>

#include "core/geometry/predicates.h"
#include "core/geometry/vec.h"
#include "core/quality/optimise_steps.h"
#include "core/quality/ring_triangulation.h"

namespace afmesh {
namespace {

// Where z is tried, as fractions of the way from the edge's midpoint to the ring's centroid.
constexpr double kPlacements[] = {0.0, 0.25, 0.5, 0.75};

// The 2n tets of the split of `ring` by point z.
void split_tets(const EdgeRing& ring, Index z, std::vector<Tet>& out) {
  out.clear();
  const std::size_t n = ring.ring.size();
  for (std::size_t i = 0; i < n; ++i) {
    const Index r0 = ring.ring[i], r1 = ring.ring[(i + 1) % n];
    out.push_back({z, ring.b, r0, r1});
    out.push_back({ring.a, z, r0, r1});
  }
}

// Smallest quality of `tets` with point z moved to `x`, or -infinity when one is not positive by
// exact orient3d.
double split_quality(TetComplex& c, Index z, const Point& x, const std::vector<Tet>& tets) {
  c.move_point(z, x);
  const std::vector<Point>& points = c.points();
  double worst = std::numeric_limits<double>::infinity();
  for (const Tet& k : tets) {
    if (orient3d(points[k[0]], points[k[1]], points[k[2]], points[k[3]]) <= 0)
      return -std::numeric_limits<double>::infinity();
    worst = std::min(worst, tet_min_sine(points, k));
  }
  return worst;
}

}  // namespace

bool propose_edge_split(TetComplex& c, Index t, Index a, Index b, int max_ring, EdgeSplit& out) {
  if (!c.edge_ring(t, a, b, std::min(max_ring, kMaxRingSize), out.ring)) return false;
  double worst = std::numeric_limits<double>::infinity();
  for (Index s : out.ring.tets) worst = std::min(worst, tet_min_sine(c.points(), c.tet(s)));
  const Point mid = lerp(c.point(a), c.point(b), 0.5);
  Point centroid{0, 0, 0};
  for (Index r : out.ring.ring) centroid = add(centroid, c.point(r));
  centroid = scale(centroid, 1.0 / static_cast<double>(out.ring.ring.size()));

  const Index z = c.add_point(mid);  // evaluated in place, removed before returning
  std::vector<Tet> tets;
  split_tets(out.ring, z, tets);
  out.quality = worst;
  bool found = false;
  for (double w : kPlacements) {
    const Point x = lerp(mid, centroid, w);
    if (const double q = split_quality(c, z, x, tets); q > out.quality) {
      out.quality = q;
      out.z = x;
      found = true;
    }
  }
  c.drop_last_point();
  return found;
}

bool make_edge_split(TetComplex& c, const EdgeSplit& split, Index fixed_points,
                     SmoothingScratch& scratch, std::vector<Index>& created) {
  const Index z = c.add_point(split.z);
  std::vector<Tet> tets;
  split_tets(split.ring, z, tets);
  if (!c.replace(split.ring.tets, tets, created)) {
    c.drop_last_point();
    return false;
  }
  smooth_point(c, z, fixed_points, /*climb_too=*/true, scratch);
  return true;
}

}  // namespace afmesh
