// Plain mesh data shared by every core module: points, triangles, tetrahedra and their tags.
//
// Arrays are row-major and contiguous (a std::vector of fixed-size rows is an N×3 / M×3 / K×4
// array in memory). Indices are 0-based int32 (`Index`); `kInvalidIndex` marks "none".
//
// Orientation conventions (used by every module):
//  - A tetrahedron (a, b, c, d) is positive when det[b-a, c-a, d-a] > 0, i.e. its signed volume
//    (b-a)x(c-a)·(d-a)/6 is positive (the convention of Gmsh and Medit).
//  - A closed boundary surface is oriented with outward normals: triangle (a, b, c) has normal
//    (b-a)x(c-a) pointing out of the enclosed volume.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace afmesh {

using Index = std::int32_t;
inline constexpr Index kInvalidIndex = -1;

using Point = std::array<double, 3>;     // x, y, z
using Triangle = std::array<Index, 3>;   // point indices
using Tet = std::array<Index, 4>;        // point indices, positive orientation

// Whether point p is a corner of simplex s (a triangle or a tet).
template <std::size_t N>
constexpr bool has_corner(const std::array<Index, N>& s, Index p) {
  for (const Index q : s)
    if (q == p) return true;
  return false;
}

// A mesh as plain arrays. Any of the element arrays may be empty. Tag arrays always have the
// same length as their element arrays (0 where a file carries no tag): `triangle_tags[i]` is the
// patch / physical / Medit reference of triangles[i]; likewise `tet_tags`.
struct Mesh {
  std::vector<Point> points;           // N×3
  std::vector<Triangle> triangles;     // M×3
  std::vector<Index> triangle_tags;    // M
  std::vector<Tet> tets;               // K×4
  std::vector<Index> tet_tags;         // K
};

}  // namespace afmesh
