// Whole-file reading and writing for the mesh readers and writers.
#pragma once

#include <string>
#include <string_view>

#include "absl/status/status.h"
#include "absl/status/statusor.h"

namespace afmesh {

// The complete contents of the file at `path`. Errors (NOT_FOUND, PERMISSION_DENIED, ...) name
// the path and the system's reason.
absl::StatusOr<std::string> read_file_bytes(const std::string& path);

// An error for the failed file operation `action` ("open", "write") on `path`, from errno.
absl::Status file_error(std::string_view action, const std::string& path, int error_number);

}  // namespace afmesh
