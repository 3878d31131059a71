#include "core/surface/wall_sizes.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/geometry/vec.h"
#include "core/spatial/box.h"
#include "core/surface/gap_sizes.h"

namespace afmesh {
namespace {

// A face counts as the opposite wall when its normal is within 60° of the opposite of the
// face measured from, and it lies within 60° of that face's inward direction (the header).
constexpr double kOppositeCosine = 0.5;
constexpr double kBehindCosine = 0.5;
// The opposite wall is looked for within the size, but no farther than this many times the
// face's longest edge: on a scan of a million faces (bench/surface's scan900k) meshed at 0.05,
// about ten faces wide, the faces within the size were hundreds per face, and the search took
// 155 s where the mesh took 41 (78 s within 8 edges, 12 s within 3). A wall thicker than 3 of
// its faces yet thinner than the size keeps the size.
constexpr double kMaxReachInEdges = 3.0;
// Faces between two looks at the job's progress (cancellation).
constexpr Index kFacesPerLook = 4096;

}  // namespace

absl::StatusOr<std::vector<double>> wall_thickness_sizes(const DiscreteSurface& surface,
                                                         double per_thickness,
                                                         const SizeField& field,
                                                         Progress& progress) {
  const std::vector<Point>& p = surface.local_points();
  std::vector<double> size(p.size(), std::numeric_limits<double>::infinity());
  for (Index f = 0; f < surface.face_count(); ++f) {
    if (f % kFacesPerLook == 0 && progress.cancelled())
      return absl::CancelledError("wall sizes: cancelled");
    const Point& n = surface.normal(FaceId{f});
    if (!(squared_norm(n) > 0.0)) continue;
    const Point& x = surface.centroid(FaceId{f});
    const double wanted = field.size_at(surface.to_global(x));
    if (!(wanted > 0.0) || !std::isfinite(wanted)) continue;
    const Triangle& t = surface.triangles()[f];
    const double longest = std::max({distance(p[t[0]], p[t[1]]), distance(p[t[1]], p[t[2]]),
                                     distance(p[t[2]], p[t[0]])});
    const double reach = std::min(wanted, kMaxReachInEdges * longest);
    double thickness = reach;
    Box box;
    for (int a = 0; a < 3; ++a) box.lo[a] = x[a] - reach, box.hi[a] = x[a] + reach;
    surface.for_each_face_overlapping(box, [&](FaceId g) {
      if (index_of(g) == f || !(dot(surface.normal(g), n) < -kOppositeCosine)) return;
      Point closest;
      const double d2 = surface.squared_distance_to_face(x, g, closest);
      if (!(d2 < thickness * thickness)) return;
      const double d = std::sqrt(d2);
      if (!(dot(sub(closest, x), n) < -kBehindCosine * d)) return;
      thickness = d;
    });
    if (!(thickness < reach) || !(per_thickness * thickness < wanted)) continue;
    // The floor of the gaps between lines (kMinGapSizes, gap_sizes.h), for the same reasons.
    const double h = std::max(per_thickness * thickness, kMinGapSizes * wanted);
    for (const Index v : t) size[v] = std::min(size[v], h);
  }
  return size;
}

}  // namespace afmesh
