// MeshSurface's part of a streaming call (streaming_call.h): its input (SurfaceInput: the
// header's SurfaceOptions and counts, then point, triangle and background grid slices), its job's
// sequence on the worker (surface_step.h) and its result stream (SurfaceOutputStream).
//
// MeshSurface's client stream has MeshVolume's layout (the same parts, field numbers and rules),
// so SurfaceInput is MeshVolume's VolumeInput behind a header of its own, and its output is
// MeshVolume's VolumeOutputStream of a mesh without tets, with a SurfaceSummary at the end: one
// implementation of the stream rules, the limits and the slicing for both RPCs.
#pragma once

#include <cstdint>
#include <vector>

#include "absl/status/statusor.h"
#include "afmesh/v1/mesher.pb.h"
#include "server/call_log.h"
#include "server/streaming_call.h"
#include "server/surface_job.h"
#include "server/surface_options.h"
#include "server/volume_input.h"
#include "server/volume_output.h"

namespace afmesh::server {

class SurfaceInput {
 public:
  explicit SurfaceInput(const InputLimits& limits) : volume_(limits) {}

  // As VolumeInput::add (the same errors, named alike: "options.size.max_size ...",
  // "message 3 ..."), and INVALID_ARGUMENT for options.ridge_angle_deg outside (0, 180),
  // options.corner_angle_deg outside (0, 180] (0 means the default) or
  // options.curvature_angle_deg outside [0, 180) or options.curvature_deviation outside [0, 1)
  // (surface_options.h).
  absl::Status add(const v1::MeshSurfaceRequest& request);
  // As VolumeInput::finish.
  absl::Status finish() { return volume_.finish(); }

  SurfaceParams params() const;
  // The assembled input (N×3 points, M×3 triangles, M tags); leaves this input empty.
  Mesh take_input() { return volume_.take_front(); }

 private:
  VolumeInput volume_;
  SurfaceAngles angles_;  // the header's, checked
};

class SurfaceOutputStream {
 public:
  // `timings_before`: the call's stages before the job (e.g. "receive", "queue", "estimate").
  SurfaceOutputStream(SurfaceOutcome outcome, std::vector<std::string> warnings,
                      std::vector<StageTiming> timings_before);

  // Warnings, point slices, triangle slices (with tags), the SurfaceSummary; false after it.
  bool next(v1::MeshSurfaceResponse& response);

  const Mesh& mesh() const { return stream_.mesh(); }

 private:
  SurfaceOutcome outcome_;  // its mesh moved into stream_
  VolumeOutputStream stream_;
  v1::MeshVolumeResponse volume_response_;
};

class MeshSurfaceRpc {
 public:
  using Request = v1::MeshSurfaceRequest;
  using Response = v1::MeshSurfaceResponse;
  using Input = SurfaceInput;
  using Output = SurfaceOutputStream;
  static constexpr char kName[] = "MeshSurface";

  // `job` re-triangulates each call's surface (empty: calls end UNIMPLEMENTED); `limits` bound
  // its input and, by the estimate, its output (--max-elements counts triangles here).
  MeshSurfaceRpc(SurfaceJob job, const InputLimits& limits);

  Input make_input() const { return SurfaceInput(limits_); }
  static void count_request(const Request& request, CallRecord& record);
  static void count_output(const Output& output, CallRecord& record);

  // On a worker, for a checked input: run_surface_step, its notes as Warnings first.
  absl::StatusOr<Output> run(Input input, JobContext& context) const;

 private:
  const SurfaceJob job_;
  const InputLimits limits_;
};

}  // namespace afmesh::server
