#include "core/io/mesh_checks.h"

#include <cmath>
#include <cstddef>
#include <vector>

#include "core/io/return_if_error.h"
#include "core/io/string_util.h"

namespace afmesh {
namespace {

// First element of `elements` (rows of point indices) with an index outside [0, num_points).
template <typename Element>
absl::Status check_indices(const std::vector<Element>& elements, std::size_t num_points,
                           std::string_view kind) {
  for (std::size_t e = 0; e < elements.size(); ++e) {
    for (const Index v : elements[e]) {
      if (v < 0 || static_cast<std::size_t>(v) >= num_points) {
        return absl::InvalidArgumentError(str_cat(kind, " ", e, " refers to point ", v,
                                                  ", but the mesh has ", num_points, " points"));
      }
    }
  }
  return absl::OkStatus();
}

absl::Status check_tag_count(std::size_t tags, std::size_t elements, std::string_view kind) {
  if (tags == elements) return absl::OkStatus();
  return absl::InvalidArgumentError(
      str_cat("the mesh has ", elements, " ", kind, "s but ", tags, " ", kind, " tags"));
}

}  // namespace

absl::Status check_mesh_for_writing(const Mesh& mesh) {
  AFMESH_RETURN_IF_ERROR(
      check_tag_count(mesh.triangle_tags.size(), mesh.triangles.size(), "triangle"));
  AFMESH_RETURN_IF_ERROR(check_tag_count(mesh.tet_tags.size(), mesh.tets.size(), "tetrahedron"));
  for (std::size_t p = 0; p < mesh.points.size(); ++p) {
    const Point& point = mesh.points[p];
    if (!std::isfinite(point[0]) || !std::isfinite(point[1]) || !std::isfinite(point[2])) {
      return absl::InvalidArgumentError(str_cat("point ", p, " has a non-finite coordinate (",
                                                point[0], ", ", point[1], ", ", point[2], ")"));
    }
  }
  AFMESH_RETURN_IF_ERROR(check_indices(mesh.triangles, mesh.points.size(), "triangle"));
  return check_indices(mesh.tets, mesh.points.size(), "tetrahedron");
}

absl::Status check_sizes_for_writing(std::span<const double> sizes, std::size_t num_points) {
  if (sizes.size() != num_points) {
    return absl::InvalidArgumentError(str_cat("the grid has ", num_points, " points but ",
                                              sizes.size(), " sizes (one per point is needed)"));
  }
  for (std::size_t i = 0; i < sizes.size(); ++i) {
    if (!std::isfinite(sizes[i]) || sizes[i] <= 0.0) {
      return absl::InvalidArgumentError(
          str_cat("size ", i, " must be finite and > 0, got ", sizes[i]));
    }
  }
  return absl::OkStatus();
}

absl::Status check_triangles_only(const Mesh& mesh, std::string_view format) {
  if (mesh.tets.empty()) return absl::OkStatus();
  return absl::InvalidArgumentError(str_cat(
      format, " holds triangles only, but the mesh has ", mesh.tets.size(),
      " tetrahedra; write .msh, .mesh or .vtu to keep them, or remove the tetrahedra to write the ",
      mesh.triangles.size(), " triangles alone"));
}

}  // namespace afmesh
