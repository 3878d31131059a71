// Repairs of the input's sliver triangles before its features are found (not in the paper;
// generate_surface_mesh.h, steps 1 and 2). Each keeps the surface manifold where it was, moves
// it by a measured distance the report gives, and drops the points left on no face.
#pragma once

#include <cstdint>
#include <span>

#include "core/mesh/mesh.h"
#include "core/surface/discrete_surface.h"

namespace afmesh {

// Each folded face of `clean` (folded_faces in features.h) whose shortest edge is under
// kFoldedSliverEdgeRatio of its longest loses that edge: the two faces on it are dropped and one
// end takes the other's place in its other faces, the end that turns none of them by 90° or
// more (neither end: the face stays, and a surface that follows it may cross itself there,
// explain_stuck then names it). Only where the two ends have no neighbour in common but the
// edge's two opposite corners, so that the surface stays manifold. The points left on no face
// are dropped. Returns how many faces lost an edge and the longest edge they lost; `clean`'s
// points and triangles (with their tags) change together.
inline constexpr double kFoldedSliverEdgeRatio = 0.1;

struct FoldedCollapses {
  std::int64_t count = 0;
  double longest_edge = 0.0;
};

FoldedCollapses collapse_folded_slivers(Mesh& clean, std::span<const FaceId> folded);

}  // namespace afmesh
