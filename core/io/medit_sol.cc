// Medit solution files (.sol, ascii) holding one size per vertex: see medit.h.
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "core/io/medit.h"
#include "core/io/medit_header.h"
#include "core/io/mesh_checks.h"
#include "core/io/return_if_error.h"
#include "core/io/string_util.h"
#include "core/io/text_scanner.h"

namespace afmesh {
namespace {

constexpr std::int64_t kScalarType = 1;

// Medit's names of the solution types, for error messages.
std::string_view solution_type_name(std::int64_t type) {
  switch (type) {
    case 1:
      return "a scalar";
    case 2:
      return "a vector";
    case 3:
      return "a symmetric tensor (an anisotropic metric)";
    default:
      return "unknown to Medit";
  }
}

class SolParser {
 public:
  SolParser(std::string_view text, std::string_view source_name, std::size_t num_vertices)
      : scanner_(text, source_name, '#'), num_vertices_(num_vertices) {}

  absl::StatusOr<std::vector<double>> parse() {
    if (scanner_.at_end()) {
      return absl::InvalidArgumentError(str_cat(scanner_.source_name(), ": the file is empty"));
    }
    AFMESH_RETURN_IF_ERROR(parse_medit_header(scanner_));
    for (;;) {
      const std::string_view keyword = scanner_.next_token();
      if (equals_ignore_case(keyword, "End")) break;
      if (!equals_ignore_case(keyword, "SolAtVertices")) return unexpected_keyword(keyword);
      AFMESH_RETURN_IF_ERROR(parse_sol_at_vertices());
    }
    if (!have_sizes_) {
      return scanner_.error(
          "no SolAtVertices section: a background grid needs one size per vertex");
    }
    return std::move(sizes_);
  }

 private:
  absl::Status unexpected_keyword(std::string_view keyword) const {
    if (keyword.empty()) return scanner_.unexpected("'SolAtVertices' or 'End'", keyword);
    return scanner_.error(str_cat("expected 'SolAtVertices' or 'End', found '", keyword,
                                  "' (a background grid's .sol holds one SolAtVertices section "
                                  "of scalar sizes)"));
  }

  // SolAtVertices / count / number of types and the types / one line of values per vertex.
  absl::Status parse_sol_at_vertices() {
    if (have_sizes_) return scanner_.error("a second 'SolAtVertices' section");
    std::int64_t count = 0;
    AFMESH_RETURN_IF_ERROR(scanner_.read_int(count, "the SolAtVertices count"));
    if (count < 0 || static_cast<std::uint64_t>(count) != num_vertices_) {
      return scanner_.error(str_cat("SolAtVertices gives values for ", count,
                                    " vertices, but the mesh has ", num_vertices_,
                                    ": a background grid needs one size per vertex"));
    }
    std::int64_t types = 0;
    AFMESH_RETURN_IF_ERROR(scanner_.read_int(types, "the number of solution types"));
    if (types != 1) {
      return scanner_.error(str_cat("SolAtVertices holds ", types,
                                    " solutions per vertex; a background grid needs exactly one "
                                    "(type 1, a scalar size)"));
    }
    std::int64_t type = 0;
    AFMESH_RETURN_IF_ERROR(scanner_.read_int(type, "the solution type"));
    if (type != kScalarType) {
      return scanner_.error(str_cat("solution type ", type, " (", solution_type_name(type),
                                    ") is not supported: a background grid needs type 1, one "
                                    "scalar size per vertex"));
    }
    sizes_.reserve(num_vertices_);
    for (std::int64_t v = 0; v < count; ++v) {
      double size = 0;
      AFMESH_RETURN_IF_ERROR(scanner_.read_any_double(size, "the size of a vertex"));
      if (!std::isfinite(size) || size <= 0.0) {
        return scanner_.error(
            str_cat("the size of vertex ", v + 1, " must be finite and > 0, found ", size));
      }
      sizes_.push_back(size);
    }
    have_sizes_ = true;
    return absl::OkStatus();
  }

  TextScanner scanner_;
  std::size_t num_vertices_;
  std::vector<double> sizes_;
  bool have_sizes_ = false;
};

}  // namespace

absl::StatusOr<std::vector<double>> parse_medit_sol(std::string_view text,
                                                    std::string_view source_name,
                                                    std::size_t num_vertices) {
  return SolParser(text, source_name, num_vertices).parse();
}

absl::Status write_medit_sol(std::span<const double> sizes, OutputBuffer& out) {
  AFMESH_RETURN_IF_ERROR(check_sizes_for_writing(sizes, sizes.size()));
  out.put(
      str_cat("MeshVersionFormatted 2\nDimension 3\n\nSolAtVertices\n", sizes.size(), "\n1 1\n"));
  for (const double size : sizes) {
    out.put_double(size);
    out.put('\n');
  }
  out.put("\nEnd\n");
  return out.flush();
}

}  // namespace afmesh
