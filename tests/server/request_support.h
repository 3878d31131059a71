// The fronts and MeshVolume requests the in-process server tests send, and how they compare
// what comes back.
#pragma once

#include <cstring>
#include <vector>

#include "absl/status/status.h"
#include "afmesh/v1/mesher.pb.h"
#include "core/mesh/mesh.h"
#include "gtest/gtest.h"
#include "proto/slice_codec.h"

namespace afmesh::testing {

// The boundary of the unit corner tetrahedron, outward-oriented: 4 points, 4 triangles tagged
// 1 to 4.
inline Mesh tetrahedron_front() {
  Mesh front;
  front.points = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  front.triangles = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
  front.triangle_tags = {1, 2, 3, 4};
  return front;
}

// The unit corner tetrahedron's boundary (4 points, 4 triangles of tag 0) at size `size`,
// growth 1.2: header, points, triangles.
inline std::vector<v1::MeshVolumeRequest> tetrahedron_requests(double size = 0.5) {
  v1::MeshVolumeRequest header;
  header.mutable_header()->mutable_options()->mutable_size()->set_max_size(size);
  header.mutable_header()->mutable_options()->mutable_size()->set_growth(1.2);
  header.mutable_header()->set_point_count(4);
  header.mutable_header()->set_triangle_count(4);
  v1::MeshVolumeRequest points;
  for (const double c : {0., 0., 0., 1., 0., 0., 0., 1., 0., 0., 0., 1.}) {
    points.mutable_points()->add_xyz(c);
  }
  v1::MeshVolumeRequest triangles;
  for (const int i : {0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3}) {
    triangles.mutable_triangles()->add_indices(i);
  }
  for (int t = 0; t < 4; ++t) triangles.mutable_triangles()->add_tags(0);
  return {header, points, triangles};
}

// True when both point arrays hold the same bits (so -0.0 differs from 0.0).
inline bool same_bits(const std::vector<Point>& a, const std::vector<Point>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(Point)) == 0;
}

// True when a MeshVolumeResponse or MeshSurfaceResponse carries a slice of the mesh.
template <class Response>
bool carries_mesh(const Response& response) {
  if constexpr (requires { response.has_tets(); }) {
    if (response.has_tets()) return true;
  }
  return response.has_points() || response.has_triangles();
}

// The mesh carried by the point, triangle (and tet) slices of `responses`; every slice must be
// well formed.
template <class Response>
Mesh mesh_from(const std::vector<Response>& responses) {
  Mesh mesh;
  for (const Response& response : responses) {
    absl::Status status;
    if (response.has_points()) {
      status = wire::append_points(response.points(), "response", mesh.points);
    } else if (response.has_triangles()) {
      status = wire::append_triangles(response.triangles(), "response", mesh.triangles,
                                      mesh.triangle_tags);
    } else if constexpr (requires { response.has_tets(); }) {
      if (response.has_tets()) {
        status = wire::append_tets(response.tets(), "response", mesh.tets, mesh.tet_tags);
      }
    }
    EXPECT_TRUE(status.ok()) << status;
  }
  return mesh;
}

}  // namespace afmesh::testing
