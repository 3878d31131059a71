#include "core/surface/smooth_points.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include "core/geometry/vec.h"
#include "core/mesh/simplex_incidence.h"
#include "core/quality/measures.h"

namespace afmesh {
namespace {

// The fan of point q with q moved to `x`: its smallest angle, and whether every triangle's normal
// stays within `min_cosine` of `before` (its normal with q where it was).
struct Fan {
  double min_angle = 180.0;
  bool turned = false;
};

Fan fan_at(const SurfaceMeshState& s, Index q, const Point& x, const std::vector<Index>& fan,
           const std::vector<Point>& before, double min_cosine) {
  Fan out;
  for (std::size_t i = 0; i < fan.size(); ++i) {
    const Triangle& t = s.triangles[fan[i]];
    const auto at = [&](Index k) -> const Point& { return k == q ? x : s.points[k]; };
    out.min_angle = std::min(out.min_angle, triangle_min_angle_deg(at(t[0]), at(t[1]), at(t[2])));
    if (dot(unit_normal(at(t[0]), at(t[1]), at(t[2])), before[i]) < min_cosine)
      out.turned = true;
  }
  return out;
}

}  // namespace

absl::StatusOr<std::int64_t> smooth_points(SurfaceMeshState& s, const SmoothParams& params,
                                           Progress& progress) {
  SimplexIncidence<3> incidence = SimplexIncidence<3>::of(s.triangles);
  const double min_cosine = std::cos(params.max_normal_turn_deg * std::numbers::pi / 180.0);
  CancelCheck cancel(progress, 1024);  // each point a walk and a few fans
  std::vector<Index> fan;
  std::vector<Point> before;
  // The smallest angle of each triangle, computed when first needed (negative: not yet) and
  // forgotten when a corner moves: a triangle is in the fans of its three corners, and each
  // fan's angles are measured where it stands before a move is tried.
  std::vector<double> smallest_angle(s.triangles.size(), -1.0);
  const auto angle_of = [&](Index t) {
    if (smallest_angle[t] < 0) {
      const Triangle& k = s.triangles[t];
      smallest_angle[t] = triangle_min_angle_deg(s.points[k[0]], s.points[k[1]], s.points[k[2]]);
    }
    return smallest_angle[t];
  };
  // A point is looked at in a pass when it or a neighbour moved in the one before.
  std::vector<char> due(s.points.size(), 1), next(s.points.size(), 0);
  std::int64_t moves = 0;
  for (int pass = 0; pass < params.max_passes; ++pass) {
    std::int64_t moved = 0;
    for (Index q = 0; q < static_cast<Index>(s.points.size()); ++q) {
      if (cancel.due()) return absl::CancelledError("surface meshing cancelled");
      if (!due[q] || s.anchor[q] != kInvalidIndex) continue;  // a corner or a line point
      fan.clear();
      incidence.elements_of(s.triangles, q, fan);
      if (fan.size() < 3) continue;
      double now = 180.0;
      for (const Index t : fan) now = std::min(now, angle_of(t));
      if (now >= params.good_fan_deg) continue;
      // The mean of the fan's other corners, in the patch's tangent plane after projection.
      Point mean{0, 0, 0};
      before.clear();
      for (const Index t : fan) {
        const Triangle& k = s.triangles[t];
        for (const Index r : k)
          if (r != q) mean = add(mean, s.points[r]);
        before.push_back(unit_normal(s.points[k[0]], s.points[k[1]], s.points[k[2]]));
      }
      mean = scale(mean, 1.0 / (2.0 * static_cast<double>(fan.size())));
      const PatchId patch{s.triangle_patch[fan[0]]};
      const Located on =                                                         // S8
          locate_in_patch(s.surface, s.features, patch, mean, patch_hint(s, patch, q));
      const Fan moved_fan = fan_at(s, q, on.closest, fan, before, min_cosine);
      if (moved_fan.turned || !(moved_fan.min_angle >= now + params.min_gain_deg)) continue;
      s.points[q] = on.closest;
      s.host[q] = on.face;
      ++moved;
      for (const Index t : fan) {
        smallest_angle[t] = -1.0;
        for (const Index r : s.triangles[t]) next[r] = 1;
      }
    }
    moves += moved;
    if (moved == 0) break;
    due.swap(next);
    std::fill(next.begin(), next.end(), 0);
  }
  return moves;
}

}  // namespace afmesh
