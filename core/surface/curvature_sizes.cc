#include "core/surface/curvature_sizes.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <numbers>
#include <numeric>
#include <queue>
#include <utility>

#include "absl/container/flat_hash_set.h"
#include "core/geometry/vec.h"

namespace afmesh {
namespace {

std::pair<Index, Index> edge_key(Index a, Index b) { return {std::min(a, b), std::max(a, b)}; }

}  // namespace

std::vector<double> curvature_point_sizes(const DiscreteSurface& surface,
                                          const SurfaceFeatures& features, double alpha_p_deg) {
  const std::vector<Point>& p = surface.local_points();
  const std::vector<Triangle>& t = surface.triangles();
  std::vector<double> size(p.size(), std::numeric_limits<double>::infinity());
  absl::flat_hash_set<std::pair<Index, Index>> line_edges;
  for (const DiscreteLine& line : features.lines)
    for (std::size_t i = 0; i + 1 < line.vertices.size(); ++i)
      line_edges.insert(edge_key(line.vertices[i], line.vertices[i + 1]));
  const double tan_p = std::tan(0.5 * alpha_p_deg * std::numbers::pi / 180.0);
  const EdgeNeighbours& neighbours = surface.neighbours();
  // Eq. 20–22 over each edge between two faces, once (from its lower face).
  for (Index f = 0; f < surface.face_count(); ++f) {
    for (int k = 0; k < 3; ++k) {
      const Index g = neighbours.across[f][k];
      if (g == kInvalidIndex || g < f) continue;
      const Index a = t[f][k], b = t[f][(k + 1) % 3];
      if (line_edges.contains(edge_key(a, b))) continue;
      // Normals of faces that traverse the edge the same way disagree in orientation.
      const double sign = neighbours.same_way[f][k] ? -1.0 : 1.0;
      const double cosine = std::clamp(
          sign * dot(surface.normal(FaceId{f}), surface.normal(FaceId{g})), -1.0, 1.0);
      const double alpha_g = std::acos(cosine);
      if (!(alpha_g > 1e-9)) continue;
      const double tan_g = std::tan(0.5 * std::min(alpha_g, 0.99 * std::numbers::pi));
      const double l_g = distance(surface.centroid(FaceId{f}), surface.centroid(FaceId{g}));
      const double l_p = l_g * tan_p / tan_g;  // eq. 21
      size[a] = std::min(size[a], l_p);        // eq. 22
      size[b] = std::min(size[b], l_p);
    }
  }
  return size;
}

void grade_point_sizes(const DiscreteSurface& surface, double growth, std::vector<double>& size) {
  const std::vector<Point>& p = surface.local_points();
  const std::vector<Triangle>& t = surface.triangles();
  // The smallest delta_i + (c_i - 1) |x_j - x_i| over the surface's edges (Dijkstra).
  const double rate = std::max(growth, 1.0) - 1.0;
  using Item = std::pair<double, Index>;
  std::priority_queue<Item, std::vector<Item>, std::greater<>> queue;
  for (Index v = 0; v < static_cast<Index>(size.size()); ++v)
    if (std::isfinite(size[v])) queue.push({size[v], v});
  while (!queue.empty()) {
    const auto [d, v] = queue.top();
    queue.pop();
    if (d > size[v]) continue;
    for (const Index f : surface.faces_at(v)) {
      for (const Index w : t[f]) {
        if (w == v) continue;
        const double through = d + rate * norm(sub(p[w], p[v]));
        if (through < size[w]) {
          size[w] = through;
          queue.push({through, w});
        }
      }
    }
  }
}

CurvatureLimitedSize::CurvatureLimitedSize(const SizeField& base, const DiscreteSurface& surface,
                                           std::vector<double> point_sizes)
    : base_(base),
      surface_(surface),
      point_sizes_(std::move(point_sizes)),
      smallest_(std::accumulate(point_sizes_.begin(), point_sizes_.end(),
                                std::numeric_limits<double>::infinity(),
                                [](double a, double b) { return std::min(a, b); })) {}

double CurvatureLimitedSize::size_at(const Point& x) const {
  const double base = base_.size_at(x);
  // min(base, curvature) is base whenever curvature >= smallest_ >= base: the same double.
  if (base <= smallest_) return base;
  const Located at = surface_.nearest_face(surface_.to_local(x));
  double curvature = std::numeric_limits<double>::infinity();
  for (const Index v : surface_.triangle(at.face)) curvature = std::min(curvature, point_sizes_[v]);
  return std::min(base, curvature);
}

}  // namespace afmesh
