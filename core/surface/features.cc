#include "core/surface/features.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <numeric>
#include <tuple>

#include "absl/container/flat_hash_set.h"
#include "absl/status/status.h"
#include "absl/strings/str_format.h"
#include "core/geometry/vec.h"
#include "core/quality/mesh_topology.h"

namespace afmesh {
namespace {

// An input edge (a < b) on a line, the faces using it, and why it is on a line.
struct LineEdge {
  Index a = 0;
  Index b = 0;
  std::uint8_t kinds = 0;
  std::vector<Index> faces;
};

// The line edges and, for each vertex v, the ids of those at v: incident[offsets[v], offsets[v+1]).
struct LineGraph {
  std::vector<LineEdge> edges;  // ascending by (a, b)
  std::vector<Index> offsets;   // N + 1
  std::vector<Index> incident;  // 2E edge ids, ascending per vertex
  Index degree(Index v) const { return offsets[v + 1] - offsets[v]; }
  Index other(Index edge, Index v) const {
    return edges[edge].a == v ? edges[edge].b : edges[edge].a;
  }
};

double cos_degrees(double deg) { return std::cos(deg * std::numbers::pi / 180.0); }

// The cosine of the turn across edge k of face t, which has one face g across it: the unit
// normals' dot product, g's turned when the two traverse the edge the same way (disagree in
// orientation). 0 when a face has no normal (zero area).
double turn_cosine(const DiscreteSurface& s, Index t, int k) {
  const Index g = s.neighbours().across[t][k];
  const double sign = s.neighbours().same_way[t][k] ? -1.0 : 1.0;
  return sign * dot(s.normal(FaceId{t}), s.normal(FaceId{g}));
}

}  // namespace

std::vector<FaceId> folded_faces(const DiscreteSurface& surface) {
  const double cos_folded = cos_degrees(kFoldedFaceTurnDeg);
  std::vector<FaceId> out;
  for (Index t = 0; t < surface.face_count(); ++t) {
    bool folded = squared_norm(surface.normal(FaceId{t})) > 0.0;
    for (int k = 0; k < 3 && folded; ++k) {
      const Index g = surface.neighbours().across[t][k];
      folded = g != kInvalidIndex && squared_norm(surface.normal(FaceId{g})) > 0.0 &&
               turn_cosine(surface, t, k) < cos_folded;
    }
    if (folded) out.push_back(FaceId{t});
  }
  return out;
}

namespace {

// Step 1 for an edge with exactly two faces: edge k of face t (its neighbour across it is known).
// Symmetric in the two faces, so either side gives the same answer.
std::uint8_t two_face_edge_kinds(const DiscreteSurface& s, double cos_ridge, Index t, int k) {
  const Index g = s.neighbours().across[t][k];
  std::uint8_t kinds = 0;
  if (s.tags()[t] != s.tags()[g]) kinds |= kTagEdge;
  const bool both_have_normals =
      squared_norm(s.normal(FaceId{t})) > 0.0 && squared_norm(s.normal(FaceId{g})) > 0.0;
  if (both_have_normals && turn_cosine(s, t, k) < cos_ridge) kinds |= kRidgeEdge;
  return kinds;
}

void index_line_graph(Index point_count, LineGraph& graph);

// The boundary and non-manifold edges, from the surface's edge neighbours: an edge of exactly two
// faces has a face across it, so the edges without are those of one face (the rim of an open
// surface) or of three or more (non-manifold). Only they are sorted, by (a, b) and then by face,
// where grouping every edge of the surface again (analyze_triangle_topology, also counting the
// fans round each vertex) took 5% of a 900k-face scan's surface job.
void collect_edges_without_one_face_across(const DiscreteSurface& s, LineGraph& graph) {
  std::vector<std::array<Index, 3>> uses;  // (a, b, face), a < b
  for (Index t = 0; t < s.face_count(); ++t)
    for (int k = 0; k < 3; ++k) {
      if (s.neighbours().across[t][k] != kInvalidIndex) continue;
      const Index u = s.triangles()[t][k], w = s.triangles()[t][(k + 1) % 3];
      uses.push_back({std::min(u, w), std::max(u, w), t});
    }
  std::sort(uses.begin(), uses.end());
  for (std::size_t first = 0; first < uses.size();) {
    std::size_t last = first + 1;
    while (last < uses.size() && uses[last][0] == uses[first][0] &&
           uses[last][1] == uses[first][1])
      ++last;
    LineEdge edge{uses[first][0], uses[first][1],
                  last - first == 1 ? std::uint8_t{kBoundaryEdge} : std::uint8_t{kNonManifoldEdge},
                  {}};
    for (std::size_t i = first; i < last; ++i) edge.faces.push_back(uses[i][2]);
    graph.edges.push_back(std::move(edge));
    first = last;
  }
}

// Step 1: every line edge, ascending by (a, b), with its incidence by vertex.
// With `cancel` stopped, an unfinished graph (the caller checks cancel.stopped()).
LineGraph collect_line_edges(const DiscreteSurface& s, double cos_ridge, CancelCheck& cancel) {
  LineGraph graph;
  collect_edges_without_one_face_across(s, graph);
  for (Index t = 0; t < s.face_count(); ++t) {
    if (cancel.due()) return graph;
    for (int k = 0; k < 3; ++k) {
      const Index g = s.neighbours().across[t][k];
      if (g == kInvalidIndex || g < t) continue;  // each two-face edge once
      const std::uint8_t kinds = two_face_edge_kinds(s, cos_ridge, t, k);
      if (kinds == 0) continue;
      const Index u = s.triangles()[t][k], w = s.triangles()[t][(k + 1) % 3];
      graph.edges.push_back({std::min(u, w), std::max(u, w), kinds, {t, g}});
    }
  }
  std::sort(graph.edges.begin(), graph.edges.end(), [](const LineEdge& x, const LineEdge& y) {
    return std::tie(x.a, x.b) < std::tie(y.a, y.b);
  });
  index_line_graph(s.point_count(), graph);
  return graph;
}

// The incidence of graph.edges by vertex.
void index_line_graph(Index point_count, LineGraph& graph) {
  graph.offsets.assign(point_count + 1, 0);
  for (const LineEdge& e : graph.edges) {
    ++graph.offsets[e.a + 1];
    ++graph.offsets[e.b + 1];
  }
  std::partial_sum(graph.offsets.begin(), graph.offsets.end(), graph.offsets.begin());
  graph.incident.resize(2 * graph.edges.size());
  std::vector<Index> next(graph.offsets.begin(), graph.offsets.end() - 1);
  for (Index e = 0; e < static_cast<Index>(graph.edges.size()); ++e) {
    graph.incident[next[graph.edges[e].a]++] = e;
    graph.incident[next[graph.edges[e].b]++] = e;
  }
}

// Removes the edges marked in `dropped` from `graph`, keeping the others' order, and indexes it
// again.
void remove_edges(Index point_count, const std::vector<bool>& dropped, LineGraph& graph) {
  std::vector<LineEdge> kept;
  for (std::size_t e = 0; e < graph.edges.size(); ++e)
    if (!dropped[e]) kept.push_back(std::move(graph.edges[e]));
  graph.edges = std::move(kept);
  index_line_graph(point_count, graph);
}

// Step 1, last: drops the short free ridges (FeatureParams::short_ridge_sizes) from `graph`.
// Each chain is walked from its free end once per time that end is reached: O(E).
void drop_short_free_ridges(const DiscreteSurface& s, const FeatureParams& params,
                            LineGraph& graph, SurfaceFeatures& out) {
  if (params.sizes == nullptr) return;
  std::vector<Index> degree(s.point_count());
  for (Index v = 0; v < s.point_count(); ++v) degree[v] = graph.degree(v);
  std::vector<bool> dropped(graph.edges.size(), false);
  const auto live_edge_other_than = [&](Index v, Index edge) {
    for (Index i = graph.offsets[v]; i < graph.offsets[v + 1]; ++i)
      if (const Index e = graph.incident[i]; e != edge && !dropped[e]) return e;
    return kInvalidIndex;
  };
  std::vector<Index> free_ends, chain_edges, chain_vertices;
  for (Index v = 0; v < s.point_count(); ++v)
    if (degree[v] == 1) free_ends.push_back(v);
  while (!free_ends.empty()) {
    const Index start = free_ends.back();
    free_ends.pop_back();
    if (degree[start] != 1) continue;
    chain_edges.clear();
    chain_vertices.assign(1, start);
    double length = 0.0;
    bool ridge_only = true;
    Index at = start, edge = kInvalidIndex;
    do {
      edge = live_edge_other_than(at, edge);
      ridge_only = ridge_only && graph.edges[edge].kinds == kRidgeEdge;
      const Index next = graph.other(edge, at);
      length += norm(sub(s.local_points()[next], s.local_points()[at]));
      chain_edges.push_back(edge);
      chain_vertices.push_back(next);
      at = next;
    } while (degree[at] == 2 && at != start);
    const Point middle = s.local_points()[chain_vertices[chain_vertices.size() / 2]];
    if (!ridge_only ||
        !(length < params.short_ridge_sizes * params.sizes->size_at(s.to_global(middle))))
      continue;
    for (const Index e : chain_edges) {
      dropped[e] = true;
      --degree[graph.edges[e].a];
      --degree[graph.edges[e].b];
    }
    ++out.short_ridges_dropped;
    out.short_ridge_edges_dropped += static_cast<std::int64_t>(chain_edges.size());
    if (degree[at] == 1) free_ends.push_back(at);
  }
  if (out.short_ridge_edges_dropped == 0) return;
  remove_edges(s.point_count(), dropped, graph);
}

// Step 1, after the short free ridges (not in the paper): drops the ridges round small islands.
// A connected set of ridge edges with no free end (a loop, or loops sharing points), shorter in
// all than short_ridge_sizes times the size at one of its points, that closes round a patch of
// at most kMaxIslandFaces faces, is not a line: the island is a scan's spike or dimple (noise
// turning one or two faces by over the ridge angle; a 1M-face scanned sphere had 13 of them,
// each a patch of its own with its own corners), which the front meshes over as it meshes over
// a short free ridge. A CAD part's small hole is not an island: its wall is a patch of at least
// six faces. O(E) over the line edges, and a walk of a few faces per loop.
constexpr Index kMaxIslandFaces = 4;
// And an island whose ridges turn by more than this stays: noise turns by a little over the
// ridge angle, and the front cannot mesh over a sharp spike (a pyramid whose faces tilted by
// about 68°, its ridges turning by up to 158°, stopped it).
constexpr double kMaxIslandTurnDeg = 60.0;

// `joined`: the input edges dropped, as (a, b) with a < b, which the patches are joined across.
void drop_small_island_ridges(const DiscreteSurface& s, const FeatureParams& params,
                              LineGraph& graph, SurfaceFeatures& out,
                              absl::flat_hash_set<std::pair<Index, Index>>& joined) {
  if (params.sizes == nullptr || graph.edges.empty()) return;
  const std::vector<Point>& p = s.local_points();
  const std::vector<Triangle>& t = s.triangles();
  const double cos_max_turn = cos_degrees(kMaxIslandTurnDeg);
  // The line edges by face, to walk a patch without crossing them.
  absl::flat_hash_set<std::pair<Index, Index>> line_edge;
  for (const LineEdge& e : graph.edges) line_edge.insert({e.a, e.b});
  const auto on_line = [&](Index f, int k) {
    const Index a = t[f][k], b = t[f][(k + 1) % 3];
    return line_edge.contains({std::min(a, b), std::max(a, b)});
  };
  // At most kMaxIslandFaces faces reached from `start` without crossing a line edge?
  std::vector<Index> walk;
  const auto island_from = [&](Index start) {
    walk.assign(1, start);
    for (std::size_t i = 0; i < walk.size(); ++i)
      for (int k = 0; k < 3; ++k) {
        const Index g = s.neighbours().across[walk[i]][k];
        if (g == kInvalidIndex || on_line(walk[i], k)) continue;
        if (std::find(walk.begin(), walk.end(), g) != walk.end()) continue;
        walk.push_back(g);
        if (walk.size() > static_cast<std::size_t>(kMaxIslandFaces)) return false;
      }
    return true;
  };
  std::vector<bool> reached(graph.edges.size(), false);
  std::vector<bool> dropped(graph.edges.size(), false);
  std::vector<Index> stack, edges;
  for (Index first = 0; first < static_cast<Index>(graph.edges.size()); ++first) {
    if (reached[first]) continue;
    // The connected set of line edges through `first`.
    edges.clear();
    stack.assign(1, first);
    reached[first] = true;
    bool ridges_only = true, free_end = false;
    double length = 0.0;
    while (!stack.empty()) {
      const Index e = stack.back();
      stack.pop_back();
      edges.push_back(e);
      ridges_only = ridges_only && graph.edges[e].kinds == kRidgeEdge;
      length += distance(p[graph.edges[e].a], p[graph.edges[e].b]);
      for (const Index v : {graph.edges[e].a, graph.edges[e].b}) {
        free_end = free_end || graph.degree(v) == 1;
        for (Index i = graph.offsets[v]; i < graph.offsets[v + 1]; ++i)
          if (const Index n = graph.incident[i]; !reached[n]) {
            reached[n] = true;
            stack.push_back(n);
          }
      }
    }
    if (!ridges_only || free_end || edges.size() > 2 * static_cast<std::size_t>(kMaxIslandFaces) + 4)
      continue;
    // A ridge edge has two faces; the turn across it read from the first's side.
    const bool gentle = std::all_of(edges.begin(), edges.end(), [&](Index e) {
      const Index f = graph.edges[e].faces[0];
      for (int k = 0; k < 3; ++k) {
        const Index u = t[f][k], w = t[f][(k + 1) % 3];
        if (std::min(u, w) == graph.edges[e].a && std::max(u, w) == graph.edges[e].b)
          return turn_cosine(s, f, k) >= cos_max_turn;
      }
      return false;
    });
    if (!gentle) continue;
    const Point& some = p[graph.edges[first].a];
    if (!(length < params.short_ridge_sizes * params.sizes->size_at(s.to_global(some)))) continue;
    const std::vector<Index>& faces = graph.edges[first].faces;
    if (faces.size() != 2 || !(island_from(faces[0]) || island_from(faces[1]))) continue;
    for (const Index e : edges) {
      dropped[e] = true;
      joined.insert({graph.edges[e].a, graph.edges[e].b});
    }
    ++out.island_ridges_dropped;
    out.island_ridge_edges_dropped += static_cast<std::int64_t>(edges.size());
  }
  if (out.island_ridges_dropped == 0) return;
  remove_edges(s.point_count(), dropped, graph);
}

// Step 2: the CornerKind bits of every vertex (0: not a corner).
std::vector<std::uint8_t> corner_kinds(const DiscreteSurface& s, const LineGraph& graph,
                                       double cos_turn) {
  std::vector<std::uint8_t> kinds(s.point_count(), 0);
  for (Index v = 0; v < s.point_count(); ++v) {
    const Index degree = graph.degree(v);
    if (degree == 1) kinds[v] = kLineEnd;
    if (degree >= 3) kinds[v] = kJunction;
    if (degree != 2) continue;
    const Index u = graph.other(graph.incident[graph.offsets[v]], v);
    const Index w = graph.other(graph.incident[graph.offsets[v] + 1], v);
    const Point& pv = s.local_points()[v];
    const Point in = sub(pv, s.local_points()[u]), out = sub(s.local_points()[w], pv);
    // The turn is the angle between the incoming and outgoing directions; a NaN (coincident
    // points) is no turn.
    if (dot(in, out) < cos_turn * norm(in) * norm(out)) kinds[v] = kTurn;
  }
  return kinds;
}

// Step 3: follows line edges from corner `start` along `first_edge` to the next corner.
DiscreteLine chain(const LineGraph& graph, const std::vector<std::uint8_t>& corner, Index start,
                   Index first_edge, std::vector<bool>& used, std::vector<Index>& line_edges) {
  DiscreteLine line;
  line.vertices.push_back(start);
  Index at = start, edge = first_edge;
  while (true) {
    used[edge] = true;
    line_edges.push_back(edge);
    line.kinds |= graph.edges[edge].kinds;
    at = graph.other(edge, at);
    line.vertices.push_back(at);
    if (corner[at] != 0) break;
    // A vertex that is not a corner has exactly two line edges: leave by the other one.
    const Index e0 = graph.incident[graph.offsets[at]];
    edge = e0 == edge ? graph.incident[graph.offsets[at] + 1] : e0;
  }
  line.closed = line.vertices.front() == line.vertices.back();
  return line;
}

// Step 4: patches as connected components across edges that are not line edges.
// Faces are joined across edges that are not line edges: no ridge or tag edge, or one of
// `joined` (the ridges round islands that were dropped; the short free ridges dropped join
// nothing, a free end's two sides being one patch already). Once `cancel` is stopped no face is
// joined to another any more (the labels are then of no use: the caller checks
// cancel.stopped()), so that the rest of the walk is quick.
void find_patches(const DiscreteSurface& s, double cos_ridge,
                  const absl::flat_hash_set<std::pair<Index, Index>>& joined,
                  SurfaceFeatures& out, CancelCheck& cancel) {
  std::vector<Index> label;
  const Index count = label_components(
      s.neighbours(),
      [&](Index t, int k) {
        if (cancel.due()) return false;
        if (two_face_edge_kinds(s, cos_ridge, t, k) == 0) return true;
        if (joined.empty()) return false;
        const Index a = s.triangles()[t][k], b = s.triangles()[t][(k + 1) % 3];
        return joined.contains({std::min(a, b), std::max(a, b)});
      },
      label);
  out.face_patch.assign(s.face_count(), PatchId{kInvalidIndex});
  out.patches.reserve(static_cast<std::size_t>(count));
  for (Index f = 0; f < s.face_count(); ++f) {
    if (label[f] == static_cast<Index>(out.patches.size()))  // the component's lowest face
      out.patches.push_back({s.tags()[f], 0, FaceId{f}, {}});
    out.face_patch[f] = PatchId{label[f]};
    ++out.patches[label[f]].face_count;
  }
}

absl::Status check_params(const FeatureParams& params) {
  if (!(params.ridge_angle_deg > 0.0 && params.ridge_angle_deg < 180.0)) {
    return absl::InvalidArgumentError(absl::StrFormat(
        "surface features: ridge_angle_deg %g is not in (0, 180)", params.ridge_angle_deg));
  }
  if (!(params.corner_angle_deg > 0.0 && params.corner_angle_deg <= 180.0)) {
    return absl::InvalidArgumentError(absl::StrFormat(
        "surface features: corner_angle_deg %g is not in (0, 180]", params.corner_angle_deg));
  }
  return absl::OkStatus();
}

}  // namespace

absl::StatusOr<SurfaceFeatures> find_surface_features(const DiscreteSurface& surface,
                                                      const FeatureParams& params,
                                                      Progress& progress) {
  if (absl::Status status = check_params(params); !status.ok()) return status;
  const double cos_ridge = cos_degrees(params.ridge_angle_deg);
  CancelCheck cancel(progress);
  LineGraph graph = collect_line_edges(surface, cos_ridge, cancel);
  if (cancel.stopped()) return absl::CancelledError("surface features: cancelled");
  SurfaceFeatures out;
  drop_short_free_ridges(surface, params, graph, out);
  absl::flat_hash_set<std::pair<Index, Index>> joined;
  drop_small_island_ridges(surface, params, graph, out, joined);
  if (progress.cancelled()) return absl::CancelledError("surface features: cancelled");
  std::vector<std::uint8_t> corner =
      corner_kinds(surface, graph, cos_degrees(params.corner_angle_deg));

  out.line_edge_count = static_cast<std::int64_t>(graph.edges.size());
  std::vector<bool> used(graph.edges.size(), false);
  std::vector<std::vector<Index>> edges_of_line;
  const auto chain_from = [&](Index v) {
    for (Index i = graph.offsets[v]; i < graph.offsets[v + 1]; ++i) {
      if (used[graph.incident[i]]) continue;
      edges_of_line.emplace_back();
      out.lines.push_back(chain(graph, corner, v, graph.incident[i], used, edges_of_line.back()));
    }
  };
  for (Index v = 0; v < surface.point_count(); ++v) {
    if (corner[v] != 0) chain_from(v);
  }
  // What is left are loops of two-edge vertices; ascending, the first vertex met of each loop is
  // its smallest.
  for (Index v = 0; v < surface.point_count(); ++v) {
    if (graph.degree(v) != 2 || used[graph.incident[graph.offsets[v]]]) continue;
    corner[v] = kLoopStart;
    chain_from(v);
  }
  if (progress.cancelled()) return absl::CancelledError("surface features: cancelled");

  std::vector<Index> corner_index(surface.point_count(), kInvalidIndex);
  for (Index v = 0; v < surface.point_count(); ++v) {
    if (corner[v] == 0) continue;
    corner_index[v] = static_cast<Index>(out.corners.size());
    out.corners.push_back({v, corner[v], {}});
  }
  find_patches(surface, cos_ridge, joined, out, cancel);
  if (cancel.stopped()) return absl::CancelledError("surface features: cancelled");
  for (Index l = 0; l < static_cast<Index>(out.lines.size()); ++l) {
    DiscreteLine& line = out.lines[l];
    out.corners[corner_index[line.vertices.front()]].lines.push_back(LineId{l});
    out.corners[corner_index[line.vertices.back()]].lines.push_back(LineId{l});
    for (Index e : edges_of_line[l]) {
      for (Index f : graph.edges[e].faces) line.patches.push_back(out.face_patch[f]);
    }
    std::sort(line.patches.begin(), line.patches.end());
    line.patches.erase(std::unique(line.patches.begin(), line.patches.end()), line.patches.end());
    for (PatchId p : line.patches) out.patches[index_of(p)].lines.push_back(LineId{l});
  }
  return out;
}

}  // namespace afmesh
