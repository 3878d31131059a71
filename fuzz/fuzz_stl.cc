// STL reader (ascii and binary: the encoding is decided from the bytes, core/io/stl.h).
#include <cstddef>
#include <cstdint>

#include "core/io/stl.h"
#include "fuzz/fuzz_support.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  afmesh::ReadReport report;
  absl::StatusOr<afmesh::Mesh> mesh =
      afmesh::parse_stl(afmesh::fuzz::as_text(data, size), "fuzz.stl", &report);
  if (mesh.ok()) afmesh::fuzz::require_usable(*mesh, "parse_stl");
  return 0;
}
