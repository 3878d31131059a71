#include "server/volume_environments.h"

#include <algorithm>
#include <cstdint>
#include <utility>

#include "absl/strings/str_cat.h"
#include "absl/strings/str_format.h"
#include "core/environments/detect_environments.h"
#include "core/environments/environments.h"
#include "core/quality/validate.h"
#include "core/volume/generate_volume_mesh.h"

namespace afmesh::server {
namespace {

std::string environments_phrase(int count) {
  return absl::StrCat(count, count == 1 ? " environment" : " environments");
}

std::int64_t count_marked(const std::vector<std::int32_t>& environments) {
  return std::count_if(environments.begin(), environments.end(),
                       [](std::int32_t e) { return e > 0; });
}

}  // namespace

absl::Status assign_environments(v1::EnvironmentMode mode, const Mesh& front,
                                 VolumeParams& params, Progress& progress,
                                 std::vector<std::string>& notes) {
  if (mode == v1::ENVIRONMENT_MODE_NONE) return absl::OkStatus();
  progress.report("environments", -1.0);
  if (mode == v1::ENVIRONMENT_MODE_TAGS) {
    absl::StatusOr<FrontEnvironments> tagged = environments_from_tags(front);
    if (!tagged.ok()) {
      return absl::InvalidArgumentError(
          absl::StrCat("environments from tags: ", tagged.status().message()));
    }
    params.face_environments = std::move(tagged->face);
    notes.push_back(absl::StrFormat(
        "crossing environments from tags: %s on %d of %d triangles",
        environments_phrase(count_environments(params.face_environments)),
        count_marked(params.face_environments),
        front.triangles.size()));
  } else {
    absl::StatusOr<DetectedEnvironments> found = detect_environments(front, {}, progress);
    if (!found.ok()) return found.status();
    params.face_environments = std::move(found->environments.face);
    const AutoEnvironmentStats& s = found->stats;
    notes.push_back(absl::StrFormat(
        "crossing environments found: %s on %d of %d triangles (%d crossing and %d nearly "
        "touching face pairs)",
        environments_phrase(s.environment_count), s.marked_faces, front.triangles.size(), s.crossing_pairs,
        s.close_pairs));
  }
  if (progress.cancelled()) return absl::CancelledError("cancelled before validating the front");
  // The front checked with the relaxed self-intersection rule of §2 before the job is queued.
  return validate_front(front, params.face_environments);
}

}  // namespace afmesh::server
