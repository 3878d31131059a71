// The best triangulation of the ring polygon of an edge, for edge removal (Shewchuk, "Two
// discrete optimization algorithms for the topological improvement of tetrahedral meshes", 2002,
// §2: removing edge ab replaces the n tets around it by 2(n - 2) tets, two per triangle of a
// triangulation of its ring r_0 .. r_{n-1}; Klincsek's dynamic programme finds the triangulation
// that maximises the smallest quality in O(n^3) evaluations).
#pragma once

#include <array>
#include <limits>
#include <vector>

#include "absl/functional/function_ref.h"

namespace afmesh {

// Largest ring handled (n), a bound on the dynamic programme's fixed tables.
inline constexpr int kMaxRingSize = 12;

struct RingTriangulation {
  // Smallest triangle quality of the best triangulation; -infinity when every triangulation
  // has a triangle of quality -infinity (an unusable triangle) or n is out of range.
  double quality = -std::numeric_limits<double>::infinity();
  // The n - 2 triangles (i, j, k) with i < j < k ring positions, in a fixed order (the
  // programme's recursion order); empty when quality is -infinity.
  std::vector<std::array<int, 3>> triangles;
};

// Best triangulation of the polygon with corners 0 .. n-1 (3 <= n <= kMaxRingSize):
// maximises min over its triangles of quality(i, j, k), called with i < j < k and at most once
// per triple. Return -infinity from `quality` for a triangle that must not be used. Ties go to
// the smaller apex k of the sub-polygon's base (i, j), so the result is deterministic.
RingTriangulation best_ring_triangulation(int n,
                                          absl::FunctionRef<double(int, int, int)> quality);

}  // namespace afmesh
