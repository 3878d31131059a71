// make-thin-examples EXAMPLES_DIR: writes the fronts of core/shapes/thin_shapes.h with their
// default parameters as EXAMPLES_DIR/dome/dome.mesh, EXAMPLES_DIR/sails/sails.mesh and
// EXAMPLES_DIR/crossing/crossing.mesh (Medit,
// triangle references = crossing-environment ids). The shipped files are its output;
// thin_examples_test checks that they still are.
#include <cstdio>
#include <string>

#include "core/io/mesh_io.h"
#include "core/shapes/thin_shapes.h"

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: make-thin-examples EXAMPLES_DIR\n");
    return 2;
  }
  const std::string dir = argv[1];
  const struct {
    std::string path;
    afmesh::Mesh mesh;
  } outputs[] = {{dir + "/dome/dome.mesh", afmesh::quarter_dome_surface()},
                 {dir + "/sails/sails.mesh", afmesh::sails_surface()},
                 {dir + "/crossing/crossing.mesh", afmesh::crossing_plates_surface()}};
  for (const auto& [path, mesh] : outputs) {
    if (const absl::Status status = afmesh::write_mesh(mesh, path); !status.ok()) {
      std::fprintf(stderr, "make-thin-examples: %s\n", std::string(status.message()).c_str());
      return 1;
    }
    std::printf("%s: %zu points, %zu triangles\n", path.c_str(), mesh.points.size(),
                mesh.triangles.size());
  }
  return 0;
}
