#include "core/surface/gap_sizes.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/front/front_bins.h"
#include "core/geometry/closest_points.h"
#include "core/geometry/vec.h"
#include "core/spatial/box.h"

namespace afmesh {
namespace {

constexpr double kParallelCosine = 0.8660254037844386;  // within 30° of parallel
constexpr double kAlongCosine = 0.5;                      // the gap at least 60° off the line
bool share_a_patch(const DiscreteLine& a, const DiscreteLine& b) {
  auto i = a.patches.begin();
  auto j = b.patches.begin();
  while (i != a.patches.end() && j != b.patches.end()) {
    if (*i == *j) return true;
    if (index_of(*i) < index_of(*j)) ++i; else ++j;
  }
  return false;
}

}  // namespace

std::vector<double> line_gap_sizes(const DiscreteSurface& surface, const SurfaceFeatures& features,
                                   const SizeField& field) {
  const std::vector<Point>& p = surface.local_points();
  std::vector<double> size(p.size(), std::numeric_limits<double>::infinity());
  // Every line edge, in the bins by its box.
  struct Edge {
    Index a, b;
    Index line;
  };
  std::vector<Edge> edges;
  Box domain = empty_box();
  for (Index l = 0; l < static_cast<Index>(features.lines.size()); ++l) {
    const std::vector<Index>& v = features.lines[l].vertices;
    for (std::size_t i = 0; i + 1 < v.size(); ++i) {
      edges.push_back({v[i], v[i + 1], l});
      enclose(domain, p[v[i]]);
      enclose(domain, p[v[i + 1]]);
    }
  }
  if (edges.size() < 2) return size;
  // Cells of the size at the lines' middle vertex (the bins enlarge them when too many).
  const Point& some = p[edges[edges.size() / 2].a];
  const double cell = field.size_at(surface.to_global(some));
  if (!(cell > 0) || !std::isfinite(cell)) return size;
  FrontBins bins(domain, cell);
  for (Index e = 0; e < static_cast<Index>(edges.size()); ++e) {
    Box box{p[edges[e].a], p[edges[e].a]};
    enclose(box, p[edges[e].b]);
    bins.insert_item(e, box);
  }
  for (Index l = 0; l < static_cast<Index>(features.lines.size()); ++l) {
    const DiscreteLine& line = features.lines[l];
    const std::vector<Index>& v = line.vertices;
    for (std::size_t i = 0; i < v.size(); ++i) {
      const Point& x = p[v[i]];
      // The line's direction at the vertex, from its neighbours along it.
      const Point before = p[v[i > 0 ? i - 1 : (line.closed ? v.size() - 2 : i)]];
      const Point after = p[v[i + 1 < v.size() ? i + 1 : (line.closed ? 1 : i)]];
      Point t = sub(after, before);
      if (!(norm(t) > 0)) continue;
      t = scale(t, 1.0 / norm(t));
      const double wanted = field.size_at(surface.to_global(x));
      const double reach = std::min(wanted, size[v[i]]);
      if (!(reach > 0) || !std::isfinite(reach)) continue;
      const Box box{{x[0] - reach, x[1] - reach, x[2] - reach},
                    {x[0] + reach, x[1] + reach, x[2] + reach}};
      double gap = reach;
      bins.find_item_near(box, [&](Index e) {
        const Edge& edge = edges[e];
        if (edge.a == v[i] || edge.b == v[i]) return false;
        const Point along = sub(p[edge.b], p[edge.a]);
        const double length = norm(along);
        if (!(length > 0) || std::abs(dot(along, t)) < kParallelCosine * length) return false;
        const Point across = sub(closest_point_on_segment(x, p[edge.a], p[edge.b]), x);
        const double d = norm(across);
        if (!(d < gap) || std::abs(dot(across, t)) > kAlongCosine * d) return false;
        if (edge.line != l && !share_a_patch(line, features.lines[edge.line])) return false;
        gap = d;
        return false;
      });
      if (gap < reach)
        size[v[i]] = std::min(size[v[i]], std::max(gap, kMinGapSizes * wanted));
    }
  }
  return size;
}

}  // namespace afmesh
