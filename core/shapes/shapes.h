// Closed, outward-oriented triangulated surfaces of simple solids: the shipped examples, the
// integration tests and the benchmarks mesh these. Each takes a target edge length h.
#pragma once

#include <array>
#include <vector>

#include "core/mesh/mesh.h"

namespace afmesh {

// The surface of the union of unit voxels `cells` (integer lattice coordinates), scaled by
// `voxel_size` and offset by `origin`, each voxel face split into n×n squares of two triangles.
// The voxel set must not touch itself along an edge or at a corner only (the surface would not
// be a manifold); it may have through-holes.
Mesh voxel_surface(const std::vector<std::array<int, 3>>& cells, double voxel_size,
                   const Point& origin, int n);

// An axis-aligned box [lo, hi] with edges about h (at least one division per side).
Mesh box_surface(const Point& lo, const Point& hi, double h);

// The box [lo, hi] filled with tetrahedra: (n+1)^3 lattice points (x fastest, then y, then z),
// each of the n^3 cells split into the six Kuhn tets around its diagonal lo-hi, all positive and
// conforming (one tet tag 0 each; no triangles). A structured background grid for tests and
// benchmarks. n >= 1.
Mesh box_tets(const Point& lo, const Point& hi, int n);

// An L-shaped block with a square through-hole in its long leg (a non-convex solid of genus 1):
// voxels of side `unit` (see the picture in shapes.cc), divided to edges about h.
Mesh l_block_with_hole_surface(double unit, double h);

// A sphere: each face of an icosahedron divided into n×n triangles and projected, with n chosen
// so that edges are about h.
Mesh sphere_surface(const Point& center, double radius, double h);

// A torus around the z axis with major radius R and minor radius r, edges about h.
Mesh torus_surface(double major_radius, double minor_radius, double h);

// Schönhardt's twisted prism: a unit triangle in z = 0 and the same triangle turned by 30° in
// z = 1, the three side quads split along their reflex diagonals, so that no tetrahedralisation
// of its six corners exists (a new point is needed). Eight triangles.
Mesh schoenhardt_prism_surface();

}  // namespace afmesh
