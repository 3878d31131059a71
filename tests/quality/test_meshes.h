// Small hand-built meshes for the quality and validation tests.
//
// Unit cube points are numbered i = x + 2y + 4z for the corner (x, y, z) in {0, 1}^3.
#pragma once

#include <array>
#include <vector>

#include "core/mesh/mesh.h"

namespace afmesh::testing {

// The 8 corners of the unit cube, point i = (i & 1, (i >> 1) & 1, (i >> 2) & 1).
std::vector<Point> unit_cube_points();

// A mesh with the given points and tets (tags zero), every tet reordered to positive volume.
Mesh tet_mesh(std::vector<Point> points, std::vector<Tet> tets);

// A mesh with the given points and triangles (tags zero).
Mesh surface_mesh(std::vector<Point> points, std::vector<Triangle> triangles);

// The unit cube as 5 tets: corner tets at 0, 3, 5, 6 (tets 0-3) and the regular central tet
// (1, 2, 4, 7) (tet 4).
Mesh five_tet_cube();

// The 12 outward boundary triangles of five_tet_cube (each face cut along the diagonal between
// its odd corners 1, 2, 4, 7), over the cube's 8 points. Triangles 0, 2, 4 are the corner-0 ones.
Mesh five_tet_cube_boundary();

// The unit cube as 6 tets around the diagonal 0-7.
Mesh six_tet_cube();

// The 12 outward boundary triangles of six_tet_cube.
Mesh six_tet_cube_boundary();

// Two tets sharing the face (0, 1, 2): point 3 above it, point 4 below.
Mesh two_tet_mesh();

// The octahedron with vertices ±x, ±y, ±z (points 0..5 = +x, -x, +y, -y, +z, -z), 8 outward
// triangles; triangles 0-3 touch +z, 4-7 touch -z.
Mesh octahedron();

// The cube [0, n]^3 as n^3 unit cubes of 6 tets each (six_tet_cube's split, which conforms
// across cubes), with its points and tets in a scrambled but fixed order and each tet's corners
// rotated (orientation kept), so that neighbours are far apart in both arrays. Cube (i, j, k)
// is left out when `hole` is {i, j, k} (a cavity when it is an inner cube).
Mesh cube_grid(int n, std::array<int, 3> hole = {-1, -1, -1});

// The faces of exactly one tet of `mesh`, oriented out of it, as a surface over mesh.points (found
// by brute force: a map from sorted vertex triples to their uses).
Mesh boundary_by_brute_force(const Mesh& mesh);

// Concatenates two meshes' points and elements (indices of `b` shifted).
Mesh merge(const Mesh& a, const Mesh& b);

// `m` with every point moved by `offset`.
Mesh translated(Mesh m, const Point& offset);

}  // namespace afmesh::testing
