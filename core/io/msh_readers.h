// The version-specific halves of parse_msh (internal to core/io). Each reads the sections that
// follow $MeshFormat until the end of the text, into `builder`.
#pragma once

#include "absl/status/status.h"
#include "core/io/msh_common.h"
#include "core/io/text_scanner.h"

namespace afmesh::msh {

// MSH 4.1, ascii or binary (`binary`: 8-byte size_t, little-endian, as gmsh writes it).
absl::Status read_msh41_sections(TextScanner& scanner, bool binary, MeshBuilder& builder);

// MSH 2.0 to 2.2, ascii.
absl::Status read_msh2_sections(TextScanner& scanner, MeshBuilder& builder);

}  // namespace afmesh::msh
