// Open and tagged surfaces for the surface-model tests, beside the closed solids of
// core/shapes/shapes.h (sphere_surface, torus_surface, box_surface), which these tests use too,
// and the surface model with its features built in one call.
#pragma once

#include <functional>
#include <string>

#include "core/mesh/mesh.h"
#include "core/surface/discrete_surface.h"
#include "core/surface/features.h"

namespace afmesh::testing {

// A latitude-longitude sphere: two pole points and `rings` circles of `around` points, outward.
// Triangles with a centroid above z = centre z get tag 1, the others tag 2, so that the tag
// boundary is the equator ring (rings odd: the middle circle lies at the centre's height).
Mesh uv_sphere(const Point& centre, double radius, int around, int rings);

// A closed cylinder around the z axis, radius r, z in [0, height]: `around` points per circle,
// `layers` bands of quads (split in two triangles) on the side, the caps fanned to their centres.
Mesh closed_cylinder(double radius, double height, int around, int layers);

// An open height field z = height(x, y) over a disk of `radius` around (cx, cy): a centre point
// and `rings` circles of `around` points, triangles facing up (+z).
Mesh terrain_disk(double cx, double cy, double radius, int rings, int around,
                  const std::function<double(double, double)>& height);

// An open height field over the rectangle [x0, x0 + width] × [y0, y0 + depth] on an n×n grid of
// squares, each split in two triangles facing up.
Mesh terrain_grid(double x0, double y0, double width, double depth, int n,
                  const std::function<double(double, double)>& height);

// Three unit square sheets meeting along the segment x = z = 0, y in [0, 1] (a T: the halves
// x < 0 and x > 0 of the plane z = 0 and the wall x = 0, z > 0), each an n×n grid of squares
// split in two; the shared segment's edges have three faces.
Mesh three_sheet_t(int n);

// The mesh of `name` in ../shared/corpus (real files from Debian packages; CI has ../shared
// beside the checkout); a read failure is a test failure (and gives an empty mesh).
Mesh corpus_mesh(const std::string& name);

// A discrete surface over `mesh` and its features; a failure of either is a test failure (and
// leaves the features empty).
struct SurfaceModel {
  DiscreteSurface surface;
  SurfaceFeatures features;
};
SurfaceModel surface_model(const Mesh& mesh, const FeatureParams& params = {});

}  // namespace afmesh::testing
