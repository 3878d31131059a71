// environment_gap: no tet joins two different positive crossing environments (paper §2;
// design.md, "no tet joins the two sides of a thin structure"). Declared in validate_common.h,
// run by validate_volume_mesh when ValidationParams::point_environments is given.
#include <array>
#include <cstdint>
#include <span>

#include "absl/strings/str_format.h"
#include "core/quality/validate.h"
#include "core/quality/validate_common.h"

namespace afmesh {
namespace {

// The environment of point p: LPOCR[p], or 0 beyond the array (interior points).
std::int32_t environment_of(std::span<const std::int32_t> env, Index p) {
  return static_cast<std::size_t>(p) < env.size() ? env[p] : 0;
}

// Findings for a malformed environment array: longer than the points, or entries below -1.
// Returns true when there were any.
bool add_malformed_array(std::span<const std::int32_t> env, std::size_t point_count,
                         CheckBuilder& builder) {
  if (env.size() > point_count) {
    builder.add([&] {
      return Finding{absl::StrFormat("%d point environments given for %d points", env.size(),
                                     point_count)};
    });
    return true;
  }
  bool malformed = false;
  for (Index p = 0; p < static_cast<Index>(env.size()); ++p) {
    if (env[p] >= -1) continue;
    malformed = true;
    builder.add([&] {
      return Finding{absl::StrFormat("point %d has environment %d: ids must be >= -1", p, env[p]),
                     {p}, {}, {}};
    });
  }
  return malformed;
}

}  // namespace

Check check_environment_gap(const Mesh& mesh, const ValidationParams& params) {
  const std::span<const std::int32_t> env = params.point_environments;
  const CheckOutcome if_found =
      params.environment_gap_warns_only ? CheckOutcome::kWarning : CheckOutcome::kFailed;
  CheckBuilder builder(check::kEnvironmentGap, params);
  if (add_malformed_array(env, mesh.points.size(), builder)) {
    return builder.finish("", absl::StrFormat("%d invalid point environment %s", builder.count(),
                                              plural(builder.count(), "entry", "entries")),
                          CheckOutcome::kFailed);
  }
  std::int64_t touching = 0;  // tets with a point of some positive environment
  for (Index t = 0; t < static_cast<Index>(mesh.tets.size()); ++t) {
    const Tet& tet = mesh.tets[t];
    int first = -1;  // corner of the first positive-environment point
    int other = -1;  // corner of a point of another positive environment
    for (int corner = 0; corner < 4 && other < 0; ++corner) {
      const std::int32_t e = environment_of(env, tet[corner]);
      if (e <= 0) continue;
      if (first < 0) {
        first = corner;
      } else if (e != environment_of(env, tet[first])) {
        other = corner;
      }
    }
    if (first >= 0) ++touching;
    if (other < 0) continue;
    builder.add([&] {
      const Index a = tet[first], b = tet[other];
      return Finding{absl::StrFormat("tet %d (%d,%d,%d,%d) joins environment %d (point %d) and "
                                     "environment %d (point %d) across a thin gap",
                                     t, tet[0], tet[1], tet[2], tet[3], environment_of(env, a),
                                     a, environment_of(env, b), b),
                     {a, b}, {}, {t}};
    });
  }
  return builder.finish(
      absl::StrFormat("no tet joins two positive environments (%d of %d tets touch one)",
                      touching, mesh.tets.size()),
      absl::StrFormat("%d %s two different positive environments across a thin gap",
                      builder.count(), plural(builder.count(), "tet joins", "tets join")),
      if_found);
}

}  // namespace afmesh
