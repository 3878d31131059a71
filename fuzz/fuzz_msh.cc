// Gmsh MSH reader: 4.1 ascii and binary, 2.2 ascii (the version comes from $MeshFormat), both as
// a mesh (parse_msh) and as a background grid with its $NodeData sizes (parse_msh_sized_grid).
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>

#include "core/io/msh.h"
#include "fuzz/fuzz_support.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view bytes = afmesh::fuzz::as_text(data, size);
  afmesh::ReadReport report;
  absl::StatusOr<afmesh::Mesh> mesh = afmesh::parse_msh(bytes, "fuzz.msh", &report);
  if (mesh.ok()) afmesh::fuzz::require_usable(*mesh, "parse_msh");

  afmesh::ReadReport grid_report;
  absl::StatusOr<afmesh::SizedGrid> grid =
      afmesh::parse_msh_sized_grid(bytes, "fuzz.msh", &grid_report);
  if (grid.ok()) {
    afmesh::fuzz::require_usable(grid->mesh, "parse_msh_sized_grid");
    bool usable = grid->sizes.size() == grid->mesh.points.size();
    for (const double s : grid->sizes) usable = usable && std::isfinite(s) && s > 0.0;
    if (!usable) {
      std::fprintf(stderr, "parse_msh_sized_grid said OK but the sizes break its contract\n");
      std::abort();
    }
  }
  return 0;
}
