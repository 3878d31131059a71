// SurfaceParams from the wire's options, shared by MeshSurface (SurfaceOptions) and MeshVolume
// with remesh_surface (VolumeOptions' ridge, corner and curvature angles and curvature deviation).
#pragma once

#include <optional>
#include <string_view>

#include "absl/status/status.h"
#include "afmesh/v1/mesher.pb.h"
#include "core/surface/generate_surface_mesh.h"
#include "core/volume/generate_volume_mesh.h"

namespace afmesh::server {

// The surface step's angles as the wire gives them: ridge and corner 0 for their default,
// curvature unset for its default (0 is "no curvature bound"); with them the curvature's
// deviation bound (a fraction of the model size; unset for its default, 0 for none).
struct SurfaceAngles {
  double ridge_deg = 0.0;
  double corner_deg = 0.0;
  std::optional<double> curvature_deg;
  std::optional<double> curvature_deviation;
  // Elements per wall thickness (SurfaceParams::wall_sizes; unset for its default, 0 for none).
  std::optional<double> wall_sizes;
};
SurfaceAngles angles_of(const v1::SurfaceOptions& options);
SurfaceAngles angles_of(const v1::VolumeOptions& options);
// True when any angle, the deviation or the wall sizes are given (not their default).
bool any_angle_given(const SurfaceAngles& angles);

// `params` with the size of `size` (its size, growth and specification, already checked by
// VolumeInput) and `angles`; what `angles` leaves unset keeps the value `params` comes with (its
// default: SurfaceParams', or kVolumeFrontWallSizes for a volume's front). INVALID_ARGUMENT naming
// "<prefix>ridge_angle_deg" outside (0, 180), "<prefix>corner_angle_deg" outside (0, 180] or
// "<prefix>curvature_angle_deg" outside [0, 180), "<prefix>curvature_deviation" outside [0, 1)
// or "<prefix>wall_sizes" outside [0, 100).
absl::Status surface_params_from(const VolumeParams& size, const SurfaceAngles& angles,
                                 std::string_view prefix, SurfaceParams& params);

}  // namespace afmesh::server
