// The crossing environments of a MeshVolume call (paper §2; VolumeOptions.environments): the
// step the service runs on the worker, before the meshing job, when a call asks for them.
#pragma once

#include <string>
#include <vector>

#include "absl/status/status.h"
#include "afmesh/v1/mesher.pb.h"
#include "core/common/progress.h"
#include "core/mesh/mesh.h"
#include "core/volume/generate_volume_mesh.h"

namespace afmesh::server {

// For ENVIRONMENT_MODE_TAGS or _AUTO: sets params.face_environments (LFACR, one per triangle of
// `front`) from the tags or by detect_environments, then validates `front` as a closed surface
// with the relaxed self-intersection rule (validate_surface with face_environments: only faces
// of two different positive environments may cross). Appends what was found to `notes` (one
// line for the user). ENVIRONMENT_MODE_NONE leaves params untouched.
// Errors: INVALID_ARGUMENT naming the tag, the faces that cannot be told apart, or the first
// failing check of the front with its elements; CANCELLED when progress.cancelled().
absl::Status assign_environments(v1::EnvironmentMode mode, const Mesh& front,
                                 VolumeParams& params, Progress& progress,
                                 std::vector<std::string>& notes);

}  // namespace afmesh::server
