#include "server/surface_options.h"

#include <cmath>
#include <optional>
#include <string_view>

#include "absl/strings/str_format.h"

namespace afmesh::server {

namespace {

// SurfaceOptions and VolumeOptions carry the same three angle fields, the deviation and the
// wall sizes.
template <typename Options>
SurfaceAngles angles_in(const Options& options) {
  SurfaceAngles angles;
  angles.ridge_deg = options.ridge_angle_deg();
  angles.corner_deg = options.corner_angle_deg();
  if (options.has_curvature_angle_deg()) angles.curvature_deg = options.curvature_angle_deg();
  if (options.has_curvature_deviation())
    angles.curvature_deviation = options.curvature_deviation();
  if (options.has_wall_sizes()) angles.wall_sizes = options.wall_sizes();
  return angles;
}

// An optional bound of the surface options: unset keeps the default, 0 turns it off, and
// otherwise it lies in [0, upper).
struct OptionalBound {
  std::string_view field;
  double upper;
  std::string_view units;
  std::string_view zero_means;
  double default_value;
};

absl::Status check_optional_bound(const std::optional<double>& value, std::string_view prefix,
                                  const OptionalBound& bound) {
  if (!value || (std::isfinite(*value) && *value >= 0.0 && *value < bound.upper))
    return absl::OkStatus();
  return absl::InvalidArgumentError(absl::StrFormat(
      "%s%s must be in [0, %g) %s (0: %s; unset: %g), got %g", prefix, bound.field, bound.upper,
      bound.units, bound.zero_means, bound.default_value, *value));
}

}  // namespace

SurfaceAngles angles_of(const v1::SurfaceOptions& options) { return angles_in(options); }

SurfaceAngles angles_of(const v1::VolumeOptions& options) { return angles_in(options); }

bool any_angle_given(const SurfaceAngles& angles) {
  return angles.ridge_deg != 0.0 || angles.corner_deg != 0.0 || angles.curvature_deg.has_value() ||
         angles.curvature_deviation.has_value() || angles.wall_sizes.has_value();
}

absl::Status surface_params_from(const VolumeParams& size, const SurfaceAngles& angles,
                                 std::string_view prefix, SurfaceParams& params) {
  const double ridge = angles.ridge_deg, corner = angles.corner_deg;
  if (ridge != 0.0 && !(std::isfinite(ridge) && ridge > 0.0 && ridge < 180.0)) {
    return absl::InvalidArgumentError(
        absl::StrFormat("%sridge_angle_deg must be in (0, 180) degrees (or 0 for %g), got %g",
                        prefix, SurfaceParams{}.ridge_angle_deg, ridge));
  }
  if (corner != 0.0 && !(std::isfinite(corner) && corner > 0.0 && corner <= 180.0)) {
    return absl::InvalidArgumentError(
        absl::StrFormat("%scorner_angle_deg must be in (0, 180] degrees (or 0 for %g), got %g",
                        prefix, SurfaceParams{}.corner_angle_deg, corner));
  }
  if (absl::Status st = check_optional_bound(angles.curvature_deg, prefix,
                                              {"curvature_angle_deg", 180.0, "degrees",
                                               "no curvature bound",
                                               SurfaceParams{}.curvature_angle_deg});
      !st.ok())
    return st;
  if (absl::Status st = check_optional_bound(
          angles.curvature_deviation, prefix,
          {"curvature_deviation", 1.0, "of the bounding-box diagonal", "no deviation bound",
           SurfaceParams{}.curvature_deviation});
      !st.ok())
    return st;
  if (absl::Status st = check_optional_bound(
          angles.wall_sizes, prefix,
          {"wall_sizes", 100.0, "wall thicknesses", "no wall bound", params.wall_sizes});
      !st.ok())
    return st;
  params.size = size.size;
  params.growth = size.growth;
  params.spec = size.spec;
  if (ridge != 0.0) params.ridge_angle_deg = ridge;
  if (corner != 0.0) params.corner_angle_deg = corner;
  if (angles.curvature_deg) params.curvature_angle_deg = *angles.curvature_deg;
  if (angles.curvature_deviation) params.curvature_deviation = *angles.curvature_deviation;
  if (angles.wall_sizes) params.wall_sizes = *angles.wall_sizes;
  return absl::OkStatus();
}

}  // namespace afmesh::server
