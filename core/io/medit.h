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
#pragma once

#include <string_view>

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

}  // namespace afmesh
