// Element sizes from the gaps between discrete lines (paper §4.2, sizes attached to the
// geometry: "assigning to the end-points of lines a point size that is related to the minimum
// length of the lines surrounding it"; the gap across a patch is our measure of it).
//
// A patch narrower than the size between two of its lines (a chamfer, the side of a thin plate,
// a gear tooth's flank) can only be meshed with slivers if its lines are split at the size: the
// triangles span the strip from one line to the other. So each input vertex on a line takes as
// its size the width of the gap across to the nearest facing edge of another line, or of the
// same line where it turns back (a slot's rim), of a patch the two share: an edge within 30° of
// parallel to the line at the vertex, whose nearest point lies across (the vector to it at least
// 60° from the line's direction) and nearer than the size there, but not below 0.15 of that
// size. Not in the paper beyond the quotation above. The sizes are graded with the others (grade_point_sizes in curvature_sizes.h).
#pragma once

#include <vector>

#include "core/sizing/size_field.h"
#include "core/surface/discrete_surface.h"
#include "core/surface/features.h"

namespace afmesh {

// A gap takes the size down to this fraction of the size field's at most: lines that nearly
// touch (a dirty input's crossing, a sliver patch of a CAD tessellation) would otherwise ask
// for elements without bound (of_cyclone ran out of memory). 0.15: on the corpus at the mean
// edge, 0.1 leaves bones stuck and 0.2 or more gmsh_t13_data; the CAD parts keep 99.3% or more
// of their triangles at 30° from 0.1 to 0.25. The thickness of walls (wall_sizes.h) takes the
// size no lower either, for the same reasons (walls that touch, a wedge's edge).
inline constexpr double kMinGapSizes = 0.15;

// delta_i for every input point of `surface` (N values): the gap width at the vertices on lines
// where a facing line is nearer than `field`'s size there, +infinity elsewhere. O(L) bin queries
// for L line edges, each visiting the line edges within the size.
std::vector<double> line_gap_sizes(const DiscreteSurface& surface, const SurfaceFeatures& features,
                                   const SizeField& field);

}  // namespace afmesh
