#include "core/quality/mesh_topology.h"

#include <algorithm>
#include <numeric>
#include <tuple>

namespace afmesh {
namespace {

// One triangle's traversal of one edge: the edge (a, b), a < b, whether the triangle runs
// from a to b, and which of its edges it is (from corner `slot` to corner `slot` + 1).
struct HalfEdge {
  Index a = 0;
  Index b = 0;
  Index triangle = 0;
  bool forward = false;
  std::int8_t slot = 0;
};

// The half-edges ordered by (a, b, triangle, forward): bucketed by their lower point a (a
// counting sort, O(M + N)), then each bucket, a point's few edges, sorted by the rest: the same
// order as one comparison sort of them all, without its O(M log M).
std::vector<HalfEdge> sorted_half_edges(const std::vector<Triangle>& triangles,
                                        CancelCheck* cancel = nullptr) {
  const auto stop = [cancel] { return cancel != nullptr && cancel->due(); };
  Index points = 0;
  for (const Triangle& t : triangles)
    for (const Index v : t) points = std::max(points, v + 1);
  std::vector<std::size_t> start(static_cast<std::size_t>(points) + 1, 0);
  for (const Triangle& t : triangles)
    for (int k = 0; k < 3; ++k) ++start[std::min(t[k], t[(k + 1) % 3]) + 1];
  for (std::size_t v = 1; v < start.size(); ++v) start[v] += start[v - 1];
  std::vector<HalfEdge> half_edges(3 * triangles.size());
  std::vector<std::size_t> next(start.begin(), start.end() - 1);
  for (Index t = 0; t < static_cast<Index>(triangles.size()); ++t) {
    if (stop()) return half_edges;
    for (int k = 0; k < 3; ++k) {
      const Index from = triangles[t][k], to = triangles[t][(k + 1) % 3];
      half_edges[next[std::min(from, to)]++] = {std::min(from, to), std::max(from, to), t,
                                                from < to, static_cast<std::int8_t>(k)};
    }
  }
  const auto before = [](const HalfEdge& x, const HalfEdge& y) {
    return std::tie(x.b, x.triangle, x.forward) < std::tie(y.b, y.triangle, y.forward);
  };
  for (std::size_t v = 0; v + 1 < start.size(); ++v) {
    if (stop()) return half_edges;
    if (start[v + 1] - start[v] > 1)
      std::sort(half_edges.begin() + static_cast<std::ptrdiff_t>(start[v]),
                half_edges.begin() + static_cast<std::ptrdiff_t>(start[v + 1]), before);
  }
  return half_edges;
}

// Calls visit(first, last) for each run [first, last) of sorted half-edges on the same edge.
template <typename Visit>
void for_each_edge_run(const std::vector<HalfEdge>& half_edges, Visit visit) {
  for (std::size_t first = 0; first < half_edges.size();) {
    std::size_t last = first + 1;
    while (last < half_edges.size() && half_edges[last].a == half_edges[first].a &&
           half_edges[last].b == half_edges[first].b) {
      ++last;
    }
    visit(first, last);
    first = last;
  }
}

// Disjoint sets over corner ids 3 t + k (corner k of triangle t), union by size.
class CornerSets {
 public:
  explicit CornerSets(std::size_t n) : parent_(n), size_(n, 1) {
    std::iota(parent_.begin(), parent_.end(), 0);
  }
  Index find(Index x) {
    while (parent_[x] != x) {
      parent_[x] = parent_[parent_[x]];
      x = parent_[x];
    }
    return x;
  }
  void join(Index x, Index y) {
    x = find(x);
    y = find(y);
    if (x == y) return;
    if (size_[x] < size_[y]) std::swap(x, y);
    parent_[y] = x;
    size_[x] += size_[y];
  }

 private:
  std::vector<Index> parent_;
  std::vector<Index> size_;
};

Index corner_of(const std::vector<Triangle>& triangles, Index t, Index vertex) {
  const Triangle& tri = triangles[t];
  const int k = tri[0] == vertex ? 0 : tri[1] == vertex ? 1 : 2;
  return 3 * t + k;
}

// Classifies one edge's group of half-edges [first, last) into `topology`, and joins the corners
// of its triangles at each end of the edge (they are in one fan there).
void classify_edge(const std::vector<Triangle>& triangles, const std::vector<HalfEdge>& half_edges,
                   std::size_t first, std::size_t last, CornerSets& corners,
                   TriangleTopology& topology) {
  const Index a = half_edges[first].a, b = half_edges[first].b;
  const Index t0 = half_edges[first].triangle;
  for (std::size_t i = first; i < last; ++i) {
    corners.join(corner_of(triangles, t0, a), corner_of(triangles, half_edges[i].triangle, a));
    corners.join(corner_of(triangles, t0, b), corner_of(triangles, half_edges[i].triangle, b));
  }
  ++topology.edge_count;
  // Only the edges kept get their group (most edges are manifold: no allocation for them).
  const auto group = [&] {
    EdgeGroup g{a, b, {}};
    for (std::size_t i = first; i < last; ++i) g.triangles.push_back(half_edges[i].triangle);
    return g;
  };
  const std::size_t uses = last - first;
  if (uses == 1) {
    topology.open_edges.push_back(group());
  } else if (uses > 2) {
    topology.nonmanifold_edges.push_back(group());
  } else if (half_edges[first].forward == half_edges[first + 1].forward) {
    topology.misoriented_edges.push_back(group());
  }
}

// Vertices whose corners fall into two or more fans. The corners are bucketed by vertex (a
// counting sort, O(M + N)), each bucket in ascending triangle order, and a bucket's fans are
// counted among its few corners: the same result as sorting all corners by (vertex, fan,
// triangle), without its O(M log M). Stops (an unfinished list) once `cancel` is stopped.
std::vector<VertexFans> split_vertices(const std::vector<Triangle>& triangles,
                                       CornerSets& corners, CancelCheck* cancel) {
  Index points = 0;
  for (const Triangle& t : triangles)
    for (const Index v : t) points = std::max(points, v + 1);
  std::vector<std::size_t> start(static_cast<std::size_t>(points) + 1, 0);
  for (const Triangle& t : triangles)
    for (const Index v : t) ++start[v + 1];
  for (std::size_t v = 1; v < start.size(); ++v) start[v] += start[v - 1];
  std::vector<Index> corner_at(3 * triangles.size());  // corner ids 3 t + k, by vertex
  std::vector<std::size_t> next(start.begin(), start.end() - 1);
  for (Index t = 0; t < static_cast<Index>(triangles.size()); ++t)
    for (int k = 0; k < 3; ++k) corner_at[next[triangles[t][k]]++] = 3 * t + k;
  std::vector<VertexFans> result;
  std::vector<Index> fans;
  for (Index v = 0; v < points; ++v) {
    if (cancel != nullptr && cancel->due()) return result;
    fans.clear();
    for (std::size_t i = start[v]; i < start[v + 1]; ++i)
      fans.push_back(corners.find(corner_at[i]));
    std::sort(fans.begin(), fans.end());
    const int fan_count =
        static_cast<int>(std::unique(fans.begin(), fans.end()) - fans.begin());
    if (fan_count < 2) continue;
    VertexFans fan{v, fan_count, {}};
    for (std::size_t i = start[v]; i < start[v + 1]; ++i) fan.triangles.push_back(corner_at[i] / 3);
    result.push_back(std::move(fan));
  }
  return result;
}

// How many filed tets ahead for_each_tet_face asks the cache for.
constexpr Index kPrefetchDistance = 16;

// Tets filed under vertices: bucket v is tets[offsets[v] .. offsets[v + 1]).
struct TetsByVertex {
  std::vector<Index> offsets;  // N + 1
  std::vector<Index> tets;
};

// Corner of the smallest index of `tet`.
int smallest_corner(const Tet& tet) {
  int low = 0;
  for (int k = 1; k < 4; ++k) {
    if (tet[k] < tet[low]) low = k;
  }
  return low;
}

// Each listed tet under its smallest and second smallest vertex, by a counting sort: every face
// of a tet has one of these two as its smallest vertex.
// With `stop`, the filing ends early (incomplete) once stop->due() is true.
TetsByVertex file_by_two_smallest_vertices(const std::vector<Tet>& tets,
                                           const std::vector<Index>& tet_ids, CancelCheck* stop) {
  Index point_count = 0;
  for (Index id : tet_ids) {
    if (stop != nullptr && stop->due()) return {};
    for (Index v : tets[id]) point_count = std::max(point_count, v + 1);
  }
  auto two_smallest = [&](Index id) {
    const Tet& t = tets[id];
    const Index low01 = std::min(t[0], t[1]), high01 = std::max(t[0], t[1]);
    const Index low23 = std::min(t[2], t[3]), high23 = std::max(t[2], t[3]);
    return low01 < low23 ? std::array<Index, 2>{low01, std::min(high01, low23)}
                         : std::array<Index, 2>{low23, std::min(high23, low01)};
  };
  TetsByVertex filed{std::vector<Index>(point_count + 1, 0),
                     std::vector<Index>(2 * tet_ids.size())};
  for (Index id : tet_ids) {
    if (stop != nullptr && stop->due()) return {};
    for (Index v : two_smallest(id)) ++filed.offsets[v + 1];
  }
  std::partial_sum(filed.offsets.begin(), filed.offsets.end(), filed.offsets.begin());
  std::vector<Index> next(filed.offsets.begin(), filed.offsets.end() - 1);
  for (Index id : tet_ids) {
    if (stop != nullptr && stop->due()) return {};
    for (Index v : two_smallest(id)) filed.tets[next[v]++] = id;
  }
  return filed;
}

// A face whose smallest vertex is known (the bucket being grouped), ordered as FaceUse is by
// (key, tet) with the other two vertices b < c packed into one number for a cheap comparison.
struct FaceAtVertex {
  std::uint64_t other_two = 0;  // b * 2^32 + c
  Index tet = 0;
  std::int8_t corner = 0;
  bool even = false;

  Index b() const { return static_cast<Index>(other_two >> 32); }
  Index c() const { return static_cast<Index>(other_two & 0xffffffffu); }
};

bool operator<(const FaceAtVertex& x, const FaceAtVertex& y) {
  return x.other_two != y.other_two ? x.other_two < y.other_two : x.tet < y.tet;
}

// Appends to `faces` the faces of tet `id` whose smallest vertex is `v` (one of its two
// smallest): the three faces at v when v is the tet's smallest vertex, else the face opposite
// the smallest.
void add_faces_with_smallest_vertex(const std::vector<Tet>& tets, Index id, Index v,
                                    std::vector<FaceAtVertex>& faces) {
  const Tet& tet = tets[id];
  const int low = smallest_corner(tet);
  for (int corner = 0; corner < 4; ++corner) {
    if ((tet[low] == v) == (corner == low)) continue;
    const Triangle face = tet_face(tet, corner);
    const Triangle key = sorted_triangle(face);
    faces.push_back({(static_cast<std::uint64_t>(key[1]) << 32) | static_cast<std::uint32_t>(key[2]),
                     id, static_cast<std::int8_t>(corner), canonical_rotation(face) == key});
  }
}

}  // namespace

Triangle canonical_rotation(const Triangle& t) {
  if (t[1] < t[0] && t[1] <= t[2]) return {t[1], t[2], t[0]};
  if (t[2] < t[0] && t[2] < t[1]) return {t[2], t[0], t[1]};
  return t;
}

// Three compare-exchanges: called for every face of every tet, so no general sort.
Triangle sorted_triangle(const Triangle& t) {
  Index a = t[0], b = t[1], c = t[2];
  if (b < a) std::swap(a, b);
  if (c < b) std::swap(b, c);
  if (b < a) std::swap(a, b);
  return {a, b, c};
}

Triangle tet_face(const Tet& tet, int corner) {
  switch (corner) {
    case 0:
      return {tet[1], tet[2], tet[3]};
    case 1:
      return {tet[0], tet[3], tet[2]};
    case 2:
      return {tet[0], tet[1], tet[3]};
    default:
      return {tet[0], tet[2], tet[1]};
  }
}

bool has_distinct_indices(const Triangle& t) {
  return t[0] != t[1] && t[1] != t[2] && t[0] != t[2];
}

bool has_distinct_indices(const Tet& t) {
  return t[0] != t[1] && t[0] != t[2] && t[0] != t[3] && t[1] != t[2] && t[1] != t[3] &&
         t[2] != t[3];
}

void for_each_tet_face(const std::vector<Tet>& tets, const std::vector<Index>& tet_ids,
                       absl::FunctionRef<void(std::span<const FaceUse>)> visit, CancelCheck* stop) {
  const TetsByVertex filed = file_by_two_smallest_vertices(tets, tet_ids, stop);
  if (stop != nullptr && stop->stopped()) return;
  // The faces whose smallest vertex is v, and one group of them as FaceUse; both reused.
  std::vector<FaceAtVertex> faces;
  std::vector<FaceUse> group;
  for (Index v = 0; v + 1 < static_cast<Index>(filed.offsets.size()); ++v) {
    if (stop != nullptr && stop->due()) return;
    faces.clear();
    for (Index i = filed.offsets[v]; i < filed.offsets[v + 1]; ++i) {
      // The filed tets are scattered over the tet array: fetch a few entries ahead so that
      // the loads overlap instead of waiting one by one.
      if (i + kPrefetchDistance < static_cast<Index>(filed.tets.size())) {
        __builtin_prefetch(&tets[filed.tets[i + kPrefetchDistance]]);
      }
      add_faces_with_smallest_vertex(tets, filed.tets[i], v, faces);
    }
    std::sort(faces.begin(), faces.end());
    for (std::size_t first = 0; first < faces.size();) {
      group.clear();
      std::size_t last = first;
      for (; last < faces.size() && faces[last].other_two == faces[first].other_two; ++last) {
        const FaceAtVertex& f = faces[last];
        group.push_back({{v, f.b(), f.c()}, f.tet, f.corner, f.even});
      }
      visit(group);
      first = last;
    }
  }
}

std::vector<FaceUse> sorted_face_uses(const std::vector<Tet>& tets,
                                      const std::vector<Index>& tet_ids) {
  std::vector<FaceUse> uses;
  uses.reserve(4 * tet_ids.size());
  for_each_tet_face(tets, tet_ids, [&](std::span<const FaceUse> group) {
    uses.insert(uses.end(), group.begin(), group.end());
  });
  return uses;
}

BoundaryFaces collect_boundary_faces(const std::vector<Tet>& tets,
                                     const std::vector<FaceUse>& faces) {
  BoundaryFaces boundary;
  for_each_face_group(faces, [&](std::size_t first, std::size_t last) {
    if (last - first != 1) return;
    boundary.triangles.push_back(tet_face(tets[faces[first].tet], faces[first].corner));
    boundary.tets.push_back(faces[first].tet);
  });
  return boundary;
}

TriangleTopology analyze_triangle_topology(const std::vector<Triangle>& triangles,
                                           CancelCheck* cancel) {
  TriangleTopology topology;
  const std::vector<HalfEdge> half_edges = sorted_half_edges(triangles, cancel);
  if (cancel != nullptr && cancel->stopped()) return topology;
  CornerSets corners(3 * triangles.size());
  for_each_edge_run(half_edges, [&](std::size_t first, std::size_t last) {
    if (cancel != nullptr && cancel->due()) return;  // stopped: the runs left are skipped
    classify_edge(triangles, half_edges, first, last, corners, topology);
  });
  if (cancel != nullptr && cancel->stopped()) return TriangleTopology{};
  topology.nonmanifold_vertices = split_vertices(triangles, corners, cancel);
  if (cancel != nullptr && cancel->stopped()) return TriangleTopology{};
  return topology;
}

EdgeNeighbours triangle_edge_neighbours(const std::vector<Triangle>& triangles,
                                        CancelCheck* cancel) {
  EdgeNeighbours result;
  result.across.assign(triangles.size(), {kInvalidIndex, kInvalidIndex, kInvalidIndex});
  result.same_way.assign(triangles.size(), {false, false, false});
  const std::vector<HalfEdge> half_edges = sorted_half_edges(triangles, cancel);
  if (cancel != nullptr && cancel->stopped()) return result;
  for_each_edge_run(half_edges, [&](std::size_t first, std::size_t last) {
    if (last - first != 2) return;
    const HalfEdge& x = half_edges[first];
    const HalfEdge& y = half_edges[first + 1];
    result.across[x.triangle][x.slot] = y.triangle;
    result.across[y.triangle][y.slot] = x.triangle;
    result.same_way[x.triangle][x.slot] = result.same_way[y.triangle][y.slot] =
        x.forward == y.forward;
  });
  return result;
}

Index label_components(const EdgeNeighbours& neighbours,
                       absl::FunctionRef<bool(Index t, int k)> joins, std::vector<Index>& label) {
  const auto m = static_cast<Index>(neighbours.across.size());
  label.assign(static_cast<std::size_t>(m), kInvalidIndex);
  Index count = 0;
  std::vector<Index> stack;
  for (Index seed = 0; seed < m; ++seed) {
    if (label[seed] != kInvalidIndex) continue;
    label[seed] = count;
    stack.assign(1, seed);
    while (!stack.empty()) {
      const Index t = stack.back();
      stack.pop_back();
      for (int k = 0; k < 3; ++k) {
        const Index g = neighbours.across[t][k];
        if (g == kInvalidIndex || label[g] != kInvalidIndex || !joins(t, k)) continue;
        label[g] = count;
        stack.push_back(g);
      }
    }
    ++count;
  }
  return count;
}

std::vector<std::int32_t> component_environments(const EdgeNeighbours& neighbours) {
  std::vector<Index> label;
  label_components(neighbours, [](Index, int) { return true; }, label);
  std::vector<std::int32_t> ids(label.size());
  for (std::size_t t = 0; t < label.size(); ++t) ids[t] = static_cast<std::int32_t>(label[t]) + 1;
  return ids;
}

std::vector<std::int32_t> component_environments(const std::vector<Triangle>& triangles) {
  return component_environments(triangle_edge_neighbours(triangles));
}

}  // namespace afmesh
