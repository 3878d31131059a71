// Wavefront OBJ reader (core/io/obj.h).
#include <cstddef>
#include <cstdint>

#include "core/io/obj.h"
#include "fuzz/fuzz_support.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  afmesh::ReadReport report;
  absl::StatusOr<afmesh::Mesh> mesh =
      afmesh::parse_obj(afmesh::fuzz::as_text(data, size), "fuzz.obj", &report);
  if (mesh.ok()) afmesh::fuzz::require_usable(*mesh, "parse_obj");
  return 0;
}
