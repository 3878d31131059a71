// How many elements a volume job will make, known before it runs: what the server checks its
// limits against (--max-elements, the memory budget) and what the front reserves and reports
// progress by.
//
// Not in the paper. The count is the integral over the enclosed domain of one over the volume of
// the element the size field asks for, plus the layer along the boundary where the elements grow
// from the front's own edges to that size (eq. 15 with the growth of generate_volume_mesh.h).
#pragma once

#include <cstdint>

#include "core/mesh/mesh.h"
#include "absl/status/statusor.h"
#include "core/sizing/size_field.h"
#include "core/volume/generate_volume_mesh.h"

namespace afmesh {

struct VolumeEstimate {
  double tets = 0;    // expected tetrahedra
  double points = 0;  // expected points, the front's included
  double bytes = 0;   // expected peak memory of the job
  // Front triangles whose mean edge is over kCoarseFrontRatio times the size asked on them, and
  // the largest such ratio. Not in the paper: a face's element is 0.55 to 1.6 times its edges
  // (candidates.cc), so the elements on such triangles are coarser than asked, and gaps narrower
  // than their edges may not close; the surface must be re-triangulated at the size first.
  std::int64_t coarse_front_triangles = 0;
  double coarsest_front_ratio = 0;
};

inline constexpr double kCoarseFrontRatio = 3.0;

// The expected size of the mesh of the closed front `front` (outward oriented) with sizes from
// `size_field`, none above `max_size`, growing by `growth` (>= 1; below 1.2 counts as 1.2, as
// the front does). Reads every triangle once and the size field at up to about 2^18 points, so
// it costs far less than meshing: O(M + 2^18) for M triangles. Within 2x of the real count on the
// bench shapes (tests/volume/estimate_elements_test.cc); meant for limits, not for exact counts.
// A front that is not closed gets a number, not a meaning.
VolumeEstimate estimate_volume_mesh(const Mesh& front, const SizeField& size_field,
                                    double max_size, double growth);

// The same for a job's parameters: params.size and params.growth, or params.spec's sources,
// background grid, max_size and growth. The size specification's error when it has one.
absl::StatusOr<VolumeEstimate> estimate_volume_mesh(const Mesh& front, const VolumeParams& params);

}  // namespace afmesh
