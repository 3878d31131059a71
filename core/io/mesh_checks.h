// Checks a writer makes before emitting a byte, so that no file is left half-written because of
// a bad mesh and no format silently drops what it cannot hold.
#pragma once

#include <cstddef>
#include <span>
#include <string_view>

#include "absl/status/status.h"
#include "core/mesh/mesh.h"

namespace afmesh {

// OK when tag arrays match their element arrays in length, every index is in [0, #points) and
// every coordinate is finite; else INVALID_ARGUMENT naming the first offending element.
absl::Status check_mesh_for_writing(const Mesh& mesh);

// OK when `mesh` has no tetrahedra; else INVALID_ARGUMENT saying that `format` ("STL") holds
// triangles only. Surface formats refuse volume meshes instead of dropping their tetrahedra.
absl::Status check_triangles_only(const Mesh& mesh, std::string_view format);

// OK when there are `num_points` sizes, each finite and > 0; else INVALID_ARGUMENT naming the
// first offending size (sizes of a background grid, one per point).
absl::Status check_sizes_for_writing(std::span<const double> sizes, std::size_t num_points);

}  // namespace afmesh
