// Conversion between the wire / JSON size specification (afmesh.v1.SizeSpec, mesher.proto) and
// core's afmesh::SizeSpec (core/sizing/size_spec.h): the one place both the server and the CLI
// turn one into the other.
#pragma once

#include <string_view>

#include "absl/status/statusor.h"
#include "afmesh/v1/mesher.pb.h"
#include "core/sizing/size_spec.h"

namespace afmesh {

// Converts `message` field by field: growth 0 (unset) becomes 1; a source without a law gets
// NoLaw (which validate_size_spec rejects); `background` becomes the inline grid, tets taken four
// indices at a time. Checks only what the conversion needs, with errors naming the JSON field
// (callers prefix their context, e.g. "options.size."):
//  - INVALID_ARGUMENT "background.file ...": a file name cannot be converted (servers never
//    open client paths); the client reads the file (client/spec_file.cc) and sends the grid
//    (the CLI streams it in background_grid slices, client/volume_call.cc);
//  - INVALID_ARGUMENT "background.tets ...": the index count is not a multiple of 4.
// Values are not checked: run validate_size_spec on the result before using it.
absl::StatusOr<SizeSpec> size_spec_from_proto(const v1::SizeSpec& message);

// The wire form of `spec` (an inline background grid; NoLaw leaves the law unset):
// size_spec_from_proto(size_spec_to_proto(spec)) == spec.
v1::SizeSpec size_spec_to_proto(const SizeSpec& spec);

// Parses the protobuf JSON form of the message (design.md, "Size specification"). Unknown fields
// (e.g. a misspelt law) and malformed JSON are INVALID_ARGUMENT with protobuf's message.
absl::StatusOr<v1::SizeSpec> size_spec_proto_from_json(std::string_view json);

}  // namespace afmesh
