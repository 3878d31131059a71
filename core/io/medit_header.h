// The header every Medit ASCII file starts with (.mesh and .sol alike).
#pragma once

#include "absl/status/status.h"
#include "core/io/text_scanner.h"

namespace afmesh {

// Reads `MeshVersionFormatted v` (1 to 4) and `Dimension 3`; an error names the line and what
// was expected.
absl::Status parse_medit_header(TextScanner& scanner);

}  // namespace afmesh
