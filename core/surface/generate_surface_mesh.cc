// MeshSurface (paper §3): see generate_surface_mesh.h for the steps.
#include "core/surface/generate_surface_mesh.h"

namespace afmesh {

absl::StatusOr<SurfaceResult> generate_surface_mesh(const Mesh& input, const SurfaceParams& params,
                                                    Progress& progress) {
  (void)input;
  (void)params;
  (void)progress;
  return absl::UnimplementedError("MeshSurface: the surface front is not in this build yet");
}

}  // namespace afmesh
