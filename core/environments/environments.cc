// LPOCR from LFACR, and LFACR from triangle tags (paper §2).
#include "core/environments/environments.h"

#include <algorithm>

#include "absl/strings/str_format.h"

namespace afmesh {

std::vector<std::int32_t> point_environments(std::size_t point_count,
                                             const std::vector<Triangle>& triangles,
                                             std::span<const std::int32_t> face_environments) {
  std::vector<std::int32_t> point(point_count, kNoEnvironment);
  for (std::size_t t = 0; t < triangles.size() && t < face_environments.size(); ++t) {
    const std::int32_t face = face_environments[t];
    if (face <= 0) continue;  // environment 0 leaves the point's mark as it is
    for (const Index p : triangles[t]) {
      std::int32_t& mark = point[p];
      if (mark == kNoEnvironment) {
        mark = face;
      } else if (mark != face) {
        mark = kSharedEnvironment;  // a second positive environment: a ridge point
      }
    }
  }
  // A face of no environment whose points belong to two different positive environments joins
  // the two sides where they meet: a narrow strip closing the rim of a plate instead of the
  // sides sharing their rim points. Its points are ridge points too, so that elements on it,
  // which must touch both sides, join no two environments (not in the paper, whose sides meet in
  // shared points). Decided on the marks above, not on marks this loop sets.
  std::vector<Index> rim;
  for (std::size_t t = 0; t < triangles.size() && t < face_environments.size(); ++t) {
    if (face_environments[t] > 0) continue;
    std::int32_t seen = kNoEnvironment;
    bool two = false;
    for (const Index p : triangles[t]) {
      const std::int32_t mark = point[p];
      if (mark <= 0) continue;
      if (seen != kNoEnvironment && mark != seen) two = true;
      seen = mark;
    }
    if (two) rim.insert(rim.end(), triangles[t].begin(), triangles[t].end());
  }
  for (const Index p : rim) point[p] = kSharedEnvironment;
  return point;
}

bool has_positive_tags(const Mesh& mesh) {
  return std::any_of(mesh.triangle_tags.begin(), mesh.triangle_tags.end(),
                     [](Index tag) { return tag > 0; });
}

absl::StatusOr<FrontEnvironments> environments_from_tags(const Mesh& front) {
  if (front.triangle_tags.size() != front.triangles.size()) {
    return absl::InvalidArgumentError(
        absl::StrFormat("the front has %d triangle tags for %d triangles",
                        front.triangle_tags.size(), front.triangles.size()));
  }
  const auto point_count = static_cast<std::int64_t>(front.points.size());
  for (std::size_t t = 0; t < front.triangles.size(); ++t) {
    for (const Index p : front.triangles[t]) {
      if (p < 0 || p >= point_count) {
        return absl::InvalidArgumentError(absl::StrFormat(
            "triangle %d refers to point %d, but the front has %d points", t, p, point_count));
      }
    }
    if (front.triangle_tags[t] < 0) {
      return absl::InvalidArgumentError(absl::StrFormat(
          "triangle %d has tag %d: environment ids must be >= 0 (0 = no environment)", t,
          front.triangle_tags[t]));
    }
  }
  if (!has_positive_tags(front)) {
    return absl::InvalidArgumentError(absl::StrFormat(
        "none of the %d triangles carries a positive tag, so there are no environments to "
        "read (tag the triangles on each side of a thin region with an environment id > 0)",
        front.triangles.size()));
  }
  FrontEnvironments environments;
  environments.face.assign(front.triangle_tags.begin(), front.triangle_tags.end());
  environments.point = point_environments(front.points.size(), front.triangles, environments.face);
  return environments;
}

int count_environments(std::span<const std::int32_t> face_environments) {
  std::vector<std::int32_t> ids;
  for (const std::int32_t e : face_environments) {
    if (e > 0) ids.push_back(e);
  }
  std::sort(ids.begin(), ids.end());
  return static_cast<int>(std::unique(ids.begin(), ids.end()) - ids.begin());
}

}  // namespace afmesh
