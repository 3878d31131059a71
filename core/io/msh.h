// Gmsh MSH reading (4.1 ascii and binary, 2.x ascii) and writing (4.1 ascii).
//
// Reading
//  - Nodes may be spread over any number of entity blocks with arbitrary, non-contiguous node
//    tags; points come out in file order and element node tags are mapped to point indices.
//  - Elements of type 2 (3-node triangle) and 4 (4-node tetrahedron) are read; type 15 (point)
//    and 1 (2-node line) are passed over and counted in a note; any other type (second order,
//    quadrangles, hexahedra, prisms, pyramids, ...) is an error naming the type.
//  - Tags: an element's tag is the physical tag of its entity (4.1: from $Entities; 2.x: the
//    element's first tag), 0 when it has none. An entity with several physical tags gives the
//    first (as meshio does), with a note.
//  - Elements come back in increasing element-tag order (gmsh's global numbering), so a mesh
//    written by write_msh reads back in its original order even though the file groups
//    elements by tag.
//  - Sections other than $MeshFormat, $Entities, $Nodes, $Elements are skipped (with a note,
//    except $Comments); $PartitionedEntities is an error (partitioned meshes are not read).
//    MSH 4.0, 3 and binary 2.x are errors saying which versions are read.
//  - $NodeData is skipped with a note by parse_msh. parse_msh_sized_grid reads the first
//    $NodeData view as a size per node (a background grid): it must have one component and give
//    every node of $Nodes exactly one finite size > 0; unknown node tags, a wrong count, a
//    missing view or a bad size are errors naming the line (or byte offset). Later views are
//    skipped with a note.
//  - Malformed input is INVALID_ARGUMENT naming the source and the line (ascii) or byte offset
//    (binary): wrong counts, unknown node tags, non-finite coordinates, truncation, garbage.
//
// Writing (MSH 4.1 ascii, readable by gmsh and meshio)
//  - One surface entity per distinct triangle tag and one volume entity per distinct tet tag,
//    numbered 1, 2, ... in increasing tag order. Every such entity carries exactly one physical
//    tag, the tag of its elements, and untagged elements (tag 0) carry physical tag 0: gmsh
//    reads them as physical group 0 (and keeps them when it saves the mesh), meshio as
//    gmsh:physical 0, this reader as tag 0. Tags must be >= 0. (An entity without a physical
//    tag next to tagged ones would make meshio 5 refuse the file: it keeps gmsh:physical only
//    for blocks that have one, and the arrays lose step with the blocks.) A mesh of points
//    only gets one empty surface entity with no physical tag; meshio 5 cannot read a file
//    with no node at all, whatever it holds.
//  - All nodes in one block (tags 1..N in point order, coordinates as shortest round-trip
//    doubles); element tags 1..M for triangles in order, then M+1..M+K for tets.
//  - write_msh_sized_grid appends one $NodeData view "size" (time 0, step 0, one component,
//    tag i+1 -> sizes[i]), which gmsh opens as a post-processing view of the mesh.
#pragma once

#include <span>
#include <string_view>

#include "absl/status/status.h"
#include "absl/status/statusor.h"
#include "core/io/output_buffer.h"
#include "core/io/read_report.h"
#include "core/io/sized_grid.h"
#include "core/mesh/mesh.h"

namespace afmesh {

// The mesh in the MSH file whose complete contents are `bytes`; `source_name` starts errors.
absl::StatusOr<Mesh> parse_msh(std::string_view bytes, std::string_view source_name,
                               ReadReport* report = nullptr);

// The mesh and the sizes of its first $NodeData view in the MSH file `bytes` (see above).
absl::StatusOr<SizedGrid> parse_msh_sized_grid(std::string_view bytes,
                                               std::string_view source_name,
                                               ReadReport* report = nullptr);

// Writes `mesh` (points N×3, triangles M×3, tets K×4, with tags) as MSH 4.1 ascii to `out` and
// flushes it.
absl::Status write_msh(const Mesh& mesh, OutputBuffer& out);

// write_msh, then `sizes` (N, one per point, finite and > 0) as a $NodeData view.
absl::Status write_msh_sized_grid(const Mesh& mesh, std::span<const double> sizes,
                                  OutputBuffer& out);

}  // namespace afmesh
