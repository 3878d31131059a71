#include "core/surface/collapse_edges.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <vector>

#include "core/geometry/vec.h"
#include "core/mesh/simplex_incidence.h"
#include "core/quality/measures.h"

namespace afmesh {
namespace {

double min_angle_of(const std::vector<Point>& p, const Triangle& t) {
  return triangle_min_angle_deg(p[t[0]], p[t[1]], p[t[2]]);
}

// Scratch of one trial, reused across trials.
struct Trial {
  std::vector<Index> fan_a, fan_b;        // the live triangles around the two points
  std::vector<Index> shared, moved;       // fan_a's triangles with b, and those without
  std::vector<Index> neighbours_a, neighbours_b;
};

// Whether merging patch point a into point b keeps the surface a manifold, folds nothing and
// raises the smallest angle of a's fan (collapse_edges.h); fills trial.shared and trial.moved.
bool collapse_is_better(const SurfaceMeshState& s, const SimplexIncidence<3>& incidence, Index a,
                        Index b, double min_cosine, Trial& trial) {
  trial.fan_a.clear();
  trial.fan_b.clear();
  incidence.elements_of(s.triangles, a, trial.fan_a);
  incidence.elements_of(s.triangles, b, trial.fan_b);
  trial.shared.clear();
  trial.moved.clear();
  for (const Index t : trial.fan_a)
    (has_corner(s.triangles[t], b) ? trial.shared : trial.moved).push_back(t);
  if (trial.shared.size() != 2) return false;
  // The link condition: a and b have as common neighbours only the two opposite corners.
  corners_of_fan(s.triangles, trial.fan_a, a, trial.neighbours_a);
  corners_of_fan(s.triangles, trial.fan_b, b, trial.neighbours_b);
  int common = 0;
  for (const Index q : trial.neighbours_a)
    common += q != b && std::binary_search(trial.neighbours_b.begin(), trial.neighbours_b.end(), q);
  if (common != 2) return false;
  double before = 180.0, after = 180.0;
  for (const Index t : trial.fan_a)
    before = std::min(before, min_angle_of(s.points, s.triangles[t]));
  for (const Index t : trial.moved) {
    const Triangle& k = s.triangles[t];
    const auto at = [&](Index q) -> const Point& { return s.points[q == a ? b : q]; };
    const Point n_old = unit_normal(s.points[k[0]], s.points[k[1]], s.points[k[2]]);
    const Point n_new = unit_normal(at(k[0]), at(k[1]), at(k[2]));
    if (!(dot(n_old, n_new) >= min_cosine)) return false;  // turned, or of no area (NaN)
    after = std::min(after, triangle_min_angle_deg(at(k[0]), at(k[1]), at(k[2])));
  }
  return after > before;
}

}  // namespace

absl::StatusOr<std::int64_t> collapse_edges(SurfaceMeshState& s, const CollapseParams& params,
                                            Progress& progress) {
  SimplexIncidence<3> incidence = SimplexIncidence<3>::of(s.triangles);
  const double min_cosine = std::cos(params.max_normal_turn_deg * std::numbers::pi / 180.0);
  CancelCheck cancel(progress, 4096);
  Trial trial;
  std::int64_t collapses = 0;
  const auto movable = [&](Index q) { return q >= s.line_points && s.anchor[q] == kInvalidIndex; };
  for (int pass = 0; pass < params.max_passes; ++pass) {
    if (cancel.look()) return absl::CancelledError("surface meshing cancelled");
    std::int64_t made = 0;
    for (Index t = 0; t < static_cast<Index>(s.triangles.size()); ++t) {
      if (cancel.due()) return absl::CancelledError("surface meshing cancelled");
      if (s.triangles[t][0] == kInvalidIndex) continue;
      if (min_angle_of(s.points, s.triangles[t]) >= params.bad_angle_deg) continue;
      // Its edges, shortest first; the first merge found is made.
      std::array<std::pair<double, int>, 3> edges;
      for (int k = 0; k < 3; ++k) {
        const Triangle& tri = s.triangles[t];
        edges[k] = {squared_norm(sub(s.points[tri[(k + 1) % 3]], s.points[tri[k]])), k};
      }
      std::sort(edges.begin(), edges.end());
      for (const auto& [length2, k] : edges) {
        const Index u = s.triangles[t][k], v = s.triangles[t][(k + 1) % 3];
        Index a = kInvalidIndex, b = kInvalidIndex;
        if (movable(u) && collapse_is_better(s, incidence, u, v, min_cosine, trial)) {
          a = u, b = v;
        } else if (movable(v) && collapse_is_better(s, incidence, v, u, min_cosine, trial)) {
          a = v, b = u;
        }
        if (a == kInvalidIndex) continue;
        for (const Index g : trial.fan_a) incidence.remove(s.triangles, g);
        for (const Index g : trial.shared)
          s.triangles[g] = {kInvalidIndex, kInvalidIndex, kInvalidIndex};
        for (const Index g : trial.moved) {
          for (Index& q : s.triangles[g])
            if (q == a) q = b;
          incidence.add(s.triangles, g);
        }
        ++made;
        break;
      }
    }
    collapses += made;
    if (made == 0) break;
  }
  // The merged points are used by no triangle: compacting from the first patch point drops them.
  if (collapses > 0) s.compact_patch(s.line_points, 0);
  return collapses;
}

}  // namespace afmesh
