// Reading a size-specification file (`--spec SPEC.json`): the protobuf JSON form of
// afmesh.v1.SizeSpec (design.md, "Size specification").
#pragma once

#include <string>

#include "absl/status/statusor.h"
#include "core/sizing/size_spec.h"

namespace afmesh::cli {

// The specification in the JSON file at `path`, converted to core's form (not yet validated:
// callers may override maxSize / growth first, then run validate_size_spec). INVALID_ARGUMENT,
// with the path first, when the file cannot be read, is not valid JSON for the message (with
// protobuf's message, e.g. an unknown law), or names a background file (not supported yet).
absl::StatusOr<SizeSpec> read_size_spec_file(const std::string& path);

}  // namespace afmesh::cli
