// The meshing job a MeshVolume call runs on a worker: core types in, core types out, no gRPC.
//
// The service takes the job as a function so that tests can run it with a fake (a slow job that
// polls cancellation, a job that fails, a job that returns a fixed mesh) and so that the server
// library does not depend on the mesher itself; afmesh-server passes default_volume_job().
#pragma once

#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "absl/status/statusor.h"
#include "core/common/progress.h"
#include "core/mesh/mesh.h"
#include "core/volume/generate_volume_mesh.h"
#include "core/volume/repair_front.h"
#include "server/surface_job.h"

namespace afmesh::server {

// Quality figures of a tet mesh, as the Summary message reports them (angles in degrees).
struct VolumeQuality {
  double min_dihedral_deg = 0.0;
  double max_dihedral_deg = 0.0;
  double share_below_10_deg = 0.0;  // share of tets whose smallest dihedral angle is < 10°
  double share_below_20_deg = 0.0;  // likewise < 20°
  double min_radius_ratio = 0.0;    // 3 r_in / r_circ
  double mean_radius_ratio = 0.0;
  // The boundary's smallest corner angle and its slivers, and the tets away from them
  // (QualitySummary::tets_away_from_slivers).
  double boundary_min_angle_deg = 0.0;
  std::int64_t boundary_slivers = 0;
  std::int64_t tets_away_from_slivers = 0;
  double away_min_dihedral_deg = 0.0;
  double away_share_below_20_deg = 0.0;
};

// The validator's verdict on the result.
struct VolumeValidation {
  bool passed = false;
  std::vector<std::string> messages;  // one finding per entry
};

// What a successful job hands back to the service.
struct VolumeJobOutput {
  // The mesh (points: the front's first, in input order; triangles: the input front with its
  // tags; tets positive, with tags) and the core's timings per stage.
  VolumeResult volume;
  VolumeQuality quality;
  VolumeValidation validation;
  // Notes for the user that did not stop the mesh; streamed as Warning messages.
  std::vector<std::string> warnings;
  // What the service repaired in the front before meshing it (set by the service, not the job).
  FrontRepairReport repair;
  // The tets the server expected before meshing (core/volume/estimate_elements.h; its limits
  // were checked against this); 0 when not estimated.
  double estimated_tets = 0.0;
  // With VolumeOptions.remesh_surface, the surface step that made the front (set by the
  // service): the Summary then says so and describes it.
  std::optional<SurfaceOutcome> surface;
};

// Meshes `front` (N points, M triangles with tags; already checked by the service for finite
// coordinates and indices in range) with `params`, reporting to and polling `progress`.
// Must return absl::CancelledError soon (well within 100 ms) after progress.cancelled() turns
// true. The returned status code reaches the client as the call's status.
using VolumeJob = std::function<absl::StatusOr<VolumeJobOutput>(
    const Mesh& front, const VolumeParams& params, Progress& progress)>;

}  // namespace afmesh::server
