// The surface job a MeshSurface call (or a MeshVolume call with remesh_surface) runs on a worker:
// core types in, core types out, no gRPC. As with VolumeJob, the service takes it as a function
// so that tests can inject fakes and the server library does not depend on the surface mesher;
// afmesh-server passes generate_surface_mesh (core/surface/generate_surface_mesh.h).
#pragma once

#include <cstdint>
#include <functional>

#include "absl/status/statusor.h"
#include "core/common/progress.h"
#include "core/mesh/mesh.h"
#include "core/surface/generate_surface_mesh.h"

namespace afmesh::server {

// Re-triangulates `input` (N points, M triangles with tags; checked by the service for finite
// coordinates and indices in range) with `params`, reporting to and polling `progress`. Must
// return absl::CancelledError soon after progress.cancelled() turns true. The returned status
// code reaches the client as the call's status. An empty SurfaceJob makes the calls that need
// it UNIMPLEMENTED.
using SurfaceJob = std::function<absl::StatusOr<SurfaceResult>(
    const Mesh& input, const SurfaceParams& params, Progress& progress)>;

// Corner angles of a triangulation, as SurfaceQuality reports them (degrees).
struct SurfaceQualityFigures {
  double min_angle_deg = 0.0;
  double max_angle_deg = 0.0;
  double share_below_30_deg = 0.0;      // share of triangles whose smallest angle is < 30°
  std::int64_t count_below_15_deg = 0;  // triangles whose smallest angle is < 15°
};

// What the service made of a successful surface step.
struct SurfaceOutcome {
  SurfaceResult result;  // the job's surface, report and timings
  SurfaceQualityFigures quality;
  double estimated_triangles = 0.0;  // what the limits were checked against
};

}  // namespace afmesh::server
