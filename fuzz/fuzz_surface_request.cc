// The input side of a MeshSurface call as the service runs it (server/mesh_surface_rpc.cc): each
// client message goes through SurfaceInput::add, then SurfaceInput::finish at half-close, then
// what the job does first with the assembled surface: the estimate that admits it
// (estimate_surface_mesh, server/surface_step.h) and the surface mesher's first steps
// (generate_surface_mesh: the parameters checked, the input cleaned, the size field made, the
// discrete surface built, the features' lines found), cut short by a Progress that cancels at
// its fourth poll, inside find_surface_features: well before the sides along the lines, the
// first work that grows with the size asked. (The next poll, after the curvature sizes, is
// skipped when the options turn the curvature bound off, so the budget stops short of it.)
//
// Input: up to 32 messages, each a 2-byte little-endian length and that many bytes of a
// serialized afmesh.v1.MeshSurfaceRequest (a message that protobuf refuses to parse ends the
// stream, as a broken read would). The server's limits are small here so that the checks, not
// the allocations, take the time. Any status is an answer.
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>

#include "afmesh/v1/mesher.pb.h"
#include "core/surface/generate_surface_mesh.h"
#include "fuzz/fuzz_support.h"
#include "server/mesh_surface_rpc.h"
#include "server/surface_step.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const afmesh::server::InputLimits limits{
      .max_points = 512, .max_triangles = 1024, .max_grid_points = 512, .max_grid_tets = 1024};
  afmesh::server::SurfaceInput input(limits);
  std::size_t at = 0;
  for (int message = 0; message < 32 && at + 2 <= size; ++message) {
    const std::size_t length = data[at] | (std::size_t{data[at + 1]} << 8);
    at += 2;
    if (length > size - at) return 0;
    afmesh::v1::MeshSurfaceRequest request;
    if (!request.ParseFromArray(data + at, static_cast<int>(length))) return 0;
    at += length;
    if (!input.add(request).ok()) return 0;
  }
  if (!input.finish().ok()) return 0;
  const afmesh::SurfaceParams params = input.params();
  const afmesh::Mesh surface = input.take_input();
  afmesh::fuzz::require_usable(surface, "SurfaceInput::finish");
  const absl::StatusOr<afmesh::server::SurfaceEstimate> estimate =
      afmesh::server::estimate_surface_mesh(surface, params);
  // Polls 1 to 3: after the input, after the discrete surface, the first in
  // find_surface_features.
  afmesh::fuzz::BudgetProgress progress(3);
  const absl::StatusOr<afmesh::SurfaceResult> result =
      afmesh::generate_surface_mesh(surface, params, progress);
  // Triage aid: AFMESH_FUZZ_VERBOSE=1 prints how far each assembled input went.
  if (std::getenv("AFMESH_FUZZ_VERBOSE") != nullptr) {
    std::fprintf(stderr, "%zu points, %zu triangles, estimate %g triangles: %s\n",
                 surface.points.size(), surface.triangles.size(),
                 estimate.ok() ? estimate->triangles : -1.0, result.status().ToString().c_str());
  }
  return 0;
}
