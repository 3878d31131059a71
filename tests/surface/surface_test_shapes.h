// Open and tagged surfaces for the surface-model tests, beside the closed solids of
// core/shapes/shapes.h (sphere_surface, torus_surface, box_surface), which these tests use too,
// and the surface model with its features built in one call.
#pragma once

#include <cstdint>
#include <functional>
#include <random>
#include <string>

#include "absl/status/statusor.h"
#include "core/mesh/mesh.h"
#include "core/surface/discrete_surface.h"
#include "core/surface/features.h"
#include "core/surface/generate_surface_mesh.h"
#include "core/surface/surface_front.h"

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

// A random unit vector.
Point random_direction(std::mt19937& rng);

// `mesh` with every point moved by a random vector (seeded) of length up to `amplitude` (a scan's
// noise; a third of the edge length makes neighbouring normals differ by tens of degrees), or up
// to amplitude(point) for each point.
Mesh jittered(Mesh mesh, double amplitude, unsigned seed);
Mesh jittered(Mesh mesh, const std::function<double(const Point&)>& amplitude, unsigned seed);

// A scan-like unit sphere around the origin of very uneven triangles: sphere_surface at
// `largest`, refined by grade_surface to sizes from `smallest` at x = -1 to `largest` at x = 1,
// then every point moved by a random vector (seeded) of length up to `noise` times the size
// there (0.2 gives triangles down to 8°; a third makes the surface cross itself).
Mesh graded_noisy_sphere(double smallest, double largest, double noise, unsigned seed);

// `mesh` with `count` of its triangles, chosen at random (seeded), turned the other way round
// (a surface of random winding, as STL files of some exporters are); count <= the triangles.
Mesh with_flipped_triangles(Mesh mesh, std::int64_t count, unsigned seed);

// A closed box [0, length] × [0, width] × [0, height] tessellated as CAD exporters do: only the
// four edges along x carry points (spaced geometrically, dense at x = 0 on two opposite edges
// and at x = length on the other two), each long face is one strip zipped between its two
// edges, the end faces are two triangles each. The strips' triangles are fans of slivers: with
// length 4, width 1, height 0.5 and 40 points per edge, angles well under 1° beside triangles
// spanning half the part. Outward, 6 patches (tags 0), 12 ridges, 8 corners.
Mesh sliver_box(double length, double width, double height, int points_per_edge);

// A closed cylinder around the z axis, radius r, z in [0, height], tessellated as CAD exporters
// do: `around` points per rim, the side one band of quads (two slivers each, the full height
// long), each cap a fan from one of its rim points; every triangle has an angle of 180° / around.
// Outward.
Mesh sliver_cylinder(double radius, double height, int around);

// The mesh of `name` in ../shared/corpus (real files from Debian packages; CI has ../shared
// beside the checkout); a read failure is a test failure (and gives an empty mesh).
Mesh corpus_mesh(const std::string& name);

// A corpus file (corpus_mesh) meshed at its mean edge length, as bench/surface/run_corpus.py
// does. `adjust` changes the other parameters (ridge or curvature angle) before the job runs.
absl::StatusOr<SurfaceResult> mesh_corpus_at_mean_edge(
    const std::string& name, const std::function<void(SurfaceParams&)>& adjust = {});

// A discrete surface over `mesh` and its features; a failure of either is a test failure (and
// leaves the features empty).
struct SurfaceModel {
  DiscreteSurface surface;
  SurfaceFeatures features;
};
SurfaceModel surface_model(const Mesh& mesh, const FeatureParams& params = {});

// Puts `mesh` into s as the front's result in patch 0: each point moved onto the input (its
// host the face it lands on, no anchor), the triangles as they are.
void add_on_the_input(const Mesh& mesh, SurfaceMeshState& s);

// The smallest angle of s's triangles, degrees.
double smallest_angle(const SurfaceMeshState& s);

// The triangles of `mesh` whose smallest angle is at least 30 degrees, and under 15 (issue 11's
// bars).
struct AngleCounts {
  std::int64_t at_least_30 = 0, under_15 = 0;
};
AngleCounts angle_counts(const Mesh& mesh);

// The largest distance from the samples of `from` (vertices, edge midpoints, centroids) to
// `to`, by scanning every triangle of `to`: the reference for the report's Hausdorff distance.
double scanned_distance(const Mesh& from, const Mesh& to);

}  // namespace afmesh::testing
