#include "server/volume_output.h"

#include <string>
#include <utility>

#include "absl/strings/str_format.h"
#include "proto/slice_codec.h"
#include "server/surface_step.h"

namespace afmesh::server {
namespace {

// INTERNAL unless every index of `elements` (rows of K indices) is in [0, point_count).
template <typename Element>
absl::Status check_indices(const std::vector<Element>& elements, std::size_t point_count,
                           const char* kind) {
  for (std::size_t e = 0; e < elements.size(); ++e) {
    for (const Index index : elements[e]) {
      if (index < 0 || static_cast<std::size_t>(index) >= point_count) {
        return absl::InternalError(
            absl::StrFormat("the mesher returned %s %d with point index %d out of range [0, %d)",
                            kind, e, index, point_count));
      }
    }
  }
  return absl::OkStatus();
}

}  // namespace

absl::Status check_job_output(const VolumeJobOutput& output) {
  return check_mesh_output(output.volume.mesh);
}

absl::Status check_mesh_output(const Mesh& mesh) {
  if (mesh.triangle_tags.size() != mesh.triangles.size() ||
      mesh.tet_tags.size() != mesh.tets.size()) {
    return absl::InternalError(absl::StrFormat(
        "the mesher returned %d triangle tags for %d triangles and %d tet tags for %d tets",
        mesh.triangle_tags.size(), mesh.triangles.size(), mesh.tet_tags.size(), mesh.tets.size()));
  }
  if (absl::Status status = check_indices(mesh.triangles, mesh.points.size(), "triangle");
      !status.ok()) {
    return status;
  }
  return check_indices(mesh.tets, mesh.points.size(), "tet");
}

VolumeOutputStream::VolumeOutputStream(VolumeJobOutput output,
                                       std::vector<StageTiming> timings_before)
    : output_(std::move(output)), timings_before_(std::move(timings_before)) {}

bool VolumeOutputStream::next(v1::MeshVolumeResponse& response) {
  if (!send_start_) send_start_ = std::chrono::steady_clock::now();
  response.Clear();
  const Mesh& mesh = output_.volume.mesh;
  switch (part_) {
    case Part::kWarnings:
      if (offset_ < output_.warnings.size()) {
        response.mutable_warning()->set_message(output_.warnings[offset_++]);
        return true;
      }
      part_ = Part::kPoints;
      offset_ = 0;
      [[fallthrough]];
    case Part::kPoints:
      if (offset_ < mesh.points.size()) {
        next_points(*response.mutable_points());
        advance_if_done(mesh.points.size());
        return true;
      }
      part_ = Part::kTriangles;
      [[fallthrough]];
    case Part::kTriangles:
      if (offset_ < mesh.triangles.size()) {
        next_triangles(*response.mutable_triangles());
        advance_if_done(mesh.triangles.size());
        return true;
      }
      part_ = Part::kTets;
      [[fallthrough]];
    case Part::kTets:
      if (offset_ < mesh.tets.size()) {
        next_tets(*response.mutable_tets());
        advance_if_done(mesh.tets.size());
        return true;
      }
      part_ = Part::kSummary;
      [[fallthrough]];
    case Part::kSummary:
      fill_summary(*response.mutable_summary());
      part_ = Part::kDone;
      return true;
    case Part::kDone:
      break;
  }
  return false;
}

void VolumeOutputStream::advance_if_done(std::size_t size) {
  if (offset_ < size) return;
  part_ = static_cast<Part>(static_cast<int>(part_) + 1);
  offset_ = 0;
}

void VolumeOutputStream::next_points(v1::PointSlice& slice) {
  const std::vector<Point>& points = output_.volume.mesh.points;
  const std::size_t end = wire::slice_end(offset_, points.size());
  wire::encode_points(points, offset_, end, slice);
  offset_ = end;
}

void VolumeOutputStream::next_triangles(v1::TriangleSlice& slice) {
  const Mesh& mesh = output_.volume.mesh;
  const std::size_t end = wire::slice_end(offset_, mesh.triangles.size());
  wire::encode_triangles(mesh.triangles, mesh.triangle_tags, offset_, end, slice);
  offset_ = end;
}

void VolumeOutputStream::next_tets(v1::TetSlice& slice) {
  const Mesh& mesh = output_.volume.mesh;
  const std::size_t end = wire::slice_end(offset_, mesh.tets.size());
  wire::encode_tets(mesh.tets, mesh.tet_tags, offset_, end, slice);
  offset_ = end;
}

void VolumeOutputStream::fill_summary(v1::Summary& summary) const {
  const Mesh& mesh = output_.volume.mesh;
  summary.set_point_count(mesh.points.size());
  summary.set_triangle_count(mesh.triangles.size());
  summary.set_tet_count(mesh.tets.size());

  const VolumeQuality& quality = output_.quality;
  v1::QualityFigures& figures = *summary.mutable_quality();
  figures.set_min_dihedral_deg(quality.min_dihedral_deg);
  figures.set_max_dihedral_deg(quality.max_dihedral_deg);
  figures.set_share_below_10_deg(quality.share_below_10_deg);
  figures.set_share_below_20_deg(quality.share_below_20_deg);
  figures.set_min_radius_ratio(quality.min_radius_ratio);
  figures.set_mean_radius_ratio(quality.mean_radius_ratio);
  figures.set_boundary_min_angle_deg(quality.boundary_min_angle_deg);
  figures.set_boundary_sliver_count(static_cast<std::uint64_t>(quality.boundary_slivers));
  figures.set_tets_away_from_slivers(static_cast<std::uint64_t>(quality.tets_away_from_slivers));
  figures.set_min_dihedral_away_from_slivers_deg(quality.away_min_dihedral_deg);
  figures.set_share_away_from_slivers_below_20_deg(quality.away_share_below_20_deg);

  v1::Validation& validation = *summary.mutable_validation();
  validation.set_passed(output_.validation.passed);
  for (const std::string& message : output_.validation.messages) {
    validation.add_messages(message);
  }

  const FrontRepairReport& repair = output_.repair;
  v1::FrontRepair& repaired = *summary.mutable_repair();
  repaired.set_triangles_dropped(static_cast<std::uint64_t>(repair.triangles_dropped));
  repaired.set_triangles_reoriented(static_cast<std::uint64_t>(repair.triangles_reoriented));
  repaired.set_components(static_cast<std::uint64_t>(repair.components));
  repaired.set_cavities(static_cast<std::uint64_t>(repair.cavities));
  summary.set_estimated_tet_count(output_.estimated_tets);
  if (output_.surface) {
    summary.set_surface_remeshed(true);
    fill_surface_summary(*output_.surface, *summary.mutable_surface());
    add_timings(output_.surface->result.timings, *summary.mutable_surface());
  }
  add_timings(timings(), summary);
}

std::vector<StageTiming> VolumeOutputStream::timings() const {
  std::vector<StageTiming> all = timings_before_;
  all.insert(all.end(), output_.volume.timings.begin(), output_.volume.timings.end());
  const auto since = send_start_.value_or(std::chrono::steady_clock::now());
  all.push_back(
      {"send", std::chrono::duration<double>(std::chrono::steady_clock::now() - since).count()});
  return all;
}

}  // namespace afmesh::server
