// VTK XML UnstructuredGrid (.vtu) writing, for viewing meshes in ParaView and reading them with
// meshio. Write-only: afmesh does not read .vtu.
//
// The file is ascii (points as shortest round-trip doubles, so coordinates are exact): Points
// (Float64 N×3), Cells with connectivity (Int32, 0-based), offsets (Int64) and types (UInt8:
// 5 = triangle, 10 = tetrahedron; triangles first, then tetrahedra), and CellData "tag"
// (Int32: triangle_tags then tet_tags). VTK's reader opens every such file; meshio 5 cannot
// read one without cells (a mesh of points only), whatever it holds.
#pragma once

#include "absl/status/status.h"
#include "core/io/output_buffer.h"
#include "core/mesh/mesh.h"

namespace afmesh {

// Writes `mesh` (points N×3, triangles M×3, tets K×4, with tags) as .vtu to `out` and flushes it.
absl::Status write_vtu(const Mesh& mesh, OutputBuffer& out);

}  // namespace afmesh
