// The size specification as the CLI reads a --spec file (client/spec_file.cc): protobuf JSON of
// afmesh.v1.SizeSpec, converted to core's SizeSpec and validated; a valid one is then evaluated
// (SpecSizeField, eq. 14) at a lattice of points in and around a unit box, where every size must
// be finite, > 0 and <= max_size (its documented contract). `background.file` is a path the CLI
// opens; it is not followed here (the grid readers have their own targets).
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>

#include "core/sizing/size_spec.h"
#include "core/sizing/spec_size_field.h"
#include "fuzz/fuzz_support.h"
#include "proto/size_spec_convert.h"

namespace {

void check_field(const afmesh::SizeSpec& spec) {
  const afmesh::Box domain{.lo = {0.0, 0.0, 0.0}, .hi = {1.0, 1.0, 1.0}};
  absl::StatusOr<afmesh::SpecSizeField> field = afmesh::SpecSizeField::create(spec, domain);
  if (!field.ok()) {
    std::fprintf(stderr, "validate_size_spec passed but SpecSizeField::create refused: %s\n",
                 std::string(field.status().message()).c_str());
    std::abort();
  }
  for (int i = 0; i < 4; ++i) {
    for (int j = 0; j < 4; ++j) {
      for (int k = 0; k < 4; ++k) {
        const afmesh::Point x{-0.5 + 0.6 * i, -0.5 + 0.6 * j, -0.5 + 0.6 * k};
        const double size = field->size_at(x);
        if (!(std::isfinite(size) && size > 0.0 && size <= spec.max_size)) {
          std::fprintf(stderr, "size %.17g at (%g, %g, %g) outside (0, max_size = %.17g]\n", size,
                       x[0], x[1], x[2], spec.max_size);
          std::abort();
        }
      }
    }
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  absl::StatusOr<afmesh::v1::SizeSpec> message =
      afmesh::size_spec_proto_from_json(afmesh::fuzz::as_text(data, size));
  if (!message.ok()) return 0;
  if (message->has_background() && !message->background().file().empty()) return 0;
  absl::StatusOr<afmesh::SizeSpec> spec = afmesh::size_spec_from_proto(*message);
  if (!spec.ok()) return 0;
  if (!afmesh::validate_size_spec(*spec).ok()) return 0;
  check_field(*spec);
  return 0;
}
