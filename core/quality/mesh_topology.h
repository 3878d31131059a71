// Combinatorial structure of tet and triangle meshes, as needed by validation (validate.h):
// how tets share faces, and how triangles share edges and vertices.
//
// Everything here works on indices only (no coordinates), groups elements by sorting keys
// (sorted vertex pairs / triples), so it runs in O(n log n), and returns its results in
// ascending key order, so the output does not depend on hashing or on the platform.
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "absl/functional/function_ref.h"
#include "core/common/progress.h"
#include "core/mesh/mesh.h"

namespace afmesh {

// `t` rotated so that its smallest index comes first. Rotation keeps the orientation, so two
// oriented triangles are the same oriented face exactly when their rotations are equal.
Triangle canonical_rotation(const Triangle& t);

// `t` with its indices sorted ascending: the key of the unoriented face.
Triangle sorted_triangle(const Triangle& t);

// The face of `tet` opposite its corner `corner` (0..3), oriented outward when the tet is
// positive (det[b-a, c-a, d-a] > 0): (b,c,d), (a,d,c), (a,b,d), (a,c,b) for corners 0..3.
Triangle tet_face(const Tet& tet, int corner);

// The same face unoriented: its key, sorted_triangle(tet_face(tet, corner)).
inline Triangle tet_face_key(const Tet& tet, int corner) {
  return sorted_triangle(tet_face(tet, corner));
}

// True when all indices of the element are distinct.
bool has_distinct_indices(const Triangle& t);
bool has_distinct_indices(const Tet& t);

// One face of one tet.
struct FaceUse {
  Triangle key;         // sorted vertex triple
  Index tet = 0;        // tet index
  std::int8_t corner = 0;  // the face is tet_face(tets[tet], corner)
  bool even = false;    // tet_face(...) is an even permutation of key (same orientation)
};

// Calls visit(uses) once per distinct face of the tets whose ids are listed in `tet_ids`
// (indices into `tets`, K×4; each listed tet has distinct, non-negative indices), in ascending
// key order; `uses` are that face's uses, ordered by (tet, corner). The same order as
// sorted_face_uses, without building the whole list: each tet is filed under its two smallest
// vertices (a counting sort; a face's smallest vertex is one of them), and only the faces whose
// smallest vertex is v are sorted together. Cost O(K + N) plus sorts of a vertex's few faces;
// memory two indices per tet and N + 1 offsets, N the largest index + 1. With `stop`, returns
// early (some faces unvisited) once stop->due() is true; the caller looks at stop->stopped().
void for_each_tet_face(const std::vector<Tet>& tets, const std::vector<Index>& tet_ids,
                       absl::FunctionRef<void(std::span<const FaceUse>)> visit,
                       CancelCheck* stop = nullptr);

// All faces of the tets whose ids are listed in `tet_ids` (as for for_each_tet_face), sorted by
// (key, tet, corner): uses of the same face are adjacent.
std::vector<FaceUse> sorted_face_uses(const std::vector<Tet>& tets,
                                      const std::vector<Index>& tet_ids);

// Calls visit(first, last) for each run [first, last) of equal keys in sorted face uses.
template <typename Visit>
void for_each_face_group(const std::vector<FaceUse>& faces, Visit visit) {
  for (std::size_t first = 0; first < faces.size();) {
    std::size_t last = first + 1;
    while (last < faces.size() && faces[last].key == faces[first].key) ++last;
    visit(first, last);
    first = last;
  }
}

// The faces of exactly one tet, each oriented as tet_face gives it (outward for a positive
// tet), in ascending key order: the tets' boundary surface.
struct BoundaryFaces {
  std::vector<Triangle> triangles;  // B×3 oriented faces
  std::vector<Index> tets;          // B: tets[i] owns triangles[i]
};

// The boundary faces among sorted face uses (from sorted_face_uses over `tets`).
BoundaryFaces collect_boundary_faces(const std::vector<Tet>& tets,
                                     const std::vector<FaceUse>& faces);

// An edge (a, b), a < b, and the triangles using it, ascending.
struct EdgeGroup {
  Index a = 0;
  Index b = 0;
  std::vector<Index> triangles;
};

// A vertex whose triangles do not form a single fan (an edge-connected disk or half-disk).
struct VertexFans {
  Index vertex = 0;
  int fan_count = 0;
  std::vector<Index> triangles;  // all triangles at the vertex, ascending
};

// Edge and vertex structure of an oriented triangle list. Triangle ids are positions in the
// list given to `analyze_triangle_topology`; its triangles must have distinct indices.
struct TriangleTopology {
  std::vector<EdgeGroup> open_edges;          // used by exactly 1 triangle
  std::vector<EdgeGroup> nonmanifold_edges;   // used by 3 or more triangles
  std::vector<EdgeGroup> misoriented_edges;   // used by 2 triangles traversing it the same way
  std::vector<VertexFans> nonmanifold_vertices;  // fan_count >= 2
  std::int64_t edge_count = 0;                // distinct edges
};

// Groups the edges of `triangles` (M×3, distinct indices in each) and counts the fans around
// each vertex: the triangles at a vertex v fall into fans, the classes of "shares an edge at v".
// A manifold vertex has one fan. Results are ascending by edge (a, b) and by vertex.
// With `cancel`, it is looked at while the edges are sorted, grouped and the fans counted, and
// once it is stopped an empty topology is returned: a caller checks cancel->stopped().
TriangleTopology analyze_triangle_topology(const std::vector<Triangle>& triangles,
                                           CancelCheck* cancel = nullptr);

// The triangles across the edges of `triangles` (M×3, distinct indices in each): across[t][k] is
// the other triangle on edge (triangles[t][k], triangles[t][(k + 1) % 3]) when exactly two
// triangles use that edge, else kInvalidIndex (an open or non-manifold edge); same_way[t][k] is
// true when that triangle traverses the edge in the same direction as t (the two disagree in
// orientation). O(M log M).
struct EdgeNeighbours {
  std::vector<std::array<Index, 3>> across;  // M×3
  std::vector<std::array<bool, 3>> same_way;  // M×3
};
// With `cancel`, it is looked at while the edges are sorted, and once it is stopped the result
// is returned unfinished: a caller checks cancel->stopped().
EdgeNeighbours triangle_edge_neighbours(const std::vector<Triangle>& triangles,
                                        CancelCheck* cancel = nullptr);

// Labels the triangles by connected component, joined across the edges of `neighbours` for
// which joins(t, k) is true (edge k of triangle t; never across kInvalidIndex): label[t] in
// [0, count), numbered in the order of each component's lowest triangle. Returns the count.
// O(M).
Index label_components(const EdgeNeighbours& neighbours,
                       absl::FunctionRef<bool(Index t, int k)> joins, std::vector<Index>& label);

// One id per triangle of `triangles` (distinct indices in each): 1 + its component, joined across
// every edge of two triangles (label_components). As validate_surface's face_environments, only
// triangles of different components may cross: the judge of an assembly whose components cross
// in the input and are re-triangulated one by one (MeshSurface, issue 11 part 6). O(M log M).
std::vector<std::int32_t> component_environments(const std::vector<Triangle>& triangles);
// The same from the triangles' edge neighbours, when they are at hand. O(M).
std::vector<std::int32_t> component_environments(const EdgeNeighbours& neighbours);

}  // namespace afmesh
