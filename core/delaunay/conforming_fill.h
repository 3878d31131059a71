// A fill of a closed front by a tetrahedralisation of given points that has every front triangle
// as a face, not in the paper.
//
// The volume front (F1–F11) can fail among sliver input triangles (a CAD tessellation's fans of
// needles, thin lenses along faceted walls: issue 10 part 3) however often it is meshed again.
// TetGen meshes such fronts as given (-pY) from a Delaunay tetrahedralisation of the front's
// points whose missing boundary triangles it recovers by flips. This does the same with the
// points given (the front's, and interior points the front placed before it failed): the Delaunay
// tetrahedralisation of all of them (delaunay_3d.h), the front's triangles recovered by flips
// (recover_faces.h, no new points), and the elements on the inner side of the front kept (those
// reached from an element on a triangle's inner side without crossing a front triangle).
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "absl/status/statusor.h"
#include "core/common/progress.h"
#include "core/mesh/mesh.h"

namespace afmesh {

// The positive elements filling the region enclosed by `front` (closed, outward-oriented
// triangles of `points`), on `points` only, each front triangle a face of exactly one of them
// (on its inner side). The points beyond the front's corners must lie inside the region.
// Points inside near a triangle the flips cannot recover are left out and the whole is tried
// again (three tries in all): a point in the ball about a triangle keeps it from
// being a Delaunay face. FAILED_PRECONDITION when a triangle cannot be recovered within
// `max_tests` element-triangle tests in all (recover_faces_by_flips), or when the elements on
// the two sides of the front cannot be told apart (a region reached from both sides);
// INVALID_ARGUMENT when a point is not finite or two front corners coincide; CANCELLED once
// progress.cancelled() turns true (asked between the steps and during the flips; not during a
// Delaunay tetrahedralisation).
absl::StatusOr<std::vector<Tet>> conforming_fill(std::span<const Point> points,
                                                 std::span<const Triangle> front,
                                                 std::int64_t max_tests,
                                                 Progress& progress = no_progress());

}  // namespace afmesh
