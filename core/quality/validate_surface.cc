// validate_surface: the checks of a closed triangle surface, in the order validate.h lists them.
#include <algorithm>
#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "absl/strings/str_format.h"
#include "core/geometry/intersect.h"
#include "core/geometry/predicates.h"
#include "core/quality/mesh_topology.h"
#include "core/quality/validate.h"
#include "core/quality/validate_common.h"
#include "core/spatial/aabb_tree.h"
#include "core/spatial/box.h"

namespace afmesh {
namespace {

// The reason of the checks that cannot run on out-of-range triangle indices.
constexpr std::string_view kBadTriangleIndices = "the triangles' indices are invalid";

// The triangles with three distinct points, renumbered 0..n-1: those that take part in the
// topology checks. Collinear ones among them are kept there (they close the surface like any
// other) but left out of the intersection test.
struct ProperTriangles {
  std::vector<Triangle> triangles;  // n×3
  std::vector<Index> ids;           // ids[i]: index of triangles[i] in the surface
  std::vector<bool> collinear;      // n: exactly collinear points
};

// Original triangle ids of positions `positions` in `proper`, ascending.
std::vector<Index> original_ids(const ProperTriangles& proper,
                                const std::vector<Index>& positions) {
  std::vector<Index> ids;
  for (Index i : positions) ids.push_back(proper.ids[i]);
  std::sort(ids.begin(), ids.end());
  return ids;
}

// non_degenerate: no repeated point, no collinear points (exact). With non-finite coordinates
// only repeated points are looked for. Collects the triangles with distinct points into
// `proper`.
Check check_non_degenerate(const Mesh& surface, bool finite, const ValidationParams& params,
                           ProperTriangles& proper) {
  CheckBuilder builder(check::kNonDegenerate, params);
  for (Index t = 0; t < static_cast<Index>(surface.triangles.size()); ++t) {
    const Triangle& tri = surface.triangles[t];
    std::string_view problem;
    if (!has_distinct_indices(tri)) {
      problem = "repeats a point";
    } else {
      const bool flat = finite && collinear(surface.points[tri[0]], surface.points[tri[1]],
                                            surface.points[tri[2]]);
      proper.triangles.push_back(tri);
      proper.ids.push_back(t);
      proper.collinear.push_back(flat);
      if (!flat) continue;
      problem = "has collinear points";
    }
    builder.add([&] {
      return Finding{absl::StrFormat("triangle %d %s is degenerate: it %s", t, format_triple(tri),
                                     problem),
                     {tri.begin(), tri.end()}, {t}, {}};
    });
  }
  return builder.finish(
      absl::StrFormat("no degenerate triangle among %d (exact collinearity)",
                      surface.triangles.size()),
      absl::StrFormat("%d degenerate %s", builder.count(),
                      plural(builder.count(), "triangle", "triangles")));
}

// Finding for an edge and the triangles using it.
Finding edge_finding(const EdgeGroup& e, const ProperTriangles& proper, std::string_view lead) {
  const std::vector<Index> ids = original_ids(proper, e.triangles);
  return Finding{absl::StrFormat("%sedge (%d,%d) used by %d %s (%s %s)", lead, e.a, e.b,
                                 ids.size(), plural(ids.size(), "triangle", "triangles"),
                                 plural(ids.size(), "triangle", "triangles"), join_indices(ids)),
                 {e.a, e.b}, ids, {}};
}

// closed: no edge of a single triangle.
Check check_closed(const TriangleTopology& topology, const ProperTriangles& proper,
                   const ValidationParams& params) {
  CheckBuilder builder(check::kClosed, params);
  for (const EdgeGroup& e : topology.open_edges) {
    builder.add([&] { return edge_finding(e, proper, "hole: "); });
  }
  return builder.finish(
      absl::StrFormat("every one of the %d edges is used by at least two triangles",
                      topology.edge_count),
      absl::StrFormat("%d %s used by only one triangle (holes)", builder.count(),
                      plural(builder.count(), "edge", "edges")));
}

// manifold_edges: no edge of three or more triangles.
Check check_manifold_edges(const TriangleTopology& topology, const ProperTriangles& proper,
                           const ValidationParams& params) {
  CheckBuilder builder(check::kManifoldEdges, params);
  for (const EdgeGroup& e : topology.nonmanifold_edges) {
    builder.add([&] { return edge_finding(e, proper, "non-manifold "); });
  }
  return builder.finish(
      "no edge is used by more than two triangles",
      absl::StrFormat("%d %s used by more than two triangles", builder.count(),
                      plural(builder.count(), "edge", "edges")));
}

// manifold_vertices: one fan of triangles around each vertex.
Check check_manifold_vertices(const TriangleTopology& topology, const ProperTriangles& proper,
                              const ValidationParams& params) {
  CheckBuilder builder(check::kManifoldVertices, params);
  for (const VertexFans& v : topology.nonmanifold_vertices) {
    builder.add([&] {
      const std::vector<Index> ids = original_ids(proper, v.triangles);
      return Finding{absl::StrFormat("vertex %d is non-manifold: its %d triangles form %d "
                                     "separate fans (triangles %s)",
                                     v.vertex, ids.size(), v.fan_count, join_indices(ids)),
                     {v.vertex}, ids, {}};
    });
  }
  return builder.finish(
      "the triangles around every vertex form a single fan",
      absl::StrFormat("%d non-manifold %s", builder.count(),
                      plural(builder.count(), "vertex", "vertices")));
}

// consistent_orientation: the two triangles at an edge traverse it in opposite directions.
Check check_consistent_orientation(const TriangleTopology& topology, const ProperTriangles& proper,
                                   const ValidationParams& params) {
  CheckBuilder builder(check::kConsistentOrientation, params);
  for (const EdgeGroup& e : topology.misoriented_edges) {
    builder.add([&] {
      const std::vector<Index> ids = original_ids(proper, e.triangles);
      return Finding{absl::StrFormat("triangles %s traverse edge (%d,%d) in the same direction",
                                     join_indices(ids), e.a, e.b),
                     {e.a, e.b}, ids, {}};
    });
  }
  return builder.finish(
      "every edge of two triangles is traversed in opposite directions",
      absl::StrFormat("%d %s traversed in the same direction by both of %s triangles",
                      builder.count(), plural(builder.count(), "edge", "edges"),
                      plural(builder.count(), "its", "their")));
}

// environments: one environment id per triangle, none negative. Returns the check; `usable`
// tells whether no_self_intersections may use the ids.
Check check_environments(const Mesh& surface, const ValidationParams& params, bool& usable) {
  const std::span<const std::int32_t> env = params.face_environments;
  CheckBuilder builder(check::kEnvironments, params);
  if (env.size() != surface.triangles.size()) {
    builder.add([&] {
      return Finding{absl::StrFormat("%d face environments given for %d triangles", env.size(),
                                     surface.triangles.size())};
    });
  } else {
    for (Index t = 0; t < static_cast<Index>(env.size()); ++t) {
      if (env[t] >= 0) continue;
      builder.add([&] {
        return Finding{absl::StrFormat("triangle %d has environment %d: ids must be >= 0 "
                                       "(0 = none)",
                                       t, env[t]),
                       {}, {t}, {}};
      });
    }
  }
  usable = builder.count() == 0;
  std::vector<std::int32_t> ids;
  if (usable) {
    for (const std::int32_t e : env) {
      if (e > 0) ids.push_back(e);
    }
    std::sort(ids.begin(), ids.end());
    ids.erase(std::unique(ids.begin(), ids.end()), ids.end());
  }
  return builder.finish(
      absl::StrFormat("%d crossing %s over the %d triangles", ids.size(),
                      plural(ids.size(), "environment", "environments"), env.size()),
      absl::StrFormat("%d invalid face environment %s", builder.count(),
                      plural(builder.count(), "entry", "entries")));
}

// True when an intersection of triangles t and u (surface ids) is allowed: both lie in positive
// environments and these differ (paper §2: the two sides of a thin structure may cross).
bool crossing_allowed(std::span<const std::int32_t> env, Index t, Index u) {
  return !env.empty() && env[t] > 0 && env[u] > 0 && env[t] != env[u];
}

// What to do about triangles t and u of environments et and eu that intersect, though only two
// different positive environments may cross: the faces to tag, and with what.
std::string environment_crossing_message(Index t, Index u, std::int32_t et, std::int32_t eu) {
  if ((et == 0) != (eu == 0)) {
    const Index none = et == 0 ? t : u, some = et == 0 ? u : t;
    const std::int32_t side = std::max(et, eu);
    return absl::StrFormat(
        "triangles %d and %d intersect: triangle %d has no environment and crosses triangle %d "
        "of environment %d (only two different positive environments may cross); tag "
        "triangle %d with a positive environment other than %d, the one of its own side",
        t, u, none, some, side, none, side);
  }
  if (et == 0) {
    return absl::StrFormat(
        "triangles %d and %d intersect and have no environment (only two different positive "
        "environments may cross); tag them with the environments of their sides",
        t, u);
  }
  return absl::StrFormat(
      "triangles %d and %d intersect within environment %d (only two different positive "
      "environments may cross): a side crosses itself, or the two sides of a thin region share "
      "that environment",
      t, u, et);
}

// no_self_intersections: exact test of every pair of triangles whose boxes overlap. `env` is
// empty, or valid face environments whose cross-environment intersections are allowed.
Check check_self_intersections(const Mesh& surface, const ProperTriangles& proper,
                               std::span<const std::int32_t> env, const ValidationParams& params,
                               CancelCheck& stop) {
  std::vector<Box> boxes = triangle_boxes(surface.points, proper.triangles);
  std::int64_t tested = 0;
  for (std::size_t i = 0; i < boxes.size(); ++i) {
    if (proper.collinear[i]) {
      boxes[i] = empty_box();  // the tree leaves empty boxes out
    } else {
      ++tested;
    }
  }
  const AabbTree tree(std::move(boxes));
  std::vector<std::pair<Index, Index>> hits;
  std::int64_t allowed = 0;
  tree.for_each_overlapping_pair(
      [&](Index i, Index j) {
        if (triangles_intersect_improperly(surface.points, proper.triangles[i],
                                           proper.triangles[j])) {
          if (crossing_allowed(env, proper.ids[i], proper.ids[j])) {
            ++allowed;
          } else {
            hits.emplace_back(std::min(proper.ids[i], proper.ids[j]),
                              std::max(proper.ids[i], proper.ids[j]));
          }
        }
      },
      &stop);
  std::sort(hits.begin(), hits.end());
  CheckBuilder builder(check::kNoSelfIntersections, params);
  for (const auto& hit : hits) {
    // Named copies, not a structured binding: clang 14 (the fuzz preset) cannot capture those.
    const Index t = hit.first, u = hit.second;
    builder.add([&] {
      if (env.empty()) {
        return Finding{absl::StrFormat("triangles %d and %d intersect", t, u), {}, {t, u}, {}};
      }
      return Finding{environment_crossing_message(t, u, env[t], env[u]), {}, {t, u}, {}};
    });
  }
  const std::string allowed_note =
      env.empty() ? std::string()
                  : absl::StrFormat("; %d crossing %s of two different environments allowed",
                                    allowed, plural(allowed, "pair", "pairs"));
  const std::string clean =
      env.empty() ? absl::StrFormat("no two of the %d non-degenerate triangles intersect", tested)
                  : absl::StrFormat("no forbidden intersection among the %d non-degenerate "
                                    "triangles%s",
                                    tested, allowed_note);
  return builder.finish(clean, absl::StrFormat("%d intersecting triangle %s%s", builder.count(),
                                               plural(builder.count(), "pair", "pairs"),
                                               allowed_note));
}

// positive_enclosed_volume: the volume enclosed by the (closed, oriented) surface is positive.
Check check_enclosed_volume(const Mesh& surface, const ProperTriangles& proper,
                            const ValidationParams& params) {
  const double volume = enclosed_volume(surface.points, proper.triangles, nullptr);
  CheckBuilder builder(check::kPositiveEnclosedVolume, params);
  if (!(volume > 0.0)) {
    builder.add([&] {
      return Finding{absl::StrFormat("enclosed volume %.17g is not positive: the triangles' "
                                     "normals point inward",
                                     volume)};
    });
  }
  return builder.finish(absl::StrFormat("enclosed volume %.17g (outward orientation)", volume),
                        absl::StrFormat("enclosed volume %.17g is not positive", volume));
}

// The checks that need the topology of the non-degenerate triangles.
void add_topology_checks(const Mesh& surface, bool finite, const ProperTriangles& proper,
                         const ValidationParams& params, ValidationReport& report,
                         CancelCheck& stop) {
  const TriangleTopology topology = analyze_triangle_topology(proper.triangles);
  if (stop.look()) return;
  report.checks.push_back(check_closed(topology, proper, params));
  report.checks.push_back(check_manifold_edges(topology, proper, params));
  report.checks.push_back(check_manifold_vertices(topology, proper, params));
  report.checks.push_back(check_consistent_orientation(topology, proper, params));
  const bool oriented_closed = topology.open_edges.empty() &&
                               topology.nonmanifold_edges.empty() &&
                               topology.misoriented_edges.empty();
  std::span<const std::int32_t> env;
  if (!params.face_environments.empty()) {
    bool usable = false;
    report.checks.push_back(check_environments(surface, params, usable));
    if (usable) env = params.face_environments;
  }
  report.checks.push_back(finite ? check_self_intersections(surface, proper, env, params, stop)
                                 : not_run(check::kNoSelfIntersections, kNeedsFinite));
  if (stop.stopped()) return;
  if (!finite) {
    report.checks.push_back(not_run(check::kPositiveEnclosedVolume, kNeedsFinite));
  } else if (!oriented_closed) {
    report.checks.push_back(not_run(check::kPositiveEnclosedVolume,
                                    "the surface is not closed, edge-manifold and consistently "
                                    "oriented"));
  } else {
    report.checks.push_back(check_enclosed_volume(surface, proper, params));
  }
}

// The checks of validate_surface in order; once `stop` finds the caller cancelled, the report
// ends where it stopped (the caller reports CANCELLED instead).
ValidationReport surface_checks(const Mesh& surface, const ValidationParams& params,
                                CancelCheck& stop) {
  ValidationReport report;
  report.checks.push_back(check_element_indices(surface.triangles, surface.triangle_tags.size(),
                                                surface.points.size(), params));
  if (!all_indices_in_range(surface.triangles, surface.points.size())) {
    for (std::string_view name :
         {check::kFiniteCoordinates, check::kNonDegenerate, check::kClosed,
          check::kManifoldEdges, check::kManifoldVertices, check::kConsistentOrientation,
          check::kEnvironments, check::kNoSelfIntersections, check::kPositiveEnclosedVolume,
          check::kUnusedPoints}) {
      if (name == check::kEnvironments && params.face_environments.empty()) continue;
      report.checks.push_back(not_run(name, kBadTriangleIndices));
    }
    return report;
  }
  report.checks.push_back(check_finite_coordinates(surface.points, params));
  const bool finite = report.checks.back().passed();
  ProperTriangles proper;
  report.checks.push_back(check_non_degenerate(surface, finite, params, proper));
  if (stop.look()) return report;
  add_topology_checks(surface, finite, proper, params, report, stop);
  if (stop.stopped()) return report;
  report.checks.push_back(check_unused_points(surface.points.size(), surface.triangles, params));
  return report;
}

}  // namespace

ValidationReport validate_surface(const Mesh& surface, const ValidationParams& params) {
  CancelCheck never(no_progress());
  return surface_checks(surface, params, never);
}

absl::StatusOr<ValidationReport> validate_surface(const Mesh& surface,
                                                  const ValidationParams& params,
                                                  Progress& progress) {
  CancelCheck stop(progress);
  ValidationReport report = surface_checks(surface, params, stop);
  if (stop.stopped()) return absl::CancelledError("validation of the surface cancelled");
  return report;
}

absl::StatusOr<Check> check_surface_self_intersections(const Mesh& surface,
                                                       const ValidationParams& params,
                                                       Progress& progress) {
  if (!all_indices_in_range(surface.triangles, surface.points.size()))
    return not_run(check::kNoSelfIntersections, kBadTriangleIndices);
  const bool finite = check_finite_coordinates(surface.points, params).passed();
  if (!finite) return not_run(check::kNoSelfIntersections, kNeedsFinite);
  ProperTriangles proper;
  check_non_degenerate(surface, finite, params, proper);
  std::span<const std::int32_t> env;
  if (!params.face_environments.empty()) {
    bool usable = false;
    const Check environments = check_environments(surface, params, usable);
    if (!usable) return not_run(check::kNoSelfIntersections, environments.summary);
    env = params.face_environments;
  }
  CancelCheck stop(progress);
  Check check = check_self_intersections(surface, proper, env, params, stop);
  if (stop.stopped()) return absl::CancelledError("validation of the surface cancelled");
  return check;
}

}  // namespace afmesh
