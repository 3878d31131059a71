// Mesh files: read and write a Mesh by path, the format chosen by the file extension.
//
//   extension   format                     read                     write
//   .stl        STL                        ascii + binary           binary (default) or ascii
//   .obj        Wavefront OBJ              triangles, groups        yes
//   .msh        Gmsh MSH                   4.1 ascii/binary, 2.2    4.1 ascii
//   .mesh       Medit (ascii)              yes                      yes
//   .vtu        VTK XML UnstructuredGrid   no                       ascii
//
// How tags travel and what each reader passes over is documented in the per-format headers
// (stl.h, obj.h, msh.h, medit.h, vtu.h), which also read from and write to memory. Background
// grids with a size per point (MSH $NodeData, Medit .mesh + .sol) are read by sized_grid.h.
//
// Errors: NOT_FOUND / PERMISSION_DENIED / ... when a file cannot be opened or written (with the
// path and the system's reason); INVALID_ARGUMENT for an unknown extension, malformed content
// (with the path and the line or byte offset) or a mesh the format cannot hold (tetrahedra in
// STL or OBJ); UNIMPLEMENTED for reading .vtu. A failed write removes the partial file.
#pragma once

#include <string>
#include <string_view>

#include "absl/status/status.h"
#include "absl/status/statusor.h"
#include "core/io/read_report.h"
#include "core/mesh/mesh.h"

namespace afmesh {

enum class MeshFormat { kStl, kObj, kMsh, kMedit, kVtu };

// The format named by the extension of `path` (.stl .obj .msh .mesh .vtu, any letter case);
// INVALID_ARGUMENT naming the path and the supported extensions otherwise.
absl::StatusOr<MeshFormat> format_from_path(std::string_view path);

// Reads the mesh at `path`. Anything in the file that does not become part of the mesh is
// described in `report->notes` when `report` is not null.
absl::StatusOr<Mesh> read_mesh(const std::string& path, ReadReport* report = nullptr);

struct WriteOptions {
  // STL only: binary (true; coordinates rounded to float, no tags) or ascii (false; exact
  // coordinates, one solid per run of equal tags). MSH is always written as 4.1 ascii.
  bool binary_stl = true;
};

// Writes `mesh` (points N×3, triangles M×3, tets K×4, tags) to `path`, replacing the file.
// The mesh is checked before the file is created (indices in range, tag arrays as long as their
// element arrays, finite coordinates, what the format can hold).
absl::Status write_mesh(const Mesh& mesh, const std::string& path,
                        const WriteOptions& options = {});

}  // namespace afmesh
