// The boundary_match check of validate_volume_mesh (see validate.h): do the tets' boundary
// faces equal a given boundary mesh's triangles? Internal to core/quality.
#pragma once

#include "core/mesh/mesh.h"
#include "core/quality/mesh_topology.h"
#include "core/quality/validate.h"

namespace afmesh {

// Compares `faces` (the boundary faces of mesh.tets) with boundary.triangles as oriented
// vertex triples with multiplicity, matching points by index when boundary.points are the
// first points of mesh.points and by exact coordinates otherwise. Findings, in unoriented key
// order: boundary triangles missing from the tets' boundary, tet faces not in the boundary
// mesh, and pairs that match only with opposite orientation. A boundary mesh with indices out
// of range or non-finite coordinates fails with findings naming them.
Check check_boundary_match(const Mesh& mesh, const BoundaryFaces& faces, const Mesh& boundary,
                           const ValidationParams& params);

}  // namespace afmesh
