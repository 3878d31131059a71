// Background-grid files: a tetrahedral mesh with one size per point (paper §4, delta_bg of
// eq. 15), read by the CLI for a size specification's `background.file` and written for tests
// and tools.
//
//   extension  mesh                                       sizes
//   .msh       Gmsh MSH 4.1 (ascii, binary) or 2.2 ascii  the first $NodeData view (msh.h)
//   .mesh      Medit ascii (medit.h)                      SolAtVertices of the ascii .sol with
//                                                         the same stem beside it (medit.h)
//
// Errors: NOT_FOUND / PERMISSION_DENIED / ... when a file cannot be opened (with the path and the
// system's reason); INVALID_ARGUMENT for another extension, a binary .solb, malformed content
// (the path and line, or byte offset, and what was expected), sizes that are missing, not one
// per point, not finite or not > 0, or a file without tetrahedra. The tets' orientation and
// conformity are not checked here: validate_background_grid (core/sizing) does that.
#pragma once

#include <span>
#include <string>
#include <vector>

#include "absl/status/status.h"
#include "absl/status/statusor.h"
#include "core/io/read_report.h"
#include "core/mesh/mesh.h"

namespace afmesh {

// A mesh with a size at each point.
struct SizedGrid {
  Mesh mesh;                  // points N×3, tets K×4 (read_sized_grid: no triangles)
  std::vector<double> sizes;  // N: sizes[i] at mesh.points[i], finite and > 0
};

// The grid in the file at `path` (.msh, or .mesh with its .sol): its points, tets (with their
// tags) and sizes. Triangles in the file are dropped with a note in `report`.
absl::StatusOr<SizedGrid> read_sized_grid(const std::string& path, ReadReport* report = nullptr);

// Writes `mesh` with `sizes` (N, one per point, finite and > 0) to `path`: .msh (MSH 4.1 ascii
// with a $NodeData view "size"), or .mesh and the .sol of the same stem beside it. A failed write
// removes what it created.
absl::Status write_sized_grid(const Mesh& mesh, std::span<const double> sizes,
                              const std::string& path);

// The .sol file read with the Medit grid `mesh_path`: the same path with the extension .sol.
std::string medit_sol_path(const std::string& mesh_path);

}  // namespace afmesh
