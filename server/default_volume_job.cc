#include "server/default_volume_job.h"

#include <chrono>
#include <string>
#include <thread>
#include <utility>

#include "absl/strings/str_cat.h"
#include "core/environments/environments.h"
#include "core/quality/validate.h"
#include "core/volume/generate_volume_mesh.h"

namespace afmesh::server {
namespace {

using Clock = std::chrono::steady_clock;

// Appends the wall time since `start` to `timings` as `stage`.
void add_timing(std::vector<StageTiming>& timings, std::string stage, Clock::time_point start) {
  timings.push_back(
      {std::move(stage), std::chrono::duration<double>(Clock::now() - start).count()});
}

absl::Status stop_if_cancelled(const Progress& progress) {
  if (progress.cancelled()) return absl::CancelledError("volume meshing cancelled");
  return absl::OkStatus();
}

// The validator's verdict: INTERNAL with the full report when a check failed, else the
// summaries of the checks that warned. With crossing environments, the environment_gap check
// too: no tet may join two environments across a thin gap (paper §2).
absl::StatusOr<VolumeValidation> validate_result(const Mesh& mesh, const Mesh& front,
                                                 const VolumeParams& params, Progress& progress) {
  ValidationParams validation_params;
  std::vector<std::int32_t> point_environments;
  if (!params.face_environments.empty()) {
    point_environments =
        afmesh::point_environments(front.points.size(), front.triangles, params.face_environments);
    validation_params.point_environments = point_environments;
  }
  const absl::StatusOr<ValidationReport> report =
      validate_volume_mesh(mesh, &front, validation_params, progress);
  if (!report.ok()) return report.status();
  if (!report->valid()) {
    return absl::InternalError(
        absl::StrCat("the volume mesh failed validation:\n", report->to_string()));
  }
  VolumeValidation validation{.passed = true, .messages = {}};
  for (const Check& check : report->checks) {
    if (check.outcome == CheckOutcome::kWarning) {
      validation.messages.push_back(absl::StrCat(check.name, ": ", check.summary));
    }
  }
  return validation;
}

}  // namespace

VolumeQuality volume_quality(const QualitySummary& summary) {
  return VolumeQuality{
      .min_dihedral_deg = summary.tet_min_dihedral_deg.min,
      .max_dihedral_deg = summary.tet_max_dihedral_deg.max,
      .share_below_10_deg = summary.share_min_dihedral_below_10,
      .share_below_20_deg = summary.share_min_dihedral_below_20,
      .min_radius_ratio = summary.tet_radius_ratio.min,
      .mean_radius_ratio = summary.tet_radius_ratio.mean,
      .boundary_min_angle_deg = summary.triangle_min_angle_deg.min,
      .boundary_slivers = summary.boundary_slivers,
      .tets_away_from_slivers = summary.tets_away_from_slivers,
      .away_min_dihedral_deg = summary.away_min_dihedral_deg.min,
      .away_share_below_20_deg = summary.share_away_below_20,
  };
}

absl::StatusOr<VolumeJobOutput> run_volume_job(const Mesh& front, const VolumeParams& params,
                                               Progress& progress) {
  absl::StatusOr<VolumeResult> volume = generate_volume_mesh(front, params, progress);
  if (!volume.ok()) return volume.status();
  std::vector<std::string> warnings = std::move(volume->warnings);
  VolumeJobOutput output{
      .volume = *std::move(volume),
      .quality = {},
      .validation = {},
      .warnings = std::move(warnings),
      .repair = {},
      .estimated_tets = 0,
      .surface = std::nullopt};
  std::vector<StageTiming>& timings = output.volume.timings;

  if (absl::Status status = stop_if_cancelled(progress); !status.ok()) return status;
  // The quality figures and the validation read the same finished mesh: they run side by side
  // (the quality on a second thread), so the answer waits for the longer one, not their sum.
  progress.report("quality and validation", -1.0);
  const Clock::time_point start = Clock::now();
  absl::StatusOr<QualitySummary> quality = absl::InternalError("quality not computed");
  std::thread quality_thread([&] { quality = summarize_quality(output.volume.mesh, progress); });
  absl::StatusOr<VolumeValidation> validation =
      validate_result(output.volume.mesh, front, params, progress);
  quality_thread.join();
  add_timing(timings, "quality+validation", start);
  if (absl::Status status = stop_if_cancelled(progress); !status.ok()) return status;
  if (!quality.ok()) return absl::InternalError(quality.status().message());
  output.quality = volume_quality(*quality);
  if (!validation.ok()) return validation.status();
  output.validation = *std::move(validation);
  return output;
}

VolumeJob default_volume_job() { return run_volume_job; }

}  // namespace afmesh::server
