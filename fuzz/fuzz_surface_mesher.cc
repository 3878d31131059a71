// The surface mesher on small surfaces, through the same step as a MeshSurface job on the server
// (server/mesh_surface_rpc.cc, MeshSurfaceRpc::run): run_surface_step with the job afmesh-server
// passes (generate_surface_mesh): the estimate and its admission, the mesher, the output's
// check (INTERNAL naming a broken element) and its quality figures. Any status is an answer; a
// crash, a sanitizer report or a hang (libFuzzer's -timeout) is a finding.
//
// Input bytes, read in order (missing bytes read as 0):
//   shape   %3: 0 a cube, 1 an octahedron (both closed and outward, corners within [-1, 1]),
//           2 free triangles (4..11 points on a 1/32 lattice in [-4, 4], then triples of
//           point indices until the bytes or 32 triangles run out: open, crossing, repeated
//           or degenerate as they come);
//   options bits 0-1: the ridge angle (30, 10, 60, 150 degrees); bits 2-3: the corner angle
//           (60, 20, 120, 180); bit 4: no curvature bound (else 30 degrees); bit 5, for the
//           closed shapes: add a cube of half the size inside (a cavity, or a crossing second
//           surface once moved); bit 6: a bound on the distance from the input of 0.001 of
//           its diagonal (SurfaceParams::curvature_deviation: the chord and kink sizes, the
//           sliver steps kept over the bound, the distance to the input as sent), else none;
//   size    the element size: (0.1 + 0.9 b / 255) times the surface's largest extent, so a job
//           makes at most a few thousand triangles (a cube at the smallest: about 1400);
//   then, for the closed shapes: 3 bytes per corner (int8 / 256: a move of up to half a unit),
//   one byte per 8 triangles whose bits flip them; then one tag byte per triangle (%3).
// The Progress cancels after a fixed number of polls, bounding the work of any input.
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "core/common/stage_timing.h"
#include "core/surface/generate_surface_mesh.h"
#include "fuzz/fuzz_shapes.h"
#include "fuzz/fuzz_support.h"
#include "server/memory_budget.h"
#include "server/streaming_call.h"
#include "server/surface_job.h"
#include "server/surface_step.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  afmesh::fuzz::Bytes in(data, size);
  const int shape = in.next() % 3;
  const std::uint8_t options = in.next();
  const std::uint8_t size_byte = in.next();

  afmesh::Mesh surface = afmesh::fuzz::shape_from_bytes(in, shape, (options & 32) != 0);

  const double extent = afmesh::fuzz::largest_extent(surface);
  if (!(extent > 0.0)) return 0;
  afmesh::SurfaceParams params;
  params.size = extent * (0.1 + 0.9 * size_byte / 255.0);
  params.growth = 1.2;
  constexpr double kRidgeAngles[] = {30.0, 10.0, 60.0, 150.0};
  constexpr double kCornerAngles[] = {60.0, 20.0, 120.0, 180.0};
  params.ridge_angle_deg = kRidgeAngles[options & 3];
  params.corner_angle_deg = kCornerAngles[(options >> 2) & 3];
  params.curvature_angle_deg = (options & 16) ? 0.0 : 30.0;
  params.curvature_deviation = (options & 64) ? 0.001 : 0.0;

  // As afmesh-server's job (server/main.cc).
  const afmesh::server::SurfaceJob job = [](const afmesh::Mesh& input,
                                            const afmesh::SurfaceParams& job_params,
                                            afmesh::Progress& progress) {
    return afmesh::generate_surface_mesh(input, job_params, progress);
  };
  // 24 polls: one per 256 steps of a patch's front, and 7 to 11 more (between the stages, in
  // the features, the flips and the distances): every seed, the largest (1356 triangles)
  // included, polls at most 11 times. A cube meshed as one patch (ridge angle 150) at the
  // smallest size can build 10 times the triangles asked before its front is stuck; with 64
  // polls that took 14 s under ASan (2.1 s in release), so the budget stops it sooner.
  afmesh::fuzz::BudgetProgress progress(24);
  afmesh::server::MemoryBudget budget(std::int64_t{1} << 30);
  afmesh::server::JobContext context(progress, budget, {});
  std::vector<std::string> notes;
  std::vector<afmesh::StageTiming> timings;
  // --max-elements well over what the size asks, so that only a wild estimate is refused.
  constexpr std::int64_t kMaxTriangles = 20000;
  const absl::StatusOr<afmesh::server::SurfaceOutcome> outcome = afmesh::server::run_surface_step(
      job, surface, params, kMaxTriangles, context, notes, timings);
  // Triage aid: AFMESH_FUZZ_VERBOSE=1 prints each input's outcome.
  if (std::getenv("AFMESH_FUZZ_VERBOSE") != nullptr) {
    const std::string said =
        outcome.ok() ? std::to_string(outcome->result.mesh.triangles.size()) + " triangles out"
                     : outcome.status().ToString();
    std::fprintf(stderr, "%zu points, %zu triangles, h %g: %s\n", surface.points.size(),
                 surface.triangles.size(), params.size, said.c_str());
  }
  return 0;
}
