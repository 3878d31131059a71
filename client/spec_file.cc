#include "client/spec_file.h"

#include <fstream>
#include <iterator>

#include "absl/strings/str_cat.h"
#include "proto/size_spec_convert.h"

namespace afmesh::cli {

absl::StatusOr<SizeSpec> read_size_spec_file(const std::string& path) {
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
    return absl::InvalidArgumentError(absl::StrCat(
        path, ": not a size specification (protobuf JSON of afmesh.v1.SizeSpec): ",
        message.status().message()));
  }
  absl::StatusOr<SizeSpec> spec = size_spec_from_proto(*message);
  if (!spec.ok()) return absl::InvalidArgumentError(absl::StrCat(path, ": ", spec.status().message()));
  return spec;
}

}  // namespace afmesh::cli
