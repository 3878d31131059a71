// MeshVolume's part of a streaming call (streaming_call.h): its input (the header's
// VolumeOptions and counts, then point, triangle and background grid slices: VolumeInput), its
// job's sequence on the worker, and its result stream (VolumeOutputStream).
#pragma once

#include <cstdint>

#include "absl/status/statusor.h"
#include "afmesh/v1/mesher.pb.h"
#include "server/call_log.h"
#include "server/streaming_call.h"
#include "server/surface_job.h"
#include "server/volume_input.h"
#include "server/volume_job.h"
#include "server/volume_output.h"

namespace afmesh::server {

class MeshVolumeRpc {
 public:
  using Request = v1::MeshVolumeRequest;
  using Response = v1::MeshVolumeResponse;
  using Input = VolumeInput;
  using Output = VolumeOutputStream;
  static constexpr char kName[] = "MeshVolume";

  // `job` meshes each call's front; `limits` bound its input and, by the estimate, its mesh;
  // `surface_job` re-triangulates the front first when a call asks for remesh_surface (empty:
  // such calls end UNIMPLEMENTED).
  MeshVolumeRpc(VolumeJob job, const InputLimits& limits, SurfaceJob surface_job = {});

  Input make_input() const { return VolumeInput(limits_); }
  static void count_request(const Request& request, CallRecord& record);
  static void count_output(const Output& output, CallRecord& record);

  // On a worker, for a checked input: the front repaired where that needs no guessing (F1 for
  // fronts as files bring them), the mesh estimated and admitted against --max-elements and the
  // memory budget, the crossing environments when asked for (paper §2), then the job, whose
  // mesh must be whole (check_job_output). With remesh_surface, the surface step
  // (surface_step.h) first, whose surface becomes the front. Each step's notes become Warnings,
  // before the job's.
  absl::StatusOr<Output> run(Input input, JobContext& context) const;

 private:
  const VolumeJob job_;
  const SurfaceJob surface_job_;
  const InputLimits limits_;
};

}  // namespace afmesh::server
