#include "server/volume_input.h"

#include <cmath>
#include <cstddef>
#include <string>
#include <utility>

#include "absl/strings/str_cat.h"
#include "absl/strings/str_format.h"
#include "core/sizing/size_spec.h"
#include "proto/size_spec_convert.h"
#include "proto/slice_codec.h"

namespace afmesh::server {
namespace {

// "message 3" for the third message of the client stream (1-based, as a person counts).
std::string message_name(std::int64_t count) { return absl::StrCat("message ", count); }

// Checks options.size: max_size finite and > 0, growth 0 (meaning 1) or finite and >= 1; with
// sources, a background grid or `grid_streamed` (the grid comes in slices, attached at
// half-close), the whole specification (validate_size_spec) goes to the job in params.spec.
// Errors name the field under "options.size.".
absl::Status params_from_options(const v1::VolumeOptions& options, bool grid_streamed,
                                 VolumeParams& params) {
  const v1::SizeSpec& size = options.size();
  if (!std::isfinite(size.max_size()) || size.max_size() <= 0.0) {
    return absl::InvalidArgumentError(
        absl::StrFormat("options.size.max_size must be finite and > 0, got %g", size.max_size()));
  }
  const double growth = size.growth() == 0.0 ? 1.0 : size.growth();
  if (!std::isfinite(growth) || growth < 1.0) {
    return absl::InvalidArgumentError(absl::StrFormat(
        "options.size.growth must be finite and >= 1 (or 0 for 1), got %g", size.growth()));
  }
  params.size = size.max_size();
  params.growth = growth;
  if (options.has_max_reruns()) {
    if (options.max_reruns() < 0 || options.max_reruns() > kMaxLocalRefinements) {
      return absl::InvalidArgumentError(
          absl::StrFormat("options.max_reruns must be in [0, %d], got %d", kMaxLocalRefinements,
                          options.max_reruns()));
    }
    params.local_refinements = options.max_reruns();
  }
  if (size.sources_size() == 0 && !size.has_background() && !grid_streamed) {
    return absl::OkStatus();
  }
  absl::StatusOr<SizeSpec> spec = size_spec_from_proto(size);
  absl::Status status = spec.ok() ? validate_size_spec(*spec) : spec.status();
  if (!status.ok()) {
    return absl::InvalidArgumentError(absl::StrCat("options.size.", status.message()));
  }
  params.spec = *std::move(spec);
  return absl::OkStatus();
}

absl::Status over_limit(std::string_view what, std::uint64_t count, std::int64_t limit,
                        std::string_view flag) {
  return absl::ResourceExhaustedError(absl::StrFormat(
      "the input has %d %s, over this server's limit of %d (%s)", count, what, limit, flag));
}

// The grid limits on an inline options.size.background (it is small, being in the header, but
// the limits hold however the grid comes).
absl::Status check_inline_grid_limits(const v1::SizeSpec& size, const InputLimits& limits) {
  if (!size.has_background()) return absl::OkStatus();
  const auto points = static_cast<std::uint64_t>(size.background().points_size());
  const auto tets = static_cast<std::uint64_t>(size.background().tets_size() / 4);
  if (points > static_cast<std::uint64_t>(limits.max_grid_points)) {
    return over_limit("background grid points", points, limits.max_grid_points,
                      "--max-grid-points");
  }
  if (tets > static_cast<std::uint64_t>(limits.max_grid_tets)) {
    return over_limit("background grid tets", tets, limits.max_grid_tets, "--max-grid-tets");
  }
  return absl::OkStatus();
}

}  // namespace

absl::Status VolumeInput::add(const v1::MeshVolumeRequest& request) {
  ++message_count_;
  bytes_ += static_cast<std::int64_t>(request.ByteSizeLong());
  if (bytes_ > limits_.max_request_bytes) {
    return absl::ResourceExhaustedError(absl::StrFormat(
        "the request is over this server's limit of %d bytes (--max-request-mb) at %s",
        limits_.max_request_bytes, message_name(message_count_)));
  }
  switch (request.part_case()) {
    case v1::MeshVolumeRequest::kHeader:
      return add_header(request.header());
    case v1::MeshVolumeRequest::kPoints:
      return add_points(request.points());
    case v1::MeshVolumeRequest::kTriangles:
      return add_triangles(request.triangles());
    case v1::MeshVolumeRequest::kBackgroundGrid:
      return add_grid_slice(request.background_grid());
    case v1::MeshVolumeRequest::PART_NOT_SET:
      break;
  }
  return absl::InvalidArgumentError(absl::StrCat(
      message_name(message_count_), " is empty: set header, points, triangles or background_grid"));
}

absl::Status VolumeInput::add_header(const v1::MeshVolumeHeader& header) {
  if (has_header_) {
    return absl::InvalidArgumentError(
        absl::StrCat(message_name(message_count_), " is a second header; send exactly one, first"));
  }
  has_header_ = true;
  if (header.has_point_count()) {
    declared_points_ = header.point_count();
    if (*declared_points_ > static_cast<std::uint64_t>(limits_.max_points)) {
      return over_limit("points", *declared_points_, limits_.max_points, "--max-points");
    }
  }
  if (header.has_triangle_count()) {
    declared_triangles_ = header.triangle_count();
    if (*declared_triangles_ > static_cast<std::uint64_t>(limits_.max_triangles)) {
      return over_limit("triangles", *declared_triangles_, limits_.max_triangles,
                        "--max-triangles");
    }
  }
  if (header.has_grid_point_count() != header.has_grid_tet_count()) {
    return absl::InvalidArgumentError(absl::StrCat(
        "the header sets ", header.has_grid_point_count() ? "grid_point_count" : "grid_tet_count",
        " but not ", header.has_grid_point_count() ? "grid_tet_count" : "grid_point_count",
        ": set both to stream a background grid, or neither"));
  }
  const bool grid_streamed = header.has_grid_point_count();
  if (grid_streamed) {
    if (header.options().size().has_background()) {
      return absl::InvalidArgumentError(
          "the header declares a streamed background grid (grid_point_count, grid_tet_count) "
          "and also gives options.size.background: give the grid one way only");
    }
    declared_grid_points_ = header.grid_point_count();
    declared_grid_tets_ = header.grid_tet_count();
    if (*declared_grid_points_ > static_cast<std::uint64_t>(limits_.max_grid_points)) {
      return over_limit("background grid points", *declared_grid_points_,
                        limits_.max_grid_points, "--max-grid-points");
    }
    if (*declared_grid_tets_ > static_cast<std::uint64_t>(limits_.max_grid_tets)) {
      return over_limit("background grid tets", *declared_grid_tets_, limits_.max_grid_tets,
                        "--max-grid-tets");
    }
    grid_.points.reserve(*declared_grid_points_);
    grid_.sizes.reserve(*declared_grid_points_);
    grid_.tets.reserve(*declared_grid_tets_);
  }
  if (absl::Status status = check_inline_grid_limits(header.options().size(), limits_);
      !status.ok()) {
    return status;
  }
  const v1::EnvironmentMode mode = header.options().environments();
  if (!v1::EnvironmentMode_IsValid(mode)) {
    return absl::InvalidArgumentError(absl::StrFormat(
        "options.environments has the unknown value %d (known: ENVIRONMENT_MODE_NONE, "
        "ENVIRONMENT_MODE_TAGS, ENVIRONMENT_MODE_AUTO)",
        static_cast<int>(mode)));
  }
  environment_mode_ = mode;
  if (absl::Status status = params_from_options(header.options(), grid_streamed, params_);
      !status.ok()) {
    return status;
  }
  return surface_options(header.options());
}

// With remesh_surface, the angles of the surface step; without, none may be given.
absl::Status VolumeInput::surface_options(const v1::VolumeOptions& options) {
  remesh_surface_ = options.remesh_surface();
  angles_ = angles_of(options);
  if (!remesh_surface_) {
    if (!any_angle_given(angles_)) return absl::OkStatus();
    return absl::InvalidArgumentError(absl::StrFormat(
        "options.%s is set, but options.remesh_surface is not: the angles only apply when the "
        "surface is re-triangulated first",
        angles_.ridge_deg != 0.0            ? "ridge_angle_deg"
        : angles_.corner_deg != 0.0         ? "corner_angle_deg"
        : angles_.curvature_deg.has_value() ? "curvature_angle_deg"
        : angles_.curvature_deviation.has_value() ? "curvature_deviation"
                                                  : "wall_sizes"));
  }
  SurfaceParams checked = front_surface_defaults();
  return surface_params_from(params_, angles_, "options.", checked);
}

// The surface step re-triangulates a volume's front: its thin walls bounded by default.
SurfaceParams VolumeInput::front_surface_defaults() {
  SurfaceParams params;
  params.wall_sizes = kVolumeFrontWallSizes;
  return params;
}

SurfaceParams VolumeInput::surface_params() const {
  SurfaceParams params = front_surface_defaults();
  (void)surface_params_from(params_, angles_, "options.", params);
  return params;
}

absl::Status VolumeInput::add_points(const v1::PointSlice& slice) {
  if (!has_header_) {
    return absl::InvalidArgumentError(
        absl::StrCat(message_name(message_count_),
                     " is a points slice before the header; send the header first"));
  }
  const std::string where = message_name(message_count_);
  const absl::StatusOr<std::size_t> count = wire::point_count(slice, where);
  if (!count.ok()) return count.status();
  const std::uint64_t total = front_.points.size() + *count;
  if (total > static_cast<std::uint64_t>(limits_.max_points)) {
    return over_limit("points", total, limits_.max_points, "--max-points");
  }
  if (declared_points_ && total > *declared_points_) {
    return absl::InvalidArgumentError(
        absl::StrFormat("%s: %d points sent, more than the %d the header declared", where, total,
                        *declared_points_));
  }
  return wire::append_points(slice, where, front_.points);
}

absl::Status VolumeInput::add_triangles(const v1::TriangleSlice& slice) {
  if (!has_header_) {
    return absl::InvalidArgumentError(
        absl::StrCat(message_name(message_count_),
                     " is a triangles slice before the header; send the header first"));
  }
  const std::string where = message_name(message_count_);
  const absl::StatusOr<std::size_t> count = wire::triangle_count(slice, where);
  if (!count.ok()) return count.status();
  const std::uint64_t total = front_.triangles.size() + *count;
  if (total > static_cast<std::uint64_t>(limits_.max_triangles)) {
    return over_limit("triangles", total, limits_.max_triangles, "--max-triangles");
  }
  if (declared_triangles_ && total > *declared_triangles_) {
    return absl::InvalidArgumentError(
        absl::StrFormat("%s: %d triangles sent, more than the %d the header declared", where,
                        total, *declared_triangles_));
  }
  return wire::append_triangles(slice, where, front_.triangles, front_.triangle_tags);
}

absl::Status VolumeInput::add_grid_slice(const v1::BackgroundGridSlice& slice) {
  if (!has_header_) {
    return absl::InvalidArgumentError(
        absl::StrCat(message_name(message_count_),
                     " is a background_grid slice before the header; send the header first"));
  }
  if (!declared_grid_points_) {
    return absl::InvalidArgumentError(absl::StrCat(
        message_name(message_count_),
        " is a background_grid slice, but the header declares no streamed grid: set "
        "grid_point_count and grid_tet_count in the header"));
  }
  if (absl::Status status = add_grid_points(slice); !status.ok()) return status;
  if (absl::Status status = add_grid_sizes(slice); !status.ok()) return status;
  return add_grid_tets(slice);
}

absl::Status VolumeInput::add_grid_points(const v1::BackgroundGridSlice& slice) {
  const std::string where = message_name(message_count_);
  const absl::StatusOr<std::size_t> count = wire::grid_point_count(slice, where);
  if (!count.ok()) return count.status();
  const std::uint64_t total = grid_.points.size() + *count;
  if (total > *declared_grid_points_) {
    return absl::InvalidArgumentError(absl::StrFormat(
        "%s: %d background grid points sent, more than the %d the header declared "
        "(grid_point_count)",
        where, total, *declared_grid_points_));
  }
  return wire::append_grid_points(slice, where, grid_.points);
}

absl::Status VolumeInput::add_grid_sizes(const v1::BackgroundGridSlice& slice) {
  const std::uint64_t total = grid_.sizes.size() + static_cast<std::uint64_t>(slice.sizes_size());
  if (total > *declared_grid_points_) {
    return absl::InvalidArgumentError(absl::StrFormat(
        "%s: %d background grid sizes sent, more than the %d points the header declared "
        "(grid_point_count; one size per point)",
        message_name(message_count_), total, *declared_grid_points_));
  }
  return wire::append_grid_sizes(slice, grid_.sizes);
}

absl::Status VolumeInput::add_grid_tets(const v1::BackgroundGridSlice& slice) {
  const std::string where = message_name(message_count_);
  const absl::StatusOr<std::size_t> count = wire::grid_tet_count(slice, where);
  if (!count.ok()) return count.status();
  const std::uint64_t total = grid_.tets.size() + *count;
  if (total > *declared_grid_tets_) {
    return absl::InvalidArgumentError(absl::StrFormat(
        "%s: %d background grid tets sent, more than the %d the header declared "
        "(grid_tet_count)",
        where, total, *declared_grid_tets_));
  }
  return wire::append_grid_tets(slice, where, grid_.tets);
}

// The streamed grid is whole and valid (indices in range, positive tets: validate_background_grid,
// one exact orientation test per tet), then becomes the specification's background grid.
absl::Status VolumeInput::finish_grid() {
  if (!declared_grid_points_) return absl::OkStatus();
  const auto mismatch = [](std::string_view what, std::uint64_t declared, std::size_t sent,
                           std::string_view field) {
    return absl::InvalidArgumentError(
        absl::StrFormat("the header declared %d background grid %s (%s) but %d were sent",
                        declared, what, field, sent));
  };
  if (grid_.points.size() != *declared_grid_points_) {
    return mismatch("points", *declared_grid_points_, grid_.points.size(), "grid_point_count");
  }
  if (grid_.sizes.size() != *declared_grid_points_) {
    return absl::InvalidArgumentError(absl::StrFormat(
        "the header declared %d background grid points (grid_point_count), so as many sizes, "
        "but %d sizes were sent",
        *declared_grid_points_, grid_.sizes.size()));
  }
  if (grid_.tets.size() != *declared_grid_tets_) {
    return mismatch("tets", *declared_grid_tets_, grid_.tets.size(), "grid_tet_count");
  }
  if (absl::Status status = validate_background_grid(grid_, "background_grid"); !status.ok()) {
    return status;
  }
  params_.spec->background = std::move(grid_);
  grid_ = {};
  declared_grid_points_.reset();
  declared_grid_tets_.reset();
  return absl::OkStatus();
}

absl::Status VolumeInput::finish() {
  if (!has_header_) {
    return absl::InvalidArgumentError("the request stream ended without a header");
  }
  if (front_.points.empty()) return absl::InvalidArgumentError("the input has no points");
  if (front_.triangles.empty()) return absl::InvalidArgumentError("the input has no triangles");
  if (declared_points_ && front_.points.size() != *declared_points_) {
    return absl::InvalidArgumentError(absl::StrFormat(
        "the header declared %d points but %d were sent", *declared_points_, front_.points.size()));
  }
  if (declared_triangles_ && front_.triangles.size() != *declared_triangles_) {
    return absl::InvalidArgumentError(
        absl::StrFormat("the header declared %d triangles but %d were sent", *declared_triangles_,
                        front_.triangles.size()));
  }
  if (absl::Status status = check_indices(); !status.ok()) return status;
  if (absl::Status status = check_environment_tags(); !status.ok()) return status;
  return finish_grid();
}

// With environments from tags, the tags must be environment ids: none negative, some positive.
// Cheap, so checked here rather than on a worker.
absl::Status VolumeInput::check_environment_tags() const {
  if (environment_mode_ != v1::ENVIRONMENT_MODE_TAGS) return absl::OkStatus();
  bool any_positive = false;
  for (std::size_t t = 0; t < front_.triangle_tags.size(); ++t) {
    const Index tag = front_.triangle_tags[t];
    if (tag < 0) {
      return absl::InvalidArgumentError(absl::StrFormat(
          "triangle %d has tag %d, but with options.environments = ENVIRONMENT_MODE_TAGS tags "
          "are crossing-environment ids and must be >= 0 (0 = none)",
          t, tag));
    }
    any_positive = any_positive || tag > 0;
  }
  if (!any_positive) {
    return absl::InvalidArgumentError(absl::StrFormat(
        "options.environments is ENVIRONMENT_MODE_TAGS (--envs tags), but none of the %d "
        "triangles carries a positive tag: there are no environments to read; tag the "
        "triangles on each side of a thin region with an environment id > 0, or use "
        "ENVIRONMENT_MODE_AUTO (--envs auto)",
        front_.triangles.size()));
  }
  return absl::OkStatus();
}

// Indices are checked at the end since points and triangles may arrive interleaved.
absl::Status VolumeInput::check_indices() const {
  const auto point_count = static_cast<std::int64_t>(front_.points.size());
  for (std::size_t t = 0; t < front_.triangles.size(); ++t) {
    for (int corner = 0; corner < 3; ++corner) {
      const Index index = front_.triangles[t][corner];
      if (index >= point_count) {
        return absl::InvalidArgumentError(absl::StrFormat(
            "triangle %d refers to point %d (corner %d), but the input has %d points "
            "(indices are 0-based)",
            t, index, corner, point_count));
      }
    }
  }
  return absl::OkStatus();
}

}  // namespace afmesh::server
