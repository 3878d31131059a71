// F1: the front must bound a volume before the loop may start.
#include <string>

#include "absl/strings/str_cat.h"
#include "core/quality/validate.h"
#include "core/volume/generate_volume_mesh.h"

namespace afmesh {

absl::Status validate_front(const Mesh& front, std::span<const std::int32_t> face_environments,
                            bool check_self_intersections, Progress& progress) {
  if (front.points.empty() || front.triangles.empty())
    return absl::InvalidArgumentError(absl::StrCat("the front is empty: ", front.points.size(),
                                                   " points, ", front.triangles.size(),
                                                   " triangles"));
  if (!front.tets.empty())
    return absl::InvalidArgumentError(absl::StrCat(
        "the front must be a surface, but it has ", front.tets.size(), " tetrahedra"));
  ValidationParams params;
  params.max_findings_per_check = 3;
  params.face_environments = face_environments;
  const absl::StatusOr<ValidationReport> report = validate_surface(front, params, progress);
  if (!report.ok()) return report.status();
  for (const Check& c : report->checks) {
    if (c.passed()) continue;
    if (c.outcome == CheckOutcome::kNotRun) continue;  // its cause failed before it
    if (!check_self_intersections && c.name == check::kNoSelfIntersections) continue;
    std::string message = absl::StrCat("invalid front: ", c.name, ": ", c.summary);
    for (const Finding& f : c.findings) absl::StrAppend(&message, "; ", f.message);
    return absl::InvalidArgumentError(message);
  }
  return absl::OkStatus();
}

}  // namespace afmesh
