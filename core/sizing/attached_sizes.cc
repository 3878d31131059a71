#include "core/sizing/attached_sizes.h"

#include <cmath>
#include <limits>

#include "absl/strings/str_cat.h"
#include "core/geometry/vec.h"

namespace afmesh {
namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();

absl::Status check_triangles(const Mesh& surface) {
  const Index n = static_cast<Index>(surface.points.size());
  for (std::size_t t = 0; t < surface.triangles.size(); ++t) {
    for (int c = 0; c < 3; ++c) {
      const Index v = surface.triangles[t][c];
      if (v < 0 || v >= n) {
        return absl::InvalidArgumentError(absl::StrCat("triangles[", t, "][", c, "] = ", v,
                                                       " is out of range [0, ", n, ")"));
      }
    }
  }
  return absl::OkStatus();
}

absl::Status check_overrides(const Mesh& surface, const AttachedSizeParams& params) {
  const Index n = static_cast<Index>(surface.points.size());
  for (const auto& [p, size] : params.point_sizes) {
    if (p < 0 || p >= n) {
      return absl::InvalidArgumentError(
          absl::StrCat("point_sizes names point ", p, ", out of range [0, ", n, ")"));
    }
    if (!(std::isfinite(size) && size > 0.0)) {
      return absl::InvalidArgumentError(
          absl::StrCat("point_sizes[", p, "] must be a finite number > 0, got ", size));
    }
  }
  for (const auto& [tag, size] : params.tag_sizes) {
    if (!(std::isfinite(size) && size > 0.0)) {
      return absl::InvalidArgumentError(
          absl::StrCat("tag_sizes[", tag, "] must be a finite number > 0, got ", size));
    }
  }
  return absl::OkStatus();
}

// The edge-length default of every point (+inf on no triangle). Each interior edge of a closed
// surface is seen from both of its triangles, which leaves the minimum unchanged and weights
// every edge twice in the mean.
std::vector<double> edge_length_sizes(const Mesh& surface, EdgeLengthRule rule) {
  const std::size_t n = surface.points.size();
  std::vector<double> shortest(n, kInfinity), sum(n, 0.0);
  std::vector<int> count(n, 0);
  for (const Triangle& t : surface.triangles) {
    for (int i = 0; i < 3; ++i) {
      const Index a = t[i], b = t[(i + 1) % 3];
      const double length = distance(surface.points[a], surface.points[b]);
      for (Index p : {a, b}) {
        shortest[p] = std::min(shortest[p], length);
        sum[p] += length;
        ++count[p];
      }
    }
  }
  if (rule == EdgeLengthRule::kMinimum) return shortest;
  for (std::size_t p = 0; p < n; ++p) sum[p] = count[p] > 0 ? sum[p] / count[p] : kInfinity;
  return sum;
}

}  // namespace

absl::StatusOr<std::vector<double>> attached_point_sizes(const Mesh& surface,
                                                         const AttachedSizeParams& params) {
  if (absl::Status s = check_triangles(surface); !s.ok()) return s;
  if (absl::Status s = check_overrides(surface, params); !s.ok()) return s;
  std::vector<double> sizes = edge_length_sizes(surface, params.rule);
  if (!params.tag_sizes.empty()) {
    std::vector<double> tagged(surface.points.size(), kInfinity);
    for (std::size_t t = 0; t < surface.triangles.size(); ++t) {
      const Index tag = t < surface.triangle_tags.size() ? surface.triangle_tags[t] : 0;
      const auto it = params.tag_sizes.find(tag);
      if (it == params.tag_sizes.end()) continue;
      for (Index p : surface.triangles[t]) tagged[p] = std::min(tagged[p], it->second);
    }
    for (std::size_t p = 0; p < sizes.size(); ++p) {
      if (tagged[p] < kInfinity) sizes[p] = tagged[p];
    }
  }
  for (const auto& [p, size] : params.point_sizes) sizes[p] = size;
  return sizes;
}

}  // namespace afmesh
