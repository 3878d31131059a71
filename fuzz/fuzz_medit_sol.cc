// Medit .sol reader (core/io/medit.h). The first byte is the vertex count of the mesh the sizes
// belong to (0..255); the rest is the .sol text.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>

#include "core/io/medit.h"
#include "fuzz/fuzz_support.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size < 1) return 0;
  const std::size_t num_vertices = data[0];
  absl::StatusOr<std::vector<double>> sizes = afmesh::parse_medit_sol(
      afmesh::fuzz::as_text(data + 1, size - 1), "fuzz.sol", num_vertices);
  if (!sizes.ok()) return 0;
  // The documented contract: one finite size > 0 per vertex.
  bool usable = sizes->size() == num_vertices;
  for (const double s : *sizes) usable = usable && std::isfinite(s) && s > 0.0;
  if (!usable) {
    std::fprintf(stderr, "parse_medit_sol said OK but the sizes break its contract\n");
    std::abort();
  }
  return 0;
}
