// The production MeshVolume job: the advancing-front mesher, then the quality figures and the
// validator's verdict for the Summary.
#pragma once

#include "absl/status/statusor.h"
#include "core/quality/measures.h"
#include "server/volume_job.h"

namespace afmesh::server {

// generate_volume_mesh (which validates the front first: INVALID_ARGUMENT naming the element),
// then summarize_quality and validate_volume_mesh against the front (with
// params.face_environments also the environment_gap check) side by side on two threads, one
// "quality+validation" stage. A mesh that fails validation is not handed out: INTERNAL with the
// validator's report. Checks that only warn go to VolumeJobOutput::validation.messages.
absl::StatusOr<VolumeJobOutput> run_volume_job(const Mesh& front, const VolumeParams& params,
                                               Progress& progress);

// run_volume_job as a VolumeJob.
VolumeJob default_volume_job();

// The Summary's quality figures from core/quality's mesh summary.
VolumeQuality volume_quality(const QualitySummary& summary);

}  // namespace afmesh::server
