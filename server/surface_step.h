// The surface step of a call, as MeshSurface runs it and MeshVolume runs it first with
// remesh_surface: the output estimated and admitted against --max-elements and the memory budget,
// the SurfaceJob run, its surface checked whole, its triangle quality measured; and what the
// SurfaceSummary message reports of it. Not in the paper.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "absl/status/statusor.h"
#include "afmesh/v1/mesher.pb.h"
#include "core/common/stage_timing.h"
#include "core/mesh/mesh.h"
#include "core/surface/generate_surface_mesh.h"
#include "server/streaming_call.h"
#include "server/surface_job.h"

namespace afmesh::server {

// The figures of `surface` (indices in range); all 0 for no triangles.
SurfaceQualityFigures surface_quality(const Mesh& surface);

// What the size field asks of a surface, before meshing.
struct SurfaceEstimate {
  double triangles = 0.0;  // output triangles
  double bytes = 0.0;      // memory the job is expected to need
};

// Output triangles: the sum over input triangles of their area over the area of an equilateral
// triangle of the local size h (sqrt(3)/4 h²), with 1/h² averaged over the triangle's corners
// and centroid. Bytes: kSurfaceBytesPerInputTriangle per input triangle plus
// kSurfaceBytesPerTriangle per output triangle. INVALID_ARGUMENT when params.spec cannot be
// evaluated (validated before: not expected).
absl::StatusOr<SurfaceEstimate> estimate_surface_mesh(const Mesh& input,
                                                      const SurfaceParams& params);

// Provisional memory figures for the estimate, to be measured once the surface front has
// landed: the discrete surface (host faces, normals, AABB tree, features) per input triangle,
// and the result with the front's bins and lookup tables per output triangle.
inline constexpr double kSurfaceBytesPerInputTriangle = 400.0;
inline constexpr double kSurfaceBytesPerTriangle = 600.0;

// The step: estimate (stage "estimate" in `timings`) and admission (params.max_triangles set to
// `max_elements`; RESOURCE_EXHAUSTED giving the estimate when it is over `max_elements`, or its
// bytes over the memory budget), then `job` (UNIMPLEMENTED when empty; exceptions become
// statuses; the job is admitted again in the same way, through params.admit_expected, when the
// sizes attached to the surface ask for more triangles than the estimate), its surface checked
// (INTERNAL naming the element when tags or indices are wrong), its quality measured. The
// report's repairs are appended to `notes` for Warnings.
absl::StatusOr<SurfaceOutcome> run_surface_step(const SurfaceJob& job, const Mesh& input,
                                                SurfaceParams params, std::int64_t max_elements,
                                                JobContext& context,
                                                std::vector<std::string>& notes,
                                                std::vector<StageTiming>& timings);

// Counts, quality, repairs, features, distance and estimate of `outcome` into `summary` (not
// its timings, which the caller knows).
void fill_surface_summary(const SurfaceOutcome& outcome, v1::SurfaceSummary& summary);

// Appends `timings` to a Summary's or SurfaceSummary's timings.
template <class SummaryMessage>
void add_timings(const std::vector<StageTiming>& timings, SummaryMessage& summary) {
  for (const StageTiming& t : timings) {
    v1::StageTiming& timing = *summary.add_timings();
    timing.set_stage(t.stage);
    timing.set_seconds(t.seconds);
  }
}

}  // namespace afmesh::server
