// Crossing environments of a front (paper §2, "Thin/crossing surfaces").
//
// Where the two sides of a thin structure (a shell, membrane, sail, cusped trailing edge) come
// very close or cross, the faces on each side are marked with a crossing environment id, LFACR
// (one per face), and the points with LPOCR (one per point). The volume front then filters by
// them (paper §2 (a), (b)): for a face of environment k, points of any other positive
// environment are not candidates, and only faces of environment k or 0 enter the crossing
// checks. This module computes the marks; the front uses them (core/volume).
//
// Values:
//   LFACR: 0 = the face belongs to no environment; k > 0 = environment k. Never negative.
//   LPOCR: 0 = none; k > 0 = environment k; kSharedEnvironment (-1) = the point lies on faces of
//          two or more different positive environments (a ridge where two sides meet, paper
//          Figure 4).
//
// Where the marks come from:
//   - tags (environments_from_tags): LFACR = the triangle's tag (Medit triangle reference, Gmsh
//     physical tag), the paper's "marking the different surface patches ... before the surface
//     grid is generated";
//   - automatically (detect_environments.h): the paper's "checking the initial front for
//     crossing faces".
#pragma once

#include <algorithm>
#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "absl/status/statusor.h"
#include "core/mesh/mesh.h"

namespace afmesh {

inline constexpr std::int32_t kNoEnvironment = 0;
inline constexpr std::int32_t kSharedEnvironment = -1;

// The crossing environments of a front's faces and points.
struct FrontEnvironments {
  std::vector<std::int32_t> face;   // LFACR, M (one per front triangle), each >= 0
  std::vector<std::int32_t> point;  // LPOCR, N (one per front point), each >= -1
};

// LPOCR from LFACR (paper §2: "the points are marked according to the environment variable of
// the faces surrounding them"). For each of `point_count` points, over the triangles using it:
//   - no face of a positive environment        -> 0;
//   - faces of exactly one positive environment k -> k, whatever other faces of environment 0
//     it also touches: a point on the surface of environment k belongs to k even where that
//     surface meets unmarked faces (its rim on a symmetry plane, say), so the filter of §2 (a)
//     keeps it away from the other side;
//   - faces of two or more positive environments -> kSharedEnvironment (-1), the ridge points;
//   - and kSharedEnvironment for every point of a face of environment 0 whose points (by the
//     rules above) belong to two different positive environments: a strip closing a plate's rim
//     between its two sides is where they meet, as the shared rim points are (not in the paper).
// Points that no triangle uses get 0. `triangles` (M×3) must have indices in [0, point_count),
// `face_environments` has M entries (negative entries count as environment 0 here; callers
// validate them first).
std::vector<std::int32_t> point_environments(std::size_t point_count,
                                             const std::vector<Triangle>& triangles,
                                             std::span<const std::int32_t> face_environments);

// True when some triangle tag of `mesh` is positive (the mesh carries environment ids).
bool has_positive_tags(const Mesh& mesh);

// LFACR from the triangle tags of `front` (tag = environment id, 0 = none) and LPOCR from them.
// INVALID_ARGUMENT when a tag is negative (naming the first such triangle and its tag), when
// triangle_tags does not have one entry per triangle, when an index is out of range, or when
// no tag is positive (there is nothing to mark; the message says so).
absl::StatusOr<FrontEnvironments> environments_from_tags(const Mesh& front);

// Number of distinct positive environments in `face_environments`.
int count_environments(std::span<const std::int32_t> face_environments);

// The filters of paper §2 as a front applies them, for faces of the volume front and sides of
// the surface front alike. `point_env` is LPOCR of the front's first points (the input points;
// empty when the input has no environments); points past its end are new points, LPOCR 0.

// LPOCR of point q.
inline std::int32_t point_environment(std::span<const std::int32_t> point_env, Index q) {
  return static_cast<std::size_t>(q) < point_env.size() ? point_env[q] : kNoEnvironment;
}

// §2 (a): an item (face or side) of environment `env` ignores the points of any other positive
// environment. An item of no environment (its points all new) ignores them too: a point of
// environment k is reached only from the items of k's side, which are the items touching k's
// surface. Without this, a face off a thin shell connects to the other side's points where the
// two surfaces cross, its new faces take that side's environment and, blind to this side's
// faces, cross them.
inline bool point_visible(std::span<const std::int32_t> point_env, Index env, Index q) {
  const std::int32_t e = point_environment(point_env, q);
  return e <= 0 || e == env;
}

// §2 (b): only items of the item's own environment or of none enter its crossing checks; an
// item of no environment checks against all.
inline bool item_visible(Index env, Index other_env) {
  return env <= 0 || other_env == kNoEnvironment || other_env == env;
}

// §2: a new item takes LFACR = max(0, LPOCR of its points).
template <std::size_t N>
Index item_environment(std::span<const std::int32_t> point_env, const std::array<Index, N>& v) {
  Index env = kNoEnvironment;
  for (const Index p : v) env = std::max<Index>(env, point_environment(point_env, p));
  return env;
}

}  // namespace afmesh
