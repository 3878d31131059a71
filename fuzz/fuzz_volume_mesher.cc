// The volume mesher on small fronts, through the same steps as a MeshVolume job on the server
// (server/mesh_volume_rpc.cc, MeshVolumeRpc::run): repair_front, assign_environments (none, tags
// or auto), then run_volume_job (generate_volume_mesh, which validates the front first, the
// quality figures and validate_volume_mesh). Any status is an answer; a crash, a sanitizer
// report or a hang (libFuzzer's -timeout) is a finding.
//
// Input bytes, read in order (missing bytes read as 0):
//   shape   %3: 0 a cube, 1 an octahedron (both closed and outward, corners within [-1, 1]),
//           2 free triangles (4..11 points on a 1/32 lattice in [-4, 4], then triples of
//           point indices until the bytes or 32 triangles run out);
//   mode    %3: environments none, tags, auto; bit 2: add a cube of half the size inside
//           (a cavity, or a crossing second front once moved);
//   size    the element size: (0.2 + 0.8 b / 255) times the front's largest extent, so a job
//           builds at most a few thousand tets;
//   then, for the closed shapes: 3 bytes per corner (int8 / 256: a move of up to half a unit),
//   one byte per 8 triangles whose bits flip them, one tag byte per triangle (%3).
// The Progress cancels after a fixed number of polls, bounding the work of any input.
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "core/volume/repair_front.h"
#include "fuzz/fuzz_shapes.h"
#include "fuzz/fuzz_support.h"
#include "server/default_volume_job.h"
#include "server/volume_environments.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  afmesh::fuzz::Bytes in(data, size);
  const int shape = in.next() % 3;
  const std::uint8_t mode_byte = in.next();
  const std::uint8_t size_byte = in.next();

  afmesh::Mesh front = afmesh::fuzz::shape_from_bytes(in, shape, (mode_byte & 4) != 0);

  const double extent = afmesh::fuzz::largest_extent(front);
  if (!(extent > 0.0)) return 0;
  afmesh::VolumeParams params;
  params.size = extent * (0.2 + 0.8 * size_byte / 255.0);
  params.growth = 1.2;
  const auto mode = static_cast<afmesh::v1::EnvironmentMode>(mode_byte % 3);

  // 16 polls: 16 x 256 steps of the front loop, about 1 s under ASan; a cube at the smallest
  // size closes in ~1500 steps. (A cube with a cube cavity at h = 0.4 does not close within
  // 16k steps: see fuzz/README.md, open findings.)
  afmesh::fuzz::BudgetProgress progress(16);
  afmesh::repair_front(front);
  std::vector<std::string> notes;
  if (!afmesh::server::assign_environments(mode, front, params, progress, notes).ok()) return 0;
  const absl::StatusOr<afmesh::server::VolumeJobOutput> output =
      afmesh::server::run_volume_job(front, params, progress);
  // Triage aid: AFMESH_FUZZ_VERBOSE=1 prints each input's outcome.
  if (std::getenv("AFMESH_FUZZ_VERBOSE") != nullptr) {
    std::fprintf(stderr, "%zu points, %zu triangles, h %g: %s\n", front.points.size(),
                 front.triangles.size(), params.size,
                 output.ok() ? "ok" : std::string(output.status().ToString()).c_str());
  }
  return 0;
}
