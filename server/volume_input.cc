#include "server/volume_input.h"

#include <cmath>
#include <cstddef>
#include <string>
#include <utility>

#include "absl/strings/str_cat.h"
#include "absl/strings/str_format.h"
#include "core/sizing/size_spec.h"
#include "proto/size_spec_convert.h"

namespace afmesh::server {
namespace {

// "message 3" for the third message of the client stream (1-based, as a person counts).
std::string message_name(std::int64_t count) { return absl::StrCat("message ", count); }

// Checks options.size: max_size finite and > 0, growth 0 (meaning 1) or finite and >= 1; with
// sources or a background grid, the whole specification (validate_size_spec) goes to the job in
// params.spec. Errors name the field under "options.size.".
absl::Status params_from_options(const v1::VolumeOptions& options, VolumeParams& params) {
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
  if (size.sources_size() == 0 && !size.has_background()) return absl::OkStatus();
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

}  // namespace

absl::Status VolumeInput::add(const v1::MeshVolumeRequest& request) {
  ++message_count_;
  switch (request.part_case()) {
    case v1::MeshVolumeRequest::kHeader:
      return add_header(request.header());
    case v1::MeshVolumeRequest::kPoints:
      return add_points(request.points());
    case v1::MeshVolumeRequest::kTriangles:
      return add_triangles(request.triangles());
    case v1::MeshVolumeRequest::PART_NOT_SET:
      break;
  }
  return absl::InvalidArgumentError(
      absl::StrCat(message_name(message_count_), " is empty: set header, points or triangles"));
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
  const v1::EnvironmentMode mode = header.options().environments();
  if (!v1::EnvironmentMode_IsValid(mode)) {
    return absl::InvalidArgumentError(absl::StrFormat(
        "options.environments has the unknown value %d (known: ENVIRONMENT_MODE_NONE, "
        "ENVIRONMENT_MODE_TAGS, ENVIRONMENT_MODE_AUTO)",
        static_cast<int>(mode)));
  }
  environment_mode_ = mode;
  return params_from_options(header.options(), params_);
}

absl::Status VolumeInput::add_points(const v1::PointSlice& slice) {
  if (!has_header_) {
    return absl::InvalidArgumentError(
        absl::StrCat(message_name(message_count_),
                     " is a points slice before the header; send the header first"));
  }
  const int size = slice.xyz_size();
  if (size % 3 != 0) {
    return absl::InvalidArgumentError(
        absl::StrFormat("%s: points slice has %d coordinates, not a multiple of 3",
                        message_name(message_count_), size));
  }
  const std::size_t first = front_.points.size();
  const std::uint64_t total = first + static_cast<std::uint64_t>(size / 3);
  if (total > static_cast<std::uint64_t>(limits_.max_points)) {
    return over_limit("points", total, limits_.max_points, "--max-points");
  }
  if (declared_points_ && total > *declared_points_) {
    return absl::InvalidArgumentError(
        absl::StrFormat("%s: %d points sent, more than the %d the header declared",
                        message_name(message_count_), total, *declared_points_));
  }
  for (int i = 0; i < size; i += 3) {
    const Point p = {slice.xyz(i), slice.xyz(i + 1), slice.xyz(i + 2)};
    for (int axis = 0; axis < 3; ++axis) {
      if (!std::isfinite(p[axis])) {
        return absl::InvalidArgumentError(
            absl::StrFormat("point %d has a non-finite coordinate %c = %g", front_.points.size(),
                            "xyz"[axis], p[axis]));
      }
    }
    front_.points.push_back(p);
  }
  return absl::OkStatus();
}

absl::Status VolumeInput::add_triangles(const v1::TriangleSlice& slice) {
  if (!has_header_) {
    return absl::InvalidArgumentError(
        absl::StrCat(message_name(message_count_),
                     " is a triangles slice before the header; send the header first"));
  }
  const int size = slice.indices_size();
  if (size % 3 != 0) {
    return absl::InvalidArgumentError(
        absl::StrFormat("%s: triangles slice has %d indices, not a multiple of 3",
                        message_name(message_count_), size));
  }
  const int count = size / 3;
  if (slice.tags_size() != 0 && slice.tags_size() != count) {
    return absl::InvalidArgumentError(
        absl::StrFormat("%s: triangles slice has %d tags for %d triangles (send none or one "
                        "per triangle)",
                        message_name(message_count_), slice.tags_size(), count));
  }
  const std::uint64_t total = front_.triangles.size() + static_cast<std::uint64_t>(count);
  if (total > static_cast<std::uint64_t>(limits_.max_triangles)) {
    return over_limit("triangles", total, limits_.max_triangles, "--max-triangles");
  }
  if (declared_triangles_ && total > *declared_triangles_) {
    return absl::InvalidArgumentError(
        absl::StrFormat("%s: %d triangles sent, more than the %d the header declared",
                        message_name(message_count_), total, *declared_triangles_));
  }
  for (int t = 0; t < count; ++t) {
    const Triangle triangle = {slice.indices(3 * t), slice.indices(3 * t + 1),
                               slice.indices(3 * t + 2)};
    for (int corner = 0; corner < 3; ++corner) {
      if (triangle[corner] < 0) {
        return absl::InvalidArgumentError(
            absl::StrFormat("triangle %d has a negative point index %d (corner %d)",
                            front_.triangles.size(), triangle[corner], corner));
      }
    }
    front_.triangles.push_back(triangle);
    front_.triangle_tags.push_back(slice.tags_size() == 0 ? 0 : slice.tags(t));
  }
  return absl::OkStatus();
}

absl::Status VolumeInput::finish() const {
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
  return check_environment_tags();
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
