// Medit / Gamma Mesh Format (.mesh), ascii: the format of tetgen -g, mmg and many solvers.
//
// Reading
//  - `MeshVersionFormatted v` (v = 1..4; the ascii text is the same for all) must come first,
//    then `Dimension 3`, then sections, each a keyword, a count and that many entries, and
//    finally `End`. Keywords ignore case; `#` starts a comment.
//  - `Vertices` (x y z ref; the vertex references are read and dropped, with a note when any is
//    nonzero), `Triangles` (a b c ref -> triangle_tags), `Tetrahedra` (a b c d ref -> tet_tags).
//    Indices are 1-based and must be in [1, #vertices]; `Vertices` must precede the elements.
//  - Passed over with a note: Edges, Corners, Ridges, Required{Vertices,Edges,Triangles,
//    Tetrahedra}, Normals, NormalAtVertices, NormalAtTriangleVertices, Tangents,
//    TangentAtVertices. Other element sections (Quadrilaterals, Hexahedra, Prisms, Pyramids,
//    P2 elements) and unknown keywords are errors naming the line.
//  - A count larger than the entries present, or smaller, a missing `End`, a non-finite
//    coordinate or a bad index is an error naming the file and line.
//
// Writing: MeshVersionFormatted 2 (double precision: readers such as meshio read version 1 as
// float), Dimension 3, Vertices with ref 0, Triangles and Tetrahedra with their tags, End.
//
// Solution files (.sol, ascii; the sizes of a background grid, beside its .mesh): the same
// header, then `SolAtVertices`, the vertex count, `1 1` (one solution, of type 1: a scalar) and
// one value per vertex in vertex order, then `End`. The reader wants exactly that: one
// SolAtVertices section with one scalar per vertex of the mesh, each finite and > 0; other
// keywords, other solution types (vectors, metrics), a wrong count or a bad value are errors
// naming the line. Binary .solb files are not read.
#pragma once

#include <cstddef>
#include <span>
#include <string_view>
#include <vector>

#include "absl/status/status.h"
#include "absl/status/statusor.h"
#include "core/io/output_buffer.h"
#include "core/io/read_report.h"
#include "core/mesh/mesh.h"

namespace afmesh {

// The mesh in the Medit text `text`; `source_name` starts error messages.
absl::StatusOr<Mesh> parse_medit(std::string_view text, std::string_view source_name,
                                 ReadReport* report = nullptr);

// Writes `mesh` (points N×3, triangles M×3, tets K×4, with tags) as Medit ascii to `out` and
// flushes it.
absl::Status write_medit(const Mesh& mesh, OutputBuffer& out);

// The sizes in the Medit solution text `text` of a mesh with `num_vertices` vertices (see above).
absl::StatusOr<std::vector<double>> parse_medit_sol(std::string_view text,
                                                    std::string_view source_name,
                                                    std::size_t num_vertices);

// Writes `sizes` (one per vertex, finite and > 0) as a Medit ascii .sol to `out` and flushes it.
absl::Status write_medit_sol(std::span<const double> sizes, OutputBuffer& out);

}  // namespace afmesh
