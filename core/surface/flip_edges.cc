#include "core/surface/flip_edges.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>

#include "core/geometry/predicates.h"
#include "core/geometry/vec.h"
#include "core/quality/measures.h"
#include "core/quality/mesh_topology.h"

namespace afmesh {
namespace {

std::pair<Index, Index> edge_key(Index a, Index b) { return {std::min(a, b), std::max(a, b)}; }

Point unit_normal(const std::vector<Point>& p, Index a, Index b, Index c) {
  const Point n = cross(sub(p[b], p[a]), sub(p[c], p[a]));
  const double length = norm(n);
  return length > 0 ? scale(n, 1.0 / length) : n;
}

double min_angle(const std::vector<Point>& p, Index a, Index b, Index c) {
  return triangle_quality(p[a], p[b], p[c]).min_angle_deg;
}

// orient2d of (a, b, c) in the plane with unit normal n.
int orient_in_plane(const std::vector<Point>& p, const Point& n, Index a, Index b, Index c) {
  Point t = sub(p[b], p[a]);
  t = sub(t, scale(n, dot(t, n)));
  const double length = norm(t);
  if (!(length > 0)) return 0;
  t = scale(t, 1.0 / length);
  const Point u = cross(n, t);
  const auto at = [&](Index q) {
    const Point r = sub(p[q], p[a]);
    return std::array<double, 2>{dot(r, t), dot(r, u)};
  };
  const std::array<double, 2> x = at(a), y = at(b), z = at(c);
  return orient2d(x.data(), y.data(), z.data());
}

}  // namespace

absl::StatusOr<std::int64_t> flip_edges(const std::vector<Point>& points,
                                        std::vector<Triangle>& triangles,
                                        const std::vector<Index>& patch,
                                        const absl::flat_hash_set<std::pair<Index, Index>>& fixed,
                                        const FlipParams& params, Progress& progress) {
  CancelCheck cancel(progress);
  const double min_cosine = std::cos(params.max_normal_turn_deg * std::numbers::pi / 180.0);
  absl::flat_hash_set<std::pair<Index, Index>> edges;
  for (const Triangle& t : triangles)
    for (int k = 0; k < 3; ++k) edges.insert(edge_key(t[k], t[(k + 1) % 3]));
  std::int64_t flips = 0;
  // After the first pass only the edges of triangles a flip changed can gain from a flip: the
  // others' quadrilaterals are as the pass before found them.
  std::vector<bool> changed(triangles.size(), true);
  for (int pass = 0; pass < params.max_passes; ++pass) {
    if (cancel.look()) return absl::CancelledError("edge flips: cancelled");
    const EdgeNeighbours neighbours = triangle_edge_neighbours(triangles);
    std::vector<bool> touched(triangles.size(), false);
    std::int64_t flipped = 0;
    for (Index t1 = 0; t1 < static_cast<Index>(triangles.size()); ++t1) {
      if (cancel.due()) return absl::CancelledError("edge flips: cancelled");
      for (int k = 0; k < 3 && !touched[t1]; ++k) {
        const Index t2 = neighbours.across[t1][k];
        if (t2 == kInvalidIndex || t2 < t1 || touched[t2] || neighbours.same_way[t1][k] ||
            patch[t1] != patch[t2] || !(changed[t1] || changed[t2]))
          continue;
        const Index a = triangles[t1][k], b = triangles[t1][(k + 1) % 3],
                    c = triangles[t1][(k + 2) % 3];
        if (fixed.contains(edge_key(a, b))) continue;
        Index d = kInvalidIndex;  // the corner of t2 off edge (b, a)
        for (const Index q : triangles[t2])
          if (q != a && q != b) d = q;
        if (d == kInvalidIndex || d == c || edges.contains(edge_key(c, d))) continue;
        const double before = std::min(min_angle(points, a, b, c), min_angle(points, b, a, d));
        const double after = std::min(min_angle(points, a, d, c), min_angle(points, d, b, c));
        if (!(after > before + params.min_gain_deg)) continue;
        Point n = add(unit_normal(points, a, b, c), unit_normal(points, b, a, d));
        if (!(norm(n) > 0)) continue;
        n = scale(n, 1.0 / norm(n));
        if (orient_in_plane(points, n, a, d, c) <= 0 || orient_in_plane(points, n, d, b, c) <= 0)
          continue;
        if (dot(unit_normal(points, a, d, c), n) < min_cosine ||
            dot(unit_normal(points, d, b, c), n) < min_cosine)
          continue;
        triangles[t1] = {a, d, c};
        triangles[t2] = {d, b, c};
        edges.erase(edge_key(a, b));
        edges.insert(edge_key(c, d));
        touched[t1] = touched[t2] = true;
        ++flipped;
      }
    }
    flips += flipped;
    if (flipped == 0) break;
    changed.swap(touched);
  }
  return flips;
}

}  // namespace afmesh
