#include "server/mesh_volume_rpc.h"

#include <chrono>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "absl/strings/str_cat.h"
#include "absl/strings/str_format.h"
#include "core/volume/estimate_elements.h"
#include "core/volume/repair_front.h"
#include "server/run_guarded.h"
#include "server/surface_step.h"
#include "server/volume_environments.h"

namespace afmesh::server {
namespace {

using Clock = std::chrono::steady_clock;
using call_detail::seconds_since;

// Limits up front: the tets the size field asks for and the bytes the job will need, from
// estimate_volume_mesh, against --max-elements (`max_elements`) and the server's memory budget;
// the bytes stay reserved until the call is gone (its mesh streamed out). Sets
// `estimated_tets`. A size specification that cannot be evaluated is the job's to report.
absl::Status admit_by_estimate(const Mesh& front, VolumeParams& params, std::int64_t max_elements,
                               JobContext& context, std::vector<std::string>& notes,
                               double& estimated_tets) {
  params.max_tets = max_elements;  // the front stops there too, should the estimate be wrong
  absl::StatusOr<VolumeEstimate> estimate = estimate_volume_mesh(front, params);
  if (!estimate.ok()) return absl::OkStatus();
  estimated_tets = estimate->tets;
  if (estimate->coarse_front_triangles > 0) {
    notes.push_back(absl::StrFormat(
        "%d of the %d input triangles have edges over %g times the size asked on them (up to "
        "%.3g times): the elements on them take about their size, not the size asked, and gaps "
        "narrower than their edges may not close; re-triangulate the surface at the size first",
        estimate->coarse_front_triangles, front.triangles.size(), kCoarseFrontRatio,
        estimate->coarsest_front_ratio));
  }
  return context.admit_estimate(estimate->tets, "tetrahedra", "the enclosed volume and the sizes",
                                "domain", estimate->bytes, max_elements);
}

}  // namespace

MeshVolumeRpc::MeshVolumeRpc(VolumeJob job, const InputLimits& limits, SurfaceJob surface_job)
    : job_(std::move(job)), surface_job_(std::move(surface_job)), limits_(limits) {}

void MeshVolumeRpc::count_request(const Request& request, CallRecord& record) {
  server::count_request(request, record);
}

void MeshVolumeRpc::count_output(const Output& output, CallRecord& record) {
  const Mesh& mesh = output.mesh();
  record.points_out = static_cast<std::int64_t>(mesh.points.size());
  record.triangles_out = static_cast<std::int64_t>(mesh.triangles.size());
  record.tets_out = static_cast<std::int64_t>(mesh.tets.size());
}

absl::StatusOr<VolumeOutputStream> MeshVolumeRpc::run(VolumeInput input,
                                                      JobContext& context) const {
  Mesh front = input.take_front();
  VolumeParams params = input.params();
  const v1::EnvironmentMode mode = input.environment_mode();
  Progress& progress = context.progress();
  std::vector<StageTiming> timings = context.timings_before();
  std::vector<std::string> notes;

  std::optional<SurfaceOutcome> surface;
  if (input.remesh_surface()) {
    absl::StatusOr<SurfaceOutcome> remeshed =
        run_surface_step(surface_job_, front, input.surface_params(), limits_.max_elements,
                         context, notes, timings);
    if (!remeshed.ok()) return remeshed.status();
    notes.push_back(absl::StrFormat(
        "the input surface was re-triangulated first (options.remesh_surface): the mesh's "
        "boundary is the new surface of %d triangles, not the input's %d",
        remeshed->result.mesh.triangles.size(), front.triangles.size()));
    front = remeshed->result.mesh;
    surface = *std::move(remeshed);
  }

  const Clock::time_point repair_start = Clock::now();
  const FrontRepairReport repair = repair_front(front);
  timings.push_back({"repair", seconds_since(repair_start)});
  for (std::string& note : repair.notes()) notes.push_back(std::move(note));

  const Clock::time_point start = Clock::now();
  double estimated_tets = 0.0;
  absl::Status status =
      admit_by_estimate(front, params, limits_.max_elements, context, notes, estimated_tets);
  if (status.ok()) {
    status = run_guarded("marking environments", [&] {
      return assign_environments(mode, front, params, progress, notes);
    });
  }
  if (mode != v1::ENVIRONMENT_MODE_NONE) {
    timings.push_back({"environments", seconds_since(start)});
  }
  if (!status.ok()) return status;
  if (progress.cancelled()) return absl::CancelledError("the call was stopped before meshing");

  absl::StatusOr<VolumeJobOutput> output =
      run_guarded("meshing this input", [&] { return job_(front, params, progress); });
  if (!output.ok()) {
    // The validator names the repeated points first; the user also learns why they stayed.
    if (output.status().code() == absl::StatusCode::kInvalidArgument &&
        repair.repeated_points_kept > 0)
      return absl::InvalidArgumentError(
          absl::StrCat(output.status().message(), "; ", repair.why_repeated_points_kept()));
    return output.status();
  }
  if (absl::Status whole = check_job_output(*output); !whole.ok()) return whole;
  output->warnings.insert(output->warnings.begin(), notes.begin(), notes.end());
  output->repair = repair;
  output->estimated_tets = estimated_tets;
  output->surface = std::move(surface);
  return VolumeOutputStream(*std::move(output), std::move(timings));
}

}  // namespace afmesh::server
