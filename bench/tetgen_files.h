// tetgen's piecewise linear complex input files, written from a closed triangulated surface so
// that tetgen (`tetgen -pY ...`) meshes the same front as afmesh and the other peers.
//
//   .smesh  nodes inline, then one line per triangle:  3 a b c marker
//   .poly   nodes, then one facet per triangle:         1 0 marker / 3 a b c
//
// Both list nodes 1-based ("index x y z", coordinates as the shortest decimal text that reads
// back to the same double), carry the triangle tags as facet boundary markers, and declare no
// holes and no regions (tetgen then meshes the region enclosed by the facets).
// Errors: the file cannot be created or written (the message names the path).
#pragma once

#include <string>

#include "absl/status/status.h"
#include "core/mesh/mesh.h"

namespace afmesh::bench {

// Writes `surface` (points N×3, triangles M×3, triangle_tags M) as a tetgen .smesh file.
absl::Status write_tetgen_smesh(const Mesh& surface, const std::string& path);

// Writes `surface` (points N×3, triangles M×3, triangle_tags M) as a tetgen .poly file.
absl::Status write_tetgen_poly(const Mesh& surface, const std::string& path);

}  // namespace afmesh::bench
