// Assembles the client stream of a MeshVolume call (header, point slices, triangle slices,
// background grid slices) into a core Mesh and VolumeParams, checking everything that is cheap
// to check before any meshing work: stream order, slice shapes, options, finite coordinates,
// size limits, declared counts, non-empty input, indices in range and the streamed background
// grid (one exact orientation test per tet). Every error names the message, element or limit.
// Topological checks of the front (closed, oriented, no degenerate triangle) are the job's
// (afmesh::validate_front), since they cost more than a pass over the arrays.
#pragma once

#include <cstdint>
#include <optional>

#include "absl/status/status.h"
#include "afmesh/v1/mesher.pb.h"
#include "core/mesh/mesh.h"
#include "core/sizing/size_spec.h"
#include "core/surface/generate_surface_mesh.h"
#include "core/volume/generate_volume_mesh.h"
#include "server/surface_options.h"

namespace afmesh::server {

// The server's size limits on one request (flags --max-points, --max-triangles,
// --max-grid-points, --max-grid-tets, --max-request-mb, --max-elements; the grid limits count a
// background grid inline or streamed).
struct InputLimits {
  std::int64_t max_points = 10'000'000;
  std::int64_t max_triangles = 20'000'000;
  std::int64_t max_grid_points = 10'000'000;
  std::int64_t max_grid_tets = 60'000'000;
  // Bytes of all the request's messages together, as encoded on the wire.
  std::int64_t max_request_bytes = std::int64_t{2} << 30;
  // Tetrahedra the size field may ask for, by the estimate made before meshing
  // (core/volume/estimate_elements.h); checked by the service, not by VolumeInput.
  std::int64_t max_elements = 100'000'000;
};

class VolumeInput {
 public:
  explicit VolumeInput(const InputLimits& limits) : limits_(limits) {}

  // Takes the next client message. INVALID_ARGUMENT for a malformed stream or bad values,
  // RESOURCE_EXHAUSTED when the input goes over a limit. After an error the input is unusable.
  absl::Status add(const v1::MeshVolumeRequest& request);

  // Checks the whole input at half-close: a header was sent, points and triangles are present,
  // counts match the header's, every index is in range; with ENVIRONMENT_MODE_TAGS, no tag is
  // negative and some tag is positive. A streamed background grid must match its declared
  // counts and pass validate_background_grid (errors name "background_grid..."); it then
  // becomes params().spec->background.
  absl::Status finish();

  const VolumeParams& params() const { return params_; }
  // options.remesh_surface of the header: re-triangulate the front first, with
  // surface_params() (the size of params() and the header's angles and curvature deviation,
  // checked when it came: INVALID_ARGUMENT naming options.ridge_angle_deg / corner_angle_deg /
  // curvature_angle_deg / curvature_deviation, or any given without options.remesh_surface).
  // The surface's wall sizes are kVolumeFrontWallSizes unless the header sets them.
  bool remesh_surface() const { return remesh_surface_; }
  SurfaceParams surface_params() const;
  // options.environments of the header (crossing environments, paper §2).
  v1::EnvironmentMode environment_mode() const { return environment_mode_; }
  // The assembled front (N×3 points, M×3 triangles, M tags); leaves this input empty.
  Mesh take_front() { return std::move(front_); }

 private:
  absl::Status add_header(const v1::MeshVolumeHeader& header);
  absl::Status surface_options(const v1::VolumeOptions& options);
  static SurfaceParams front_surface_defaults();
  absl::Status add_points(const v1::PointSlice& slice);
  absl::Status add_triangles(const v1::TriangleSlice& slice);
  absl::Status add_grid_slice(const v1::BackgroundGridSlice& slice);
  absl::Status add_grid_points(const v1::BackgroundGridSlice& slice);
  absl::Status add_grid_tets(const v1::BackgroundGridSlice& slice);
  absl::Status add_grid_sizes(const v1::BackgroundGridSlice& slice);
  absl::Status finish_grid();
  absl::Status check_indices() const;
  absl::Status check_environment_tags() const;

  InputLimits limits_;
  std::int64_t message_count_ = 0;  // messages taken so far, for error messages
  std::int64_t bytes_ = 0;          // their encoded size
  bool has_header_ = false;
  std::optional<std::uint64_t> declared_points_;
  std::optional<std::uint64_t> declared_triangles_;
  // Set when the header declares a streamed background grid (grid_point_count, grid_tet_count).
  std::optional<std::uint64_t> declared_grid_points_;
  std::optional<std::uint64_t> declared_grid_tets_;
  BackgroundGridSpec grid_;  // the streamed grid, so far
  VolumeParams params_;
  bool remesh_surface_ = false;
  SurfaceAngles angles_;  // options' ridge, corner and curvature angles, checked
  v1::EnvironmentMode environment_mode_ = v1::ENVIRONMENT_MODE_NONE;
  Mesh front_;
};

}  // namespace afmesh::server
