// Pieces shared by validate_volume.cc and validate_surface.cc: collecting a check's findings,
// formatting element names, and the checks both kinds of mesh run (indices, coordinates,
// unused points). Internal to core/quality.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "absl/functional/function_ref.h"
#include "core/mesh/mesh.h"
#include "core/quality/validate.h"

namespace afmesh {

// Collects the findings of one check: counts all of them, keeps the first few in detail.
// Findings are built only when kept, so a check over millions of bad elements stays cheap.
class CheckBuilder {
 public:
  CheckBuilder(std::string_view name, const ValidationParams& params);

  // Counts one finding and keeps `make()` while fewer than max_findings_per_check are kept.
  void add(absl::FunctionRef<Finding()> make);
  std::int64_t count() const { return check_.finding_count; }

  // The check: passed with `clean_summary` when nothing was found, otherwise `if_found` with
  // `found_summary`, followed by how many findings are not listed when some were dropped.
  Check finish(std::string clean_summary, std::string found_summary,
               CheckOutcome if_found = CheckOutcome::kFailed);

 private:
  Check check_;
  int max_findings_ = 0;
};

// A check that did not run, saying why.
Check not_run(std::string_view name, std::string_view reason);
// The reason of the geometric checks that need finite coordinates.
inline constexpr std::string_view kNeedsFinite = "some point coordinates are not finite";

// "4", "4 and 9", "4, 9 and 12".
std::string join_indices(const std::vector<Index>& ids);

// "(1,2,3)".
std::string format_triple(const Triangle& t);

// "tet" / "tets" (or any noun) by count.
std::string plural(std::int64_t n, std::string_view singular, std::string_view plural_form);

// Indices of `elements` (tets K×4 or triangles M×3) in [0, point_count), and `tag_count` equal
// to the element count.
Check check_element_indices(const std::vector<Tet>& elements, std::size_t tag_count,
                            std::size_t point_count, const ValidationParams& params);
Check check_element_indices(const std::vector<Triangle>& elements, std::size_t tag_count,
                            std::size_t point_count, const ValidationParams& params);

// Every coordinate of `points` (N×3) finite.
Check check_finite_coordinates(const std::vector<Point>& points, const ValidationParams& params);

// Points that no element uses, as warnings. Indices must be in range.
Check check_unused_points(std::size_t point_count, const std::vector<Tet>& tets,
                          const ValidationParams& params);
Check check_unused_points(std::size_t point_count, const std::vector<Triangle>& triangles,
                          const ValidationParams& params);

// True when every index of the elements is in [0, point_count).
bool all_indices_in_range(const std::vector<Tet>& tets, std::size_t point_count);
bool all_indices_in_range(const std::vector<Triangle>& triangles, std::size_t point_count);

// True when every index of `triangles` is in [0, point_count) and every point is finite.
bool indices_and_coordinates_ok(const std::vector<Point>& points,
                                const std::vector<Triangle>& triangles);

// environment_gap over mesh.tets with params.point_environments (validate.h). Indices must be in
// range.
Check check_environment_gap(const Mesh& mesh, const ValidationParams& params);

// Volume enclosed by oriented triangles (M×3) over `points` (N×3), by the divergence theorem:
// sum over triangles of (a-o)·((b-o)×(c-o)) / 6, with o the centre of the triangles' bounding
// box (to keep terms small), summed with compensation. `magnitude` receives the sum of the
// terms' absolute values, the scale of its rounding error.
double enclosed_volume(const std::vector<Point>& points, const std::vector<Triangle>& triangles,
                       double* magnitude);

}  // namespace afmesh
