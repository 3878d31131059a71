// SurfaceParams from the wire's options, shared by MeshSurface (SurfaceOptions) and MeshVolume
// with remesh_surface (VolumeOptions' ridge and corner angles).
#pragma once

#include <string_view>

#include "absl/status/status.h"
#include "core/surface/generate_surface_mesh.h"
#include "core/volume/generate_volume_mesh.h"

namespace afmesh::server {

// `params` with the size of `size` (its size, growth and specification, already checked by
// VolumeInput) and the two angles, 0 meaning SurfaceParams' default. INVALID_ARGUMENT naming
// "<prefix>ridge_angle_deg" outside (0, 180) or "<prefix>corner_angle_deg" outside (0, 180].
absl::Status surface_params_from(const VolumeParams& size, double ridge_angle_deg,
                                 double corner_angle_deg, std::string_view prefix,
                                 SurfaceParams& params);

}  // namespace afmesh::server
