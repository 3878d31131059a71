// Element sizes from the thickness of the solid a surface bounds (not in the paper).
//
// A surface re-triangulated to be a volume mesher's front (`afmesh volume --remesh-surface`,
// or `afmesh surface` then `afmesh volume`) must not be coarser than the walls it bounds are
// thick: a tetrahedron that spans a wall an eighth of its size is flat whatever the volume
// mesher does (cgal_rotor: a blade 0.003–0.004 thick under surface triangles of 0.025 left the
// volume's smallest dihedral angle at 14.96°, every tet under 18° on the blade). The paper's
// §4.2 attaches sizes to the geometry (curvature, the lengths of the lines around a point);
// this is one more such size, the volume's own.
//
// The thickness at an input face is the distance from its centroid to the nearest face behind
// it: a face whose normal is within 60° of the opposite of its own and whose nearest point lies
// within 60° of its inward direction (the solid is behind an outward surface, so the opposite
// wall of a plate, a blade or a shell is found, and the far side of a slot, which is outside, is
// not). Faces, not vertices: a CAD tessellation of a thin blade has points on its rim only,
// where the two sheets' normals cancel, and faces 70 times longer than the blade is thick
// (cgal_rotor). Only faces nearer than the size in force are looked for: a wall thicker than the
// size needs no size of its own. The face's corners take `per_thickness` times that thickness
// as their size (the smallest over their faces), but not less than kMinGapSizes (0.15, the
// floor of the gaps between lines, gap_sizes.h) of the size in force: where two walls meet at a
// sharp edge (a blade's tip, a wedge) the thickness falls to zero, and a dirty input's walls may
// touch. The search reaches no farther than 3 of the face's longest edges (a scan far finer
// than the size would otherwise visit hundreds of faces per face): a wall thicker than 3 of its
// faces keeps the size. The sizes are graded with the others (grade_point_sizes,
// curvature_sizes.h).
#pragma once

#include <vector>

#include "absl/status/statusor.h"
#include "core/common/progress.h"
#include "core/sizing/size_field.h"
#include "core/surface/discrete_surface.h"

namespace afmesh {

// delta_i for every input point of `surface` (N values): per_thickness times the wall's
// thickness where it is under the size of `field` there (global frame), +infinity elsewhere.
// per_thickness > 0. The surface's AABB tree must be built (has_tree()). O(M) tree queries,
// each visiting the faces within the size or 3 of the face's longest edges, whichever is
// nearer (kMaxReachInEdges). CANCELLED soon after progress.cancelled() turns true.
absl::StatusOr<std::vector<double>> wall_thickness_sizes(const DiscreteSurface& surface,
                                                         double per_thickness,
                                                         const SizeField& field,
                                                         Progress& progress = no_progress());

}  // namespace afmesh
