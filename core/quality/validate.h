// Validation of volume meshes and closed surfaces: the "quality bar for a mesh we hand out" of
// design.md, as a report a person (or a test) can read.
//
// A report is a list of named checks. Each check has an outcome, a one-line summary and the
// findings behind it; a finding names the elements involved (point, triangle and tet indices)
// both in its message and as index lists. Counts are exact; only the first
// `ValidationParams::max_findings_per_check` findings of a check are kept in detail, and the
// summary then says how many more there are.
//
// Exactness: orientation, degeneracy and intersection checks use the exact predicates of
// core/geometry (predicates.h, intersect.h); topology checks compare indices only. The one
// measurement is the volume balance, compared with a relative tolerance.
//
// Cost: O(n log n) in the number of elements (tet faces bucketed by their smallest vertex and
// sorted within a bucket, edge keys sorted; an AABB tree for self-intersection), never all
// pairs. Findings are ordered by their elements' indices, so a
// report is deterministic.
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "absl/status/statusor.h"
#include "core/common/progress.h"
#include "core/mesh/mesh.h"

namespace afmesh {

enum class CheckOutcome {
  kPassed,   // nothing found
  kWarning,  // findings that do not make the mesh invalid (unused points)
  kFailed,   // findings that make the mesh invalid
  kNotRun,   // a check it depends on failed, or its input was not given; the summary says why
};

// One problem, naming the elements involved. Index lists are in the order the message names
// them; `points` are indices into the validated mesh's points unless the message says
// otherwise, `triangles` into its triangles (or the boundary mesh's), `tets` into its tets.
struct Finding {
  std::string message;
  std::vector<Index> points{};
  std::vector<Index> triangles{};
  std::vector<Index> tets{};
};

struct Check {
  std::string name;  // one of the check names below
  CheckOutcome outcome = CheckOutcome::kPassed;
  std::string summary;
  std::int64_t finding_count = 0;  // exact number of findings
  std::vector<Finding> findings;   // the first min(finding_count, max_findings_per_check)

  // True unless the check failed or could not run.
  bool passed() const {
    return outcome == CheckOutcome::kPassed || outcome == CheckOutcome::kWarning;
  }
};

struct ValidationReport {
  std::vector<Check> checks;

  // True when no check failed. Checks that did not run because an earlier one failed leave
  // the report invalid through that earlier check.
  bool valid() const;
  // The check named `name`, or nullptr.
  const Check* find(std::string_view name) const;
  // Human-readable report: one line per check, then its detailed findings indented.
  std::string to_string() const;
};

struct ValidationParams {
  // Findings kept in detail per check (the count stays exact).
  int max_findings_per_check = 20;
  // Volume balance: |sum of tet volumes - enclosed volume| must be at most this times the sum
  // of the magnitudes of the terms of both sums.
  double volume_relative_tolerance = 1e-9;

  // Crossing environments (paper §2; core/environments). The spans must outlive the call.
  //
  // validate_surface: LFACR, one environment id per triangle (>= 0, 0 = none); empty = none.
  // When given, the `environments` check validates the array and no_self_intersections
  // allows intersections between triangles of two DIFFERENT positive environments (the two
  // sides of a thin structure may cross); intersections within one environment or involving
  // a triangle of environment 0 are still failures.
  std::span<const std::int32_t> face_environments{};
  // validate_volume_mesh: LPOCR, one environment id per point of the mesh (>= -1; -1 = ridge
  // point shared by environments, 0 = none). It may be shorter than the point array: points
  // beyond it (the interior points a mesher added after the front's) count as 0. When given,
  // the `environment_gap` check runs.
  std::span<const std::int32_t> point_environments{};
  // Report tets across a gap as warnings instead of failures (for `afmesh stats`, where the
  // triangle tags read as environments may be patch ids).
  bool environment_gap_warns_only = false;
};

// Check names, in report order.
namespace check {
// Both.
inline constexpr std::string_view kIndices = "indices";  // in range; tag arrays sized right
inline constexpr std::string_view kFiniteCoordinates = "finite_coordinates";
inline constexpr std::string_view kUnusedPoints = "unused_points";  // warning only
// Volume meshes.
inline constexpr std::string_view kPositiveVolumes = "positive_volumes";
inline constexpr std::string_view kFaceSharing = "face_sharing";
inline constexpr std::string_view kBoundarySurface = "boundary_surface";
inline constexpr std::string_view kBoundaryMatch = "boundary_match";
inline constexpr std::string_view kVolumeBalance = "volume_balance";
inline constexpr std::string_view kEnvironmentGap = "environment_gap";  // with point_environments
// Surfaces.
inline constexpr std::string_view kNonDegenerate = "non_degenerate";
inline constexpr std::string_view kClosed = "closed";
inline constexpr std::string_view kManifoldEdges = "manifold_edges";
inline constexpr std::string_view kManifoldVertices = "manifold_vertices";
inline constexpr std::string_view kConsistentOrientation = "consistent_orientation";
inline constexpr std::string_view kEnvironments = "environments";  // with face_environments
inline constexpr std::string_view kNoSelfIntersections = "no_self_intersections";
inline constexpr std::string_view kPositiveEnclosedVolume = "positive_enclosed_volume";
}  // namespace check

// Validates the tets of `mesh` (points N×3, tets K×4; mesh.triangles are not looked at).
// Checks, in order:
//  indices             every tet index in [0, N); tet_tags has K entries.
//  finite_coordinates  every point coordinate finite.
//  positive_volumes    every tet has 4 distinct points and exact orient3d(a, b, c, d) > 0.
//  face_sharing        no face in more than two tets; a face of two tets appears in them with
//                      opposite orientations.
//  boundary_surface    the faces of exactly one tet, oriented outward, form a closed, manifold
//                      (edges and vertices), consistently oriented surface.
//  boundary_match      (only with `boundary`) the tets' boundary faces equal the boundary
//                      mesh's triangles as oriented triples, counted with multiplicity; missing
//                      and extra faces are reported. Points are matched by index when the
//                      boundary's points are, exactly and in order, the first points of `mesh`
//                      (as when the volume mesh grows from its boundary); otherwise by exact
//                      coordinates (a hash map; -0.0 equals 0.0; among volume points with equal
//                      coordinates the lowest index is used). The summary says which; the
//                      vertex triples in its findings are volume-mesh point indices.
//  volume_balance      sum of signed tet volumes equals the volume enclosed by the boundary
//                      mesh (or, without one, by the tets' boundary faces), computed by the
//                      divergence theorem with compensated sums, within the relative tolerance.
//  environment_gap     (only with params.point_environments) no tet joins two different positive
//                      environments through the gap of a thin structure: among a tet's four
//                      points, those of positive environment all carry the same id. Ridge points
//                      (-1) and points of no environment (0) may join any. Findings name the
//                      tet, its points and the two environments; entries < -1 or an array longer
//                      than the point array are findings too. Paper §2; design.md, "no tet joins
//                      the two sides of a thin structure".
//  unused_points       points that no tet uses: a warning, since such points are harmless to a
//                      solver but usually a sign of an incomplete mesh.
// Tets with repeated indices are reported by positive_volumes and left out of the face checks.
ValidationReport validate_volume_mesh(const Mesh& mesh, const Mesh* boundary = nullptr,
                                      const ValidationParams& params = {});
// The same checks, stopping within a few milliseconds once progress.cancelled() turns true:
// CANCELLED then, and no report (for the server's job, on millions of tets).
absl::StatusOr<ValidationReport> validate_volume_mesh(const Mesh& mesh, const Mesh* boundary,
                                                      const ValidationParams& params,
                                                      Progress& progress);

// Validates `surface.triangles` (M×3) over `surface.points` (N×3) as a closed surface bounding
// a volume (surface.tets are not looked at). Checks, in order:
//  indices                   every triangle index in [0, N); triangle_tags has M entries.
//  finite_coordinates        every point coordinate finite.
//  non_degenerate            no triangle repeats a point or has collinear points (exact).
//  closed                    every edge is used by at least two triangles (holes are edges of
//                            one triangle).
//  manifold_edges            no edge is used by more than two triangles.
//  manifold_vertices         the triangles around each vertex form a single fan.
//  consistent_orientation    the two triangles at an edge traverse it in opposite directions.
//  environments              (only with params.face_environments) one id per triangle, each
//                            >= 0; the summary counts the environments.
//  no_self_intersections     no two triangles intersect beyond their shared vertices or edge
//                            (exact, over the pairs of overlapping boxes of an AABB tree). With
//                            valid face_environments, pairs of two different positive
//                            environments are allowed (counted in the summary).
//  positive_enclosed_volume  when closed, manifold along edges and consistently oriented: the
//                            enclosed volume is positive, i.e. the normals point outward.
//  unused_points             points that no triangle uses: a warning.
// Triangles that repeat a point are left out of the topology checks; all degenerate triangles
// are left out of the intersection check.
ValidationReport validate_surface(const Mesh& surface, const ValidationParams& params = {});
// The same checks, stopping within a few milliseconds once progress.cancelled() turns true:
// CANCELLED then, and no report. The topology (a sort of the edges) is not interruptible: about
// 0.1 s per million triangles.
absl::StatusOr<ValidationReport> validate_surface(const Mesh& surface,
                                                  const ValidationParams& params,
                                                  Progress& progress);
// validate_surface's no_self_intersections alone, for callers that want only where a surface
// crosses itself (MeshSurface on an assembly, a stuck front, or its own result): the topology
// checks are skipped. With face_environments, crossings of two different positive environments
// are allowed as in validate_surface. not_run when an index is out of range, a coordinate is not
// finite or the environments are not one id >= 0 per triangle; CANCELLED as above.
absl::StatusOr<Check> check_surface_self_intersections(const Mesh& surface,
                                                       const ValidationParams& params,
                                                       Progress& progress);

}  // namespace afmesh
