#include "server/mesh_surface_rpc.h"

#include <string>
#include <utility>

#include "server/surface_options.h"
#include "server/surface_step.h"

namespace afmesh::server {
namespace {

// MeshSurface's header as MeshVolume's: the size and the counts (no environments).
v1::MeshVolumeHeader volume_header(const v1::MeshSurfaceHeader& header) {
  v1::MeshVolumeHeader volume;
  *volume.mutable_options()->mutable_size() = header.options().size();
  if (header.has_point_count()) volume.set_point_count(header.point_count());
  if (header.has_triangle_count()) volume.set_triangle_count(header.triangle_count());
  if (header.has_grid_point_count()) volume.set_grid_point_count(header.grid_point_count());
  if (header.has_grid_tet_count()) volume.set_grid_tet_count(header.grid_tet_count());
  return volume;
}

// The MeshVolume request of the same part (slices copied: at most 1 MiB each).
v1::MeshVolumeRequest volume_request(const v1::MeshSurfaceRequest& request) {
  v1::MeshVolumeRequest volume;
  switch (request.part_case()) {
    case v1::MeshSurfaceRequest::kHeader:
      *volume.mutable_header() = volume_header(request.header());
      break;
    case v1::MeshSurfaceRequest::kPoints:
      *volume.mutable_points() = request.points();
      break;
    case v1::MeshSurfaceRequest::kTriangles:
      *volume.mutable_triangles() = request.triangles();
      break;
    case v1::MeshSurfaceRequest::kBackgroundGrid:
      *volume.mutable_background_grid() = request.background_grid();
      break;
    case v1::MeshSurfaceRequest::PART_NOT_SET:
      break;
  }
  return volume;
}

}  // namespace

absl::Status SurfaceInput::add(const v1::MeshSurfaceRequest& request) {
  if (absl::Status status = volume_.add(volume_request(request)); !status.ok()) return status;
  if (!request.has_header()) return absl::OkStatus();
  angles_ = angles_of(request.header().options());
  SurfaceParams checked;
  return surface_params_from(volume_.params(), angles_, "options.", checked);
}

SurfaceParams SurfaceInput::params() const {
  SurfaceParams params;
  // Checked when the header came.
  (void)surface_params_from(volume_.params(), angles_, "options.", params);
  return params;
}

namespace {

// The VolumeJobOutput whose stream carries `outcome`'s surface (no tets).
VolumeJobOutput surface_as_volume(SurfaceOutcome& outcome, std::vector<std::string> warnings) {
  VolumeJobOutput output;
  output.volume.mesh = std::move(outcome.result.mesh);
  output.volume.timings = outcome.result.timings;
  output.warnings = std::move(warnings);
  return output;
}

}  // namespace

SurfaceOutputStream::SurfaceOutputStream(SurfaceOutcome outcome,
                                         std::vector<std::string> warnings,
                                         std::vector<StageTiming> timings_before)
    : outcome_(std::move(outcome)),
      stream_(surface_as_volume(outcome_, std::move(warnings)), std::move(timings_before)) {}

bool SurfaceOutputStream::next(v1::MeshSurfaceResponse& response) {
  response.Clear();
  if (!stream_.next(volume_response_)) return false;
  switch (volume_response_.event_case()) {
    case v1::MeshVolumeResponse::kWarning:
      response.mutable_warning()->Swap(volume_response_.mutable_warning());
      break;
    case v1::MeshVolumeResponse::kPoints:
      response.mutable_points()->Swap(volume_response_.mutable_points());
      break;
    case v1::MeshVolumeResponse::kTriangles:
      response.mutable_triangles()->Swap(volume_response_.mutable_triangles());
      break;
    default: {  // the Summary (no tets: the mesh has none)
      v1::SurfaceSummary& summary = *response.mutable_summary();
      fill_surface_summary(outcome_, summary);
      // outcome_'s mesh lives in stream_ now: the counts are its.
      summary.set_point_count(stream_.mesh().points.size());
      summary.set_triangle_count(stream_.mesh().triangles.size());
      add_timings(stream_.timings(), summary);
      break;
    }
  }
  return true;
}

MeshSurfaceRpc::MeshSurfaceRpc(SurfaceJob job, const InputLimits& limits)
    : job_(std::move(job)), limits_(limits) {}

void MeshSurfaceRpc::count_request(const Request& request, CallRecord& record) {
  server::count_request(request, record);
}

void MeshSurfaceRpc::count_output(const Output& output, CallRecord& record) {
  record.points_out = static_cast<std::int64_t>(output.mesh().points.size());
  record.triangles_out = static_cast<std::int64_t>(output.mesh().triangles.size());
}

absl::StatusOr<SurfaceOutputStream> MeshSurfaceRpc::run(SurfaceInput input,
                                                        JobContext& context) const {
  const SurfaceParams params = input.params();
  const Mesh surface = input.take_input();
  std::vector<StageTiming> timings = context.timings_before();
  std::vector<std::string> notes;
  absl::StatusOr<SurfaceOutcome> outcome = run_surface_step(
      job_, surface, params, limits_.max_elements, context, notes, timings);
  if (!outcome.ok()) return outcome.status();
  return SurfaceOutputStream(*std::move(outcome), std::move(notes), std::move(timings));
}

}  // namespace afmesh::server
