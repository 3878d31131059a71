#include "client/spec_file.h"

#include <filesystem>
#include <fstream>
#include <iterator>
#include <optional>
#include <utility>

#include "absl/strings/str_cat.h"
#include "core/io/sized_grid.h"
#include "proto/size_spec_convert.h"

namespace afmesh::cli {
namespace {

// `file` as named in the specification at `spec_path`: relative to the specification's folder.
std::string resolve_beside(const std::string& spec_path, const std::string& file) {
  const std::filesystem::path named(file);
  if (named.is_absolute()) return file;
  return (std::filesystem::path(spec_path).parent_path() / named).string();
}

// The grid in the file that `grid.file` names, as an inline background grid.
absl::StatusOr<BackgroundGridSpec> read_background_file(const std::string& spec_path,
                                                        const v1::BackgroundGrid& grid,
                                                        ReadReport* report) {
  if (grid.points_size() > 0 || grid.tets_size() > 0 || grid.sizes_size() > 0) {
    return absl::InvalidArgumentError(
        absl::StrCat("background gives both a file (\"", grid.file(),
                     "\") and an inline grid (points, tets or sizes); give one of them"));
  }
  absl::StatusOr<SizedGrid> read = read_sized_grid(resolve_beside(spec_path, grid.file()), report);
  if (!read.ok()) {
    return absl::InvalidArgumentError(
        absl::StrCat("background.file (\"", grid.file(), "\"): ", read.status().message()));
  }
  return BackgroundGridSpec{.points = std::move(read->mesh.points),
                            .tets = std::move(read->mesh.tets),
                            .sizes = std::move(read->sizes)};
}

}  // namespace

absl::StatusOr<SizeSpec> read_size_spec_file(const std::string& path, ReadReport* report) {
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    return absl::InvalidArgumentError(absl::StrCat(path, ": cannot open the size specification"));
  }
  const std::string json(std::istreambuf_iterator<char>(in), {});
  if (in.bad()) {
    return absl::InvalidArgumentError(absl::StrCat(path, ": cannot read the size specification"));
  }
  absl::StatusOr<v1::SizeSpec> message = size_spec_proto_from_json(json);
  if (!message.ok()) {
    return absl::InvalidArgumentError(
        absl::StrCat(path, ": not a size specification (protobuf JSON of afmesh.v1.SizeSpec): ",
                     message.status().message()));
  }
  std::optional<BackgroundGridSpec> from_file;
  if (message->has_background() && !message->background().file().empty()) {
    absl::StatusOr<BackgroundGridSpec> grid =
        read_background_file(path, message->background(), report);
    if (!grid.ok()) {
      return absl::InvalidArgumentError(absl::StrCat(path, ": ", grid.status().message()));
    }
    from_file = *std::move(grid);
    message->clear_background();
  }
  absl::StatusOr<SizeSpec> spec = size_spec_from_proto(*message);
  if (!spec.ok())
    return absl::InvalidArgumentError(absl::StrCat(path, ": ", spec.status().message()));
  if (from_file) spec->background = *std::move(from_file);
  return spec;
}

}  // namespace afmesh::cli
