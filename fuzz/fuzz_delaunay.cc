// Delaunay tetrahedralisation (core/delaunay/delaunay_3d.h). Every 3 bytes are a point on a small
// integer grid (each byte's low 4 bits, scaled by the first byte's high bits), so inputs are full
// of what breaks Delaunay codes: repeated points, four on a plane, five on a sphere, points on
// the hull's faces and edges. The tiling must hold whatever comes: every element positive (exact
// orient3d), every face in at most two elements turned opposite ways, the faces in one only
// closing up (each of their edges in an even number of them), no point strictly inside an
// element's circumsphere, and every element's corner the first copy of its point.
#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <numeric>
#include <span>
#include <utility>
#include <vector>

#include "core/delaunay/delaunay_3d.h"
#include "core/geometry/predicates.h"
#include "core/quality/mesh_topology.h"

namespace {

void fail(const char* what) {
  std::fprintf(stderr, "delaunay_tetrahedralise: %s\n", what);
  std::abort();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using afmesh::Index;
  using afmesh::Point;
  if (size < 4 || size > 3 * 200 + 1) return 0;
  const double scale = 1.0 + (data[0] >> 4);  // 1..16: the grid's spacing
  std::vector<Point> points;
  for (std::size_t i = 1; i + 2 < size; i += 3)
    points.push_back({scale * (data[i] & 15), scale * (data[i + 1] & 15),
                      scale * (data[i + 2] & 15)});
  const absl::StatusOr<afmesh::DelaunayTets> d = afmesh::delaunay_tetrahedralise(points);
  if (!d.ok()) fail("refused finite points");
  if (d->vertex_of_point.size() != points.size()) fail("vertex_of_point has the wrong size");
  for (std::size_t i = 0; i < points.size(); ++i) {
    const Index v = d->vertex_of_point[i];
    if (v < 0 || v > static_cast<Index>(i) || points[v] != points[i] ||
        d->vertex_of_point[v] != v)
      fail("a point maps to no first copy of itself");
  }
  for (const afmesh::Tet& t : d->tets) {
    for (const Index v : t)
      if (v < 0 || v >= static_cast<Index>(points.size()) || d->vertex_of_point[v] != v)
        fail("an element's corner is not a first copy");
    if (afmesh::orient3d(points[t[0]], points[t[1]], points[t[2]], points[t[3]]) <= 0)
      fail("an element is not positive");
    for (std::size_t q = 0; q < points.size(); ++q)
      if (!afmesh::has_corner(t, static_cast<Index>(q)) &&
          afmesh::insphere(points[t[0]], points[t[1]], points[t[2]], points[t[3]], points[q]) > 0)
        fail("a point lies inside an element's circumsphere");
  }
  // Each face in one element or in two turned opposite ways; the faces in one only (the
  // boundary of the union) close up: each of their edges is in an even number of them (two, or
  // four where the union pinches along an edge).
  std::vector<Index> all(d->tets.size());
  std::iota(all.begin(), all.end(), 0);
  std::map<std::pair<Index, Index>, int> boundary_edges;
  afmesh::for_each_tet_face(d->tets, all, [&](std::span<const afmesh::FaceUse> uses) {
    if (uses.size() > 2 || (uses.size() == 2 && uses[0].even == uses[1].even))
      fail("two elements lie on one side of a face");
    if (uses.size() == 1)
      for (int k = 0; k < 3; ++k) {
        const Index a = uses[0].key[k], b = uses[0].key[(k + 1) % 3];
        ++boundary_edges[{std::min(a, b), std::max(a, b)}];
      }
  });
  for (const auto& [edge, n] : boundary_edges)
    if (n % 2 != 0) fail("the boundary's faces do not close up");
  return 0;
}
