// A fill of a closed front by a tetrahedralisation of given points that has every front triangle
// as a face, not in the paper.
//
// The volume front (F1–F11) can fail among sliver input triangles (a CAD tessellation's fans of
// needles, thin lenses along faceted walls: issue 10 part 3) however often it is meshed again.
// TetGen meshes such fronts as given (-pY) from a Delaunay tetrahedralisation of the front's
// points whose missing boundary triangles it recovers by flips. This does the same with the
// points given (the front's, and interior points the front placed before it failed): the Delaunay
// tetrahedralisation of all of them (delaunay_3d.h), the front's triangles recovered by flips
// and, where flips fail, by refilling cavities with Steiner points inside (recover_faces.h, as
// TetGen -Y adds Steiner points inside, never on the boundary), and the elements on the inner
// side of the front kept (those reached from an element on a triangle's inner side without
// crossing a front triangle).
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "absl/status/statusor.h"
#include "core/common/progress.h"
#include "core/mesh/mesh.h"

namespace afmesh {

// The work a fill is given per front triangle, in element-triangle tests of the flips
// (recover_faces_by_flips): by generate_volume_mesh for a whole front, by conforming_fill for a
// region of a cavity filled as a front of its own.
inline constexpr std::int64_t kFillTestsPerTriangle = 200;

// A fill: the points added inside (Steiner points, numbered after the given points) and the
// elements on the given points followed by those.
struct ConformingFill {
  std::vector<Point> steiner;
  std::vector<Tet> tets;
};

// The positive elements filling the region enclosed by `front` (closed, outward-oriented triangles
// of `points`), on `points` and any Steiner points, each front triangle a face of exactly one of
// them (on its inner side). Points beyond the front's corners lying outside the region are left
// out (no element kept uses them); none may lie on the front.
// Triangles the flips cannot recover are recovered by refilling their cavities
// (recover_faces_by_cavities, which adds Steiner points; a region no point sees whole is filled as
// a front of its own, two levels deep at most). Points inside near a triangle still missing are
// left out and the whole is tried again, and a third time with the front's corners alone: a point
// in the ball about a triangle keeps it from being a Delaunay face.
// FAILED_PRECONDITION when a triangle cannot be recovered (flips within `max_tests`
// element-triangle tests per try, recover_faces_by_flips, then cavities), or when the elements on
// the two sides of the front cannot be told apart (a region reached from both sides);
// INVALID_ARGUMENT when a point is not finite or two front corners coincide; CANCELLED once
// progress.cancelled() turns true (asked between the steps and during the flips and the cavities;
// not during a Delaunay tetrahedralisation).
absl::StatusOr<ConformingFill> conforming_fill(std::span<const Point> points,
                                               std::span<const Triangle> front,
                                               std::int64_t max_tests,
                                               Progress& progress = no_progress());

}  // namespace afmesh
