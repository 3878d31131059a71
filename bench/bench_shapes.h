// The benchmark solids by name, so that every tool and every run meshes the same front.
//
//   name     solid                                                   bounding box
//   sphere   sphere of radius 1 at the origin                        [-1, 1]^3
//   torus    torus around z, major radius 1, minor radius 0.35       [-1.35, 1.35]^2 x [-0.35, 0.35]
//   box      unit cube                                               [0, 1]^3
//   lblock   L-block with a square through-hole, voxels of side 0.5  [0, 2] x [0, 2.5] x [0, 0.5]
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "absl/status/statusor.h"
#include "core/mesh/mesh.h"

namespace afmesh::bench {

// The names accepted by `bench_surface`, in the order above.
std::vector<std::string> bench_shape_names();

// A one-line description of the solid `name` (e.g. "sphere, radius 1"); empty for an unknown name.
std::string bench_shape_description(std::string_view name);

// The closed, outward-oriented surface of solid `name` with edges about `h` (core/shapes).
// INVALID_ARGUMENT for an unknown name (listing the known ones) or h <= 0.
absl::StatusOr<Mesh> bench_surface(std::string_view name, double h);

}  // namespace afmesh::bench
