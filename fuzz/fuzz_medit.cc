// Medit .mesh reader (core/io/medit.h).
#include <cstddef>
#include <cstdint>

#include "core/io/medit.h"
#include "fuzz/fuzz_support.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  afmesh::ReadReport report;
  absl::StatusOr<afmesh::Mesh> mesh =
      afmesh::parse_medit(afmesh::fuzz::as_text(data, size), "fuzz.mesh", &report);
  if (mesh.ok()) afmesh::fuzz::require_usable(*mesh, "parse_medit");
  return 0;
}
