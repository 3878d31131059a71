// Reading a size-specification file (`--spec SPEC.json`): the protobuf JSON form of
// afmesh.v1.SizeSpec (design.md, "Size specification").
#pragma once

#include <string>

#include "absl/status/statusor.h"
#include "core/io/read_report.h"
#include "core/sizing/size_spec.h"

namespace afmesh::cli {

// The specification in the JSON file at `path`, converted to core's form (not yet validated:
// callers may override maxSize / growth first, then run validate_size_spec).
//
// A `background.file` is read here, by the client: its path is relative to the folder of the
// JSON file (unless absolute), a .msh with a $NodeData view or a .mesh with its .sol
// (core/io/sized_grid.h), and it becomes the background grid (points, tets, sizes) that
// `afmesh volume` streams to the server in background_grid slices; servers never open client
// paths. What the grid reader passed over is
// added to `report` when not null.
//
// INVALID_ARGUMENT, with the JSON file's path first, when the file cannot be read, is not valid
// JSON for the message (with protobuf's message, e.g. an unknown law), gives both a background
// file and an inline grid, or names a background file that cannot be read or is malformed (the
// grid file's path and line follow).
absl::StatusOr<SizeSpec> read_size_spec_file(const std::string& path,
                                             ReadReport* report = nullptr);

}  // namespace afmesh::cli
