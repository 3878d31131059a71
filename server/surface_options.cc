#include "server/surface_options.h"

#include <cmath>

#include "absl/strings/str_format.h"

namespace afmesh::server {

absl::Status surface_params_from(const VolumeParams& size, double ridge_angle_deg,
                                 double corner_angle_deg, std::string_view prefix,
                                 SurfaceParams& params) {
  if (ridge_angle_deg != 0.0 &&
      !(std::isfinite(ridge_angle_deg) && ridge_angle_deg > 0.0 && ridge_angle_deg < 180.0)) {
    return absl::InvalidArgumentError(absl::StrFormat(
        "%sridge_angle_deg must be in (0, 180) degrees (or 0 for %g), got %g", prefix,
        SurfaceParams{}.ridge_angle_deg, ridge_angle_deg));
  }
  if (corner_angle_deg != 0.0 &&
      !(std::isfinite(corner_angle_deg) && corner_angle_deg > 0.0 && corner_angle_deg <= 180.0)) {
    return absl::InvalidArgumentError(absl::StrFormat(
        "%scorner_angle_deg must be in (0, 180] degrees (or 0 for %g), got %g", prefix,
        SurfaceParams{}.corner_angle_deg, corner_angle_deg));
  }
  params.size = size.size;
  params.growth = size.growth;
  params.spec = size.spec;
  if (ridge_angle_deg != 0.0) params.ridge_angle_deg = ridge_angle_deg;
  if (corner_angle_deg != 0.0) params.corner_angle_deg = corner_angle_deg;
  return absl::OkStatus();
}

}  // namespace afmesh::server
