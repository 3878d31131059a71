// STL (stereolithography) reading and writing, ascii and binary.
//
// Reading
//  - The encoding is decided from the bytes, not the name: a file whose size is exactly
//    84 + 50 n (n = the triangle count at byte 80) is binary unless its first kilobyte is text
//    starting with "solid"; a text file starting with "solid" is ascii. Binary files whose
//    header happens to begin with "solid" are therefore read as binary.
//  - Corners with bit-identical coordinates become one point (-0.0 equals +0.0; no tolerance),
//    so a closed cube of 12 triangles reads as 8 points.
//  - Tags: ascii files may hold several `solid ... endsolid` blocks; each triangle's tag is the
//    1-based ordinal of its solid in the file (names are not kept). Binary STL has no solids:
//    every tag is 0. Facet normals and the binary attribute bytes are ignored.
//  - Errors (INVALID_ARGUMENT) name the source and the line (ascii) or byte offset (binary):
//    truncated data, size not matching the declared count, non-finite coordinates, garbage.
//
// Writing
//  - Binary (default): 80-byte header (never starting with "solid"), coordinates rounded to
//    float, normals computed from the corners, attribute 0. Tags are not stored.
//  - Ascii: shortest round-trip doubles (bit-exact), one `solid tag_<n>` block per run of
//    consecutive triangles with equal tag n (read back, those runs get tags 1, 2, ...).
//  - A mesh with tetrahedra is refused (STL holds triangles only).
#pragma once

#include <string_view>

#include "absl/status/status.h"
#include "absl/status/statusor.h"
#include "core/io/output_buffer.h"
#include "core/io/read_report.h"
#include "core/mesh/mesh.h"

namespace afmesh {

enum class StlEncoding { kBinary, kAscii };

// The mesh in the STL file whose complete contents are `bytes`; `source_name` (the path) starts
// error messages. Notes on merged and degenerate corners go to `report` when not null.
absl::StatusOr<Mesh> parse_stl(std::string_view bytes, std::string_view source_name,
                               ReadReport* report = nullptr);

// Writes the triangles of `mesh` (points N×3, triangles M×3) as STL to `out` and flushes it.
// INVALID_ARGUMENT when the mesh has tetrahedra or fails check_mesh_for_writing.
absl::Status write_stl(const Mesh& mesh, StlEncoding encoding, OutputBuffer& out);

}  // namespace afmesh
