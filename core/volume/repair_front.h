// F1 for fronts as real files bring them (not in the paper, which assumes a clean front): the
// defects of a closed triangulated surface that can be repaired without guessing, repaired before
// the front is checked (validate_front) and meshed.
//
// Steps, in order:
//  1. Triangles that repeat a point ((a, a, b): no area, no edge of their own) are dropped, when
//     the rest of the surface stays closed and manifold without them.
//  2. Each edge-connected component of a closed, edge-manifold surface is oriented consistently:
//     a breadth-first walk over the edges carries the orientation from triangle to triangle; of
//     the two orientations a component can take, the one that turns fewer triangles is kept.
//  3. Each component is then turned to face out of the domain, by nesting: a component inside an
//     even number of others (0: an outer wall) must enclose a positive volume, one inside an odd
//     number (a cavity) a negative one. Nesting is decided by the winding number of a point of
//     the component about each other component, and only where it is unambiguous.
// What cannot be repaired without guessing (open or non-manifold edges, a non-orientable
// component, crossing components) is left as it is, for validate_front to refuse by name.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "core/mesh/mesh.h"

namespace afmesh {

struct FrontRepairReport {
  std::int64_t triangles_dropped = 0;     // step 1: triangles that repeated a point
  std::int64_t triangles_reoriented = 0;  // steps 2-3: triangles whose orientation was turned
  std::int64_t components = 0;            // edge-connected components (0 when not examined)
  std::int64_t cavities = 0;              // components that face inward (nested an odd number)
  std::int64_t components_turned = 0;     // step 3: components turned whole to face outward
  // Steps 2-3 were skipped: the surface had open or non-manifold edges, or a component could
  // not be oriented; `skipped_because` says which.
  std::string skipped_because;
  // Step 1 was skipped: triangles that repeat a point, kept because without them the surface
  // would still not be closed and manifold (`triangle_sides_unpaired` triangle sides without
  // exactly one neighbour across them). validate_front then refuses the repeated points first.
  std::int64_t repeated_points_kept = 0;
  std::int64_t triangle_sides_unpaired = 0;

  bool changed() const { return triangles_dropped > 0 || triangles_reoriented > 0; }
  // One line per change, for the user (empty when nothing changed).
  std::vector<std::string> notes() const;
  // Why triangles that repeat a point were not dropped, for the refusal that follows (empty
  // unless repeated_points_kept > 0).
  std::string why_repeated_points_kept() const;
};

// Repairs `front` in place (points unchanged; triangles and triangle_tags dropped or re-oriented
// together, in their order). Indices must be in range and coordinates finite (the caller's
// input check); anything else is not looked at. With `neighbours`, it is set to the edge
// neighbours of the repaired triangles (triangle_edge_neighbours' answer, from the adjacency the
// repair built, its re-oriented triangles' slots turned) when steps 2-3 ran, and left empty when
// they were skipped: a caller that needs them too does not group the edges again.
struct EdgeNeighbours;  // core/quality/mesh_topology.h
FrontRepairReport repair_front(Mesh& front, EdgeNeighbours* neighbours = nullptr);

}  // namespace afmesh
