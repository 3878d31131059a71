#include "core/surface/flip_edges.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <optional>

#include "core/front/front_bins.h"
#include "core/geometry/intersect.h"
#include "core/geometry/predicates.h"
#include "core/geometry/vec.h"
#include "core/quality/measures.h"
#include "core/quality/mesh_topology.h"
#include "core/spatial/box.h"

namespace afmesh {
namespace {

std::pair<Index, Index> edge_key(Index a, Index b) { return {std::min(a, b), std::max(a, b)}; }

double min_angle(const std::vector<Point>& p, Index a, Index b, Index c) {
  return triangle_min_angle_deg(p[a], p[b], p[c]);
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

// Points the slot of `neighbour` that lies across edge {a, b} from `from` at `to` instead (the
// triangle on that side of the edge after a flip).
void repoint(EdgeNeighbours& neighbours, const std::vector<Triangle>& triangles, Index neighbour,
             Index a, Index b, Index from, Index to) {
  if (neighbour == kInvalidIndex) return;
  const Triangle& t = triangles[neighbour];
  for (int s = 0; s < 3; ++s) {
    const Index u = t[s], v = t[(s + 1) % 3];
    if (neighbours.across[neighbour][s] == from && ((u == a && v == b) || (u == b && v == a))) {
      neighbours.across[neighbour][s] = to;
      return;
    }
  }
}

// The flip of the diagonal (a, b) of t1 = (a, b, c) (slot k) and t2 = (b, a, d) (slot j) into
// t1 = (a, d, c) and t2 = (d, b, c), with the adjacency kept as a rebuild would give it: the four
// outer edges keep their neighbours and orientation flags, moved to their new slots.
void flip(std::vector<Triangle>& triangles, EdgeNeighbours& neighbours, Index t1, int k,
          Index t2, int j) {
  const int k1 = (k + 1) % 3, k2 = (k + 2) % 3, j1 = (j + 1) % 3, j2 = (j + 2) % 3;
  const Index a = triangles[t1][k], b = triangles[t1][k1], c = triangles[t1][k2];
  const Index n_bc = neighbours.across[t1][k1], n_ca = neighbours.across[t1][k2];
  const Index n_ad = neighbours.across[t2][j1], n_db = neighbours.across[t2][j2];
  const bool w_bc = neighbours.same_way[t1][k1], w_ca = neighbours.same_way[t1][k2];
  const bool w_ad = neighbours.same_way[t2][j1], w_db = neighbours.same_way[t2][j2];
  const Index d = triangles[t2][j2];
  triangles[t1] = {a, d, c};
  triangles[t2] = {d, b, c};
  neighbours.across[t1] = {n_ad, t2, n_ca};
  neighbours.same_way[t1] = {w_ad, false, w_ca};
  neighbours.across[t2] = {n_db, n_bc, t1};
  neighbours.same_way[t2] = {w_db, w_bc, false};
  repoint(neighbours, triangles, n_ad, a, d, t2, t1);
  repoint(neighbours, triangles, n_bc, b, c, t1, t2);
}

}  // namespace

absl::StatusOr<std::int64_t> flip_edges(const std::vector<Point>& points,
                                        std::vector<Triangle>& triangles,
                                        const std::vector<Index>& patch,
                                        const absl::flat_hash_set<std::pair<Index, Index>>& fixed,
                                        const FlipParams& params, Progress& progress,
                                        std::vector<bool>* may_gain) {
  CancelCheck cancel(progress);
  const double min_cosine = std::cos(params.max_normal_turn_deg * std::numbers::pi / 180.0);
  // Built once, then kept by each flip (flip()).
  EdgeNeighbours neighbours = triangle_edge_neighbours(triangles, &cancel);
  if (cancel.stopped()) return absl::CancelledError("edge flips: cancelled");
  // The mesh's edges, each inserted from one triangle where it has a neighbour: half the
  // table's probes, which miss the cache on large meshes.
  absl::flat_hash_set<std::pair<Index, Index>> edges;
  edges.reserve(3 * triangles.size() / 2 + 3);
  for (Index t = 0; t < static_cast<Index>(triangles.size()); ++t) {
    if (cancel.due()) return absl::CancelledError("edge flips: cancelled");
    for (int k = 0; k < 3; ++k) {
      const Index n = neighbours.across[t][k];
      if (n == kInvalidIndex || t < n)
        edges.insert(edge_key(triangles[t][k], triangles[t][(k + 1) % 3]));
    }
  }
  // Not in the paper: a flip must not make the surface cross itself. The quadrilateral of a
  // flip is not flat where the surface curves, and its new diagonal passes on the other side of
  // the old one: across a wall thinner than that the new triangles cross the far side
  // (gmsh_t13_data with no curvature bound, a plate 2 thick meshed at 9.8, once its lines were
  // split at the smaller size of their two sides: a quadrilateral that turned by 44°). With
  // params.keep_uncrossed, each new triangle is tested (exactly) against the triangles whose
  // boxes meet its own, found through bins of the triangles' boxes (an octree: sizes span orders
  // of magnitude), made at the first flip and kept as the flips change the triangles.
  std::optional<FrontBins> boxes;
  const auto make_boxes = [&] {
    Box domain = empty_box();
    for (const Point& x : points) enclose(domain, x);
    // An octree has no cell size of its own (FrontBins only reports the one given).
    boxes.emplace(domain, 1.0, FrontBins::Adaptive{});
    for (Index t = 0; t < static_cast<Index>(triangles.size()); ++t)
      boxes->insert_item(t, triangle_box(points, triangles[t]));
  };
  // Whether triangle `t` (a flip's new triangle) meets a triangle other than t1 and t2 (the
  // flip's pair) beyond the corners they share.
  const auto crosses_others = [&](const Triangle& t, Index t1, Index t2) {
    if (!boxes) make_boxes();
    return boxes->find_item_near(triangle_box(points, t), [&](Index u) {
      return u != t1 && u != t2 && triangles_intersect_improperly(points, t, triangles[u]);
    });
  };
  std::int64_t flips = 0;
  // The smallest angle of each triangle, computed when first needed (negative: not yet) and kept
  // until a flip changes the triangle: each triangle is looked at from its three edges, and the
  // angles (three atan2 each) are most of the cost.
  std::vector<double> smallest_angle(triangles.size(), -1.0);
  const auto angle_of = [&](Index t) {
    if (smallest_angle[t] < 0)
      smallest_angle[t] = min_angle(points, triangles[t][0], triangles[t][1], triangles[t][2]);
    return smallest_angle[t];
  };
  // After the first pass only the edges of triangles a flip changed can gain from a flip: the
  // others' quadrilaterals are as the pass before found them.
  std::vector<bool> changed =
      may_gain != nullptr ? *may_gain : std::vector<bool>(triangles.size(), true);
  for (int pass = 0; pass < params.max_passes; ++pass) {
    if (cancel.look()) return absl::CancelledError("edge flips: cancelled");
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
        int j = 0;  // t2's slot of edge (b, a); its third corner d follows
        while (j < 3 && !(triangles[t2][j] == b && triangles[t2][(j + 1) % 3] == a)) ++j;
        if (j == 3) continue;
        const Index d = triangles[t2][(j + 2) % 3];
        if (d == c) continue;
        // The smaller minimum angle must rise by min_gain_deg: the second new triangle is only
        // measured when the first passes.
        const double wanted = std::min(angle_of(t1), angle_of(t2)) + params.min_gain_deg;
        const double first = min_angle(points, a, d, c);
        if (!(first > wanted)) continue;
        const double second = min_angle(points, d, b, c);
        if (!(std::min(first, second) > wanted)) continue;
        // The new diagonal must not be an edge already (asked after the angles: most candidates
        // fail those, and the table's probes miss the cache).
        if (edges.contains(edge_key(c, d))) continue;
        Point n = add(unit_normal(points[a], points[b], points[c]),
                      unit_normal(points[b], points[a], points[d]));
        if (!(norm(n) > 0)) continue;
        n = scale(n, 1.0 / norm(n));
        if (orient_in_plane(points, n, a, d, c) <= 0 || orient_in_plane(points, n, d, b, c) <= 0)
          continue;
        if (dot(unit_normal(points[a], points[d], points[c]), n) < min_cosine ||
            dot(unit_normal(points[d], points[b], points[c]), n) < min_cosine)
          continue;
        if (params.keep_uncrossed &&
            (crosses_others({a, d, c}, t1, t2) || crosses_others({d, b, c}, t1, t2)))
          continue;
        if (boxes) {
          boxes->erase_item(t1, triangle_box(points, triangles[t1]));
          boxes->erase_item(t2, triangle_box(points, triangles[t2]));
        }
        flip(triangles, neighbours, t1, k, t2, j);
        if (boxes) {
          boxes->insert_item(t1, triangle_box(points, triangles[t1]));
          boxes->insert_item(t2, triangle_box(points, triangles[t2]));
        }
        smallest_angle[t1] = first;  // (a, d, c)
        smallest_angle[t2] = second;  // (d, b, c)
        edges.erase(edge_key(a, b));
        edges.insert(edge_key(c, d));
        touched[t1] = touched[t2] = true;
        ++flipped;
      }
    }
    flips += flipped;
    if (flipped == 0) {
      // Only a caller that reads the flags back (may_gain) needs them cleared.
      if (may_gain != nullptr) std::fill(changed.begin(), changed.end(), false);
      break;
    }
    changed.swap(touched);
  }
  if (may_gain != nullptr) *may_gain = std::move(changed);
  return flips;
}

}  // namespace afmesh
