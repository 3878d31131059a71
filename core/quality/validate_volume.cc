// validate_volume_mesh: the checks of a tetrahedral mesh, in the order validate.h lists them.
#include <algorithm>
#include <cmath>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "absl/strings/str_format.h"
#include "core/geometry/predicates.h"
#include "core/quality/boundary_match.h"
#include "core/quality/compensated_sum.h"
#include "core/quality/measures.h"
#include "core/quality/mesh_topology.h"
#include "core/quality/validate.h"
#include "core/quality/validate_common.h"

namespace afmesh {
namespace {

std::vector<Index> tets_with_distinct_indices(const std::vector<Tet>& tets) {
  std::vector<Index> ids;
  ids.reserve(tets.size());
  for (Index t = 0; t < static_cast<Index>(tets.size()); ++t) {
    if (has_distinct_indices(tets[t])) ids.push_back(t);
  }
  return ids;
}

// Owning tets of boundary faces `ids`, ascending and without repeats.
std::vector<Index> owners(const BoundaryFaces& boundary, const std::vector<Index>& ids) {
  std::vector<Index> tets;
  for (Index i : ids) tets.push_back(boundary.tets[i]);
  std::sort(tets.begin(), tets.end());
  tets.erase(std::unique(tets.begin(), tets.end()), tets.end());
  return tets;
}

// positive_volumes: four distinct points and exact orient3d(a, b, c, d) > 0 for every tet.
Check check_positive_volumes(const Mesh& mesh, const ValidationParams& params, CancelCheck& stop) {
  CheckBuilder builder(check::kPositiveVolumes, params);
  for (Index t = 0; t < static_cast<Index>(mesh.tets.size()); ++t) {
    if (stop.due()) break;
    const Tet& tet = mesh.tets[t];
    if (!has_distinct_indices(tet)) {
      builder.add([&] {
        return Finding{absl::StrFormat("tet %d repeats a point (%d,%d,%d,%d): zero volume", t,
                                       tet[0], tet[1], tet[2], tet[3]),
                       {tet.begin(), tet.end()}, {}, {t}};
      });
      continue;
    }
    const int sign = orient3d(mesh.points[tet[0]], mesh.points[tet[1]], mesh.points[tet[2]],
                              mesh.points[tet[3]]);
    if (sign > 0) continue;
    builder.add([&] {
      return Finding{absl::StrFormat("tet %d has non-positive volume (orient3d = %d)", t, sign),
                     {tet.begin(), tet.end()}, {}, {t}};
    });
  }
  return builder.finish(
      absl::StrFormat("all %d tets have positive volume (exact orient3d)", mesh.tets.size()),
      absl::StrFormat("%d of %d %s non-positive volume", builder.count(), mesh.tets.size(),
                      plural(builder.count(), "tet has", "tets have")));
}

// Tet ids of face uses, in their order.
std::vector<Index> tets_of(std::span<const FaceUse> uses) {
  std::vector<Index> tets;
  for (const FaceUse& use : uses) tets.push_back(use.tet);
  return tets;
}

// face_sharing: a face in more than two tets, or in two with the same orientation. Collects in
// `boundary` the faces of exactly one tet on the way (the tets' boundary, in key order).
Check check_face_sharing(const std::vector<Tet>& tets, const std::vector<Index>& tet_ids,
                         const ValidationParams& params, BoundaryFaces& boundary,
                         CancelCheck& stop) {
  CheckBuilder builder(check::kFaceSharing, params);
  std::int64_t interior = 0;
  for_each_tet_face(
      tets, tet_ids,
      [&](std::span<const FaceUse> uses) {
        const Triangle& key = uses[0].key;
        if (uses.size() == 1) {
          boundary.triangles.push_back(tet_face(tets[uses[0].tet], uses[0].corner));
          boundary.tets.push_back(uses[0].tet);
        } else if (uses.size() > 2) {
          builder.add([&] {
            const std::vector<Index> sharing = tets_of(uses);
            return Finding{absl::StrFormat("face %s shared by tets %s", format_triple(key),
                                           join_indices(sharing)),
                           {key.begin(), key.end()},
                           {},
                           sharing};
          });
        } else if (uses[0].even == uses[1].even) {
          builder.add([&] {
            const std::vector<Index> sharing = tets_of(uses);
            return Finding{absl::StrFormat("face %s of tets %s with the same orientation",
                                           format_triple(key), join_indices(sharing)),
                           {key.begin(), key.end()},
                           {},
                           sharing};
          });
        } else {
          ++interior;
        }
      },
      &stop);
  return builder.finish(
      absl::StrFormat("%d interior faces each shared by two tets with opposite orientations, "
                      "%d boundary faces",
                      interior, boundary.triangles.size()),
      absl::StrFormat("%d %s shared by more than two tets or with the same orientation",
                      builder.count(), plural(builder.count(), "face", "faces")));
}

// boundary_surface: the tets' boundary faces form a closed, manifold, consistently oriented
// surface.
Check check_boundary_surface(const BoundaryFaces& boundary, const ValidationParams& params) {
  const TriangleTopology topology = analyze_triangle_topology(boundary.triangles);
  CheckBuilder builder(check::kBoundarySurface, params);
  auto edge_finding = [&](const EdgeGroup& e, std::string_view what) {
    const std::vector<Index> tets = owners(boundary, e.triangles);
    return Finding{absl::StrFormat("boundary edge (%d,%d) is used by %d boundary %s (of %s %s)%s",
                                   e.a, e.b, e.triangles.size(),
                                   plural(e.triangles.size(), "face", "faces"),
                                   plural(tets.size(), "tet", "tets"), join_indices(tets), what),
                   {e.a, e.b}, {}, tets};
  };
  for (const EdgeGroup& e : topology.open_edges) {
    builder.add([&] { return edge_finding(e, ": the boundary has a hole"); });
  }
  for (const EdgeGroup& e : topology.nonmanifold_edges) {
    builder.add([&] { return edge_finding(e, ": non-manifold edge"); });
  }
  for (const EdgeGroup& e : topology.misoriented_edges) {
    builder.add([&] {
      const std::vector<Index> tets = owners(boundary, e.triangles);
      return Finding{absl::StrFormat("boundary faces of %s %s traverse edge (%d,%d) in the same "
                                     "direction",
                                     plural(tets.size(), "tet", "tets"), join_indices(tets), e.a,
                                     e.b),
                     {e.a, e.b}, {}, tets};
    });
  }
  for (const VertexFans& v : topology.nonmanifold_vertices) {
    builder.add([&] {
      const std::vector<Index> tets = owners(boundary, v.triangles);
      return Finding{
          absl::StrFormat("boundary vertex %d is non-manifold: its %d boundary faces form %d "
                          "separate fans (tets %s)",
                          v.vertex, v.triangles.size(), v.fan_count, join_indices(tets)),
          {v.vertex}, {}, tets};
    });
  }
  return builder.finish(
      absl::StrFormat("the %d boundary faces form a closed, manifold, consistently oriented "
                      "surface",
                      boundary.triangles.size()),
      absl::StrFormat("%d %s in the surface of the %d boundary faces", builder.count(),
                      plural(builder.count(), "defect", "defects"), boundary.triangles.size()));
}

// volume_balance: sum of signed tet volumes against the enclosed volume of the boundary.
Check check_volume_balance(const Mesh& mesh, const BoundaryFaces& faces, const Mesh* boundary,
                           const ValidationParams& params, CancelCheck& stop) {
  if (boundary != nullptr && !indices_and_coordinates_ok(boundary->points, boundary->triangles)) {
    return not_run(check::kVolumeBalance,
                   "the boundary mesh has point indices out of range or non-finite coordinates");
  }
  CompensatedSum tet_sum, tet_scale;
  for (const Tet& t : mesh.tets) {
    if (stop.due()) break;
    const double v = tet_signed_volume(mesh.points[t[0]], mesh.points[t[1]], mesh.points[t[2]],
                                       mesh.points[t[3]]);
    tet_sum.add(v);
    tet_scale.add(std::abs(v));
  }
  double boundary_scale = 0.0;
  const double enclosed =
      boundary != nullptr ? enclosed_volume(boundary->points, boundary->triangles, &boundary_scale)
                          : enclosed_volume(mesh.points, faces.triangles, &boundary_scale);
  const std::string_view source =
      boundary != nullptr ? "the boundary mesh" : "the tets' boundary faces";
  const double difference = tet_sum.value() - enclosed;
  const double tolerance = params.volume_relative_tolerance * (tet_scale.value() + boundary_scale);
  CheckBuilder builder(check::kVolumeBalance, params);
  if (!(std::abs(difference) <= tolerance)) {
    builder.add([&] {
      return Finding{absl::StrFormat("the tets' volumes sum to %.17g but %s encloses %.17g "
                                     "(difference %.3g, tolerance %.3g)",
                                     tet_sum.value(), source, enclosed, difference, tolerance)};
    });
  }
  return builder.finish(
      absl::StrFormat("the tets' volumes sum to %.17g, the volume %s encloses (difference %.3g, "
                      "tolerance %.3g)",
                      tet_sum.value(), source, difference, tolerance),
      absl::StrFormat("the tets' volumes differ from the volume %s encloses by %.3g", source,
                      difference));
}

// The checks of validate_volume_mesh in order; once `stop` finds the caller cancelled, the
// report ends where it stopped (the caller reports CANCELLED instead).
ValidationReport volume_checks(const Mesh& mesh, const Mesh* boundary,
                               const ValidationParams& params, CancelCheck& stop) {
  ValidationReport report;
  report.checks.push_back(
      check_element_indices(mesh.tets, mesh.tet_tags.size(), mesh.points.size(), params));
  if (!all_indices_in_range(mesh.tets, mesh.points.size())) {
    for (std::string_view name :
         {check::kFiniteCoordinates, check::kPositiveVolumes, check::kFaceSharing,
          check::kBoundarySurface, check::kBoundaryMatch, check::kVolumeBalance,
          check::kEnvironmentGap, check::kUnusedPoints}) {
      if (name == check::kEnvironmentGap && params.point_environments.empty()) continue;
      report.checks.push_back(not_run(name, "the tets' indices are invalid"));
    }
    return report;
  }
  report.checks.push_back(check_finite_coordinates(mesh.points, params));
  const bool finite = report.checks.back().passed();

  report.checks.push_back(finite ? check_positive_volumes(mesh, params, stop)
                                 : not_run(check::kPositiveVolumes, kNeedsFinite));
  if (stop.stopped()) return report;
  BoundaryFaces boundary_faces;
  report.checks.push_back(check_face_sharing(mesh.tets, tets_with_distinct_indices(mesh.tets),
                                             params, boundary_faces, stop));
  if (stop.look()) return report;
  report.checks.push_back(check_boundary_surface(boundary_faces, params));
  report.checks.push_back(boundary != nullptr
                              ? check_boundary_match(mesh, boundary_faces, *boundary, params)
                              : not_run(check::kBoundaryMatch, "no boundary mesh given"));
  if (stop.look()) return report;
  report.checks.push_back(finite
                              ? check_volume_balance(mesh, boundary_faces, boundary, params, stop)
                              : not_run(check::kVolumeBalance, kNeedsFinite));
  if (stop.stopped()) return report;
  if (!params.point_environments.empty()) {
    report.checks.push_back(check_environment_gap(mesh, params));
  }
  report.checks.push_back(check_unused_points(mesh.points.size(), mesh.tets, params));
  return report;
}

}  // namespace

ValidationReport validate_volume_mesh(const Mesh& mesh, const Mesh* boundary,
                                      const ValidationParams& params) {
  CancelCheck never(no_progress());
  return volume_checks(mesh, boundary, params, never);
}

absl::StatusOr<ValidationReport> validate_volume_mesh(const Mesh& mesh, const Mesh* boundary,
                                                      const ValidationParams& params,
                                                      Progress& progress) {
  CancelCheck stop(progress);
  ValidationReport report = volume_checks(mesh, boundary, params, stop);
  if (stop.stopped()) return absl::CancelledError("validation of the volume mesh cancelled");
  return report;
}

}  // namespace afmesh
