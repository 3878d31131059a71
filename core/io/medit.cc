#include "core/io/medit.h"

#include <algorithm>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "core/io/medit_header.h"
#include "core/io/mesh_checks.h"
#include "core/io/return_if_error.h"
#include "core/io/string_util.h"
#include "core/io/text_scanner.h"

namespace afmesh {

absl::Status parse_medit_header(TextScanner& scanner) {
  AFMESH_RETURN_IF_ERROR(scanner.expect_keyword("MeshVersionFormatted"));
  std::int64_t version = 0;
  AFMESH_RETURN_IF_ERROR(scanner.read_int(version, "the format version"));
  if (version < 1 || version > 4) {
    return scanner.error(
        str_cat("unsupported MeshVersionFormatted ", version, " (expected 1, 2, 3 or 4)"));
  }
  AFMESH_RETURN_IF_ERROR(scanner.expect_keyword("Dimension"));
  std::int64_t dimension = 0;
  AFMESH_RETURN_IF_ERROR(scanner.read_int(dimension, "the dimension"));
  if (dimension != 3) {
    return scanner.error(str_cat("Dimension ", dimension, " is not supported (only 3)"));
  }
  return absl::OkStatus();
}

namespace {

constexpr std::int64_t kMaxCount = std::numeric_limits<Index>::max();

// A section read and dropped: `values` numbers per entry, reals or integers.
struct SkippedSection {
  std::string_view keyword;
  int values;
  bool reals;
};

constexpr SkippedSection kSkippedSections[] = {
    {"Edges", 3, false},
    {"Corners", 1, false},
    {"Ridges", 1, false},
    {"RequiredVertices", 1, false},
    {"RequiredEdges", 1, false},
    {"RequiredTriangles", 1, false},
    {"RequiredTetrahedra", 1, false},
    {"Normals", 3, true},
    {"NormalAtVertices", 2, false},
    {"NormalAtTriangleVertices", 3, false},
    {"Tangents", 3, true},
    {"TangentAtVertices", 2, false},
};

// Element sections whose elements a Mesh cannot hold.
constexpr std::string_view kUnsupportedSections[] = {
    "Quadrilaterals", "Hexahedra",    "Prisms",           "Pyramids",    "EdgesP2",
    "TrianglesP2",    "TetrahedraP2", "QuadrilateralsQ2", "HexahedraQ2", "Polygons"};

class MeditParser {
 public:
  MeditParser(std::string_view text, std::string_view source_name)
      : scanner_(text, source_name, '#') {}

  absl::StatusOr<Mesh> parse(ReadReport* report) {
    if (scanner_.at_end()) {
      return absl::InvalidArgumentError(str_cat(scanner_.source_name(), ": the file is empty"));
    }
    AFMESH_RETURN_IF_ERROR(parse_medit_header(scanner_));
    for (;;) {
      const std::string_view keyword = scanner_.next_token();
      if (equals_ignore_case(keyword, "End")) break;
      AFMESH_RETURN_IF_ERROR(parse_section(keyword));
    }
    if (nonzero_vertex_refs_ > 0) {
      add_note(report, str_cat("dropped Medit vertex references (", nonzero_vertex_refs_, " of ",
                               mesh_.points.size(), " vertices had a nonzero ref)"));
    }
    for (std::string& note : notes_) add_note(report, std::move(note));
    return std::move(mesh_);
  }

 private:
  absl::Status parse_section(std::string_view keyword) {
    if (equals_ignore_case(keyword, "Vertices")) return parse_vertices();
    if (equals_ignore_case(keyword, "Triangles")) {
      return parse_elements<3>("Triangles", mesh_.triangles, mesh_.triangle_tags);
    }
    if (equals_ignore_case(keyword, "Tetrahedra")) {
      return parse_elements<4>("Tetrahedra", mesh_.tets, mesh_.tet_tags);
    }
    for (const SkippedSection& section : kSkippedSections) {
      if (equals_ignore_case(keyword, section.keyword)) return skip_section(section);
    }
    for (const std::string_view unsupported : kUnsupportedSections) {
      if (equals_ignore_case(keyword, unsupported)) {
        return scanner_.error(str_cat("Medit section '", keyword,
                                      "' is not supported: afmesh reads triangles and "
                                      "tetrahedra only"));
      }
    }
    if (keyword.empty()) return scanner_.unexpected("a section keyword or 'End'", keyword);
    double number = 0;
    if (parse_double(keyword, number)) {
      return scanner_.error(str_cat("expected a section keyword or 'End', found the number '",
                                    keyword,
                                    "' (does the previous section hold more entries than "
                                    "its count says?)"));
    }
    return scanner_.error(str_cat("unknown Medit keyword '", keyword, "'"));
  }

  // A section count in [0, 2^31 - 1].
  absl::Status read_count(std::string_view section, std::int64_t& count) {
    AFMESH_RETURN_IF_ERROR(scanner_.read_int(count, str_cat("the ", section, " count")));
    if (count < 0 || count > kMaxCount) {
      return scanner_.error(
          str_cat(section, " count ", count, " is out of range [0, ", kMaxCount, "]"));
    }
    return absl::OkStatus();
  }

  // Room for `count` entries, bounded by what the remaining text can hold (a bad count must
  // not allocate gigabytes before the entries run out).
  std::size_t plausible(std::int64_t count, int values_per_entry) const {
    const std::size_t most = scanner_.text().size() / (2 * values_per_entry);
    return std::min(static_cast<std::size_t>(count), most);
  }

  absl::Status read_reference(Index& reference) {
    std::int64_t value = 0;
    AFMESH_RETURN_IF_ERROR(scanner_.read_int(value, "a reference"));
    if (value < std::numeric_limits<Index>::min() || value > std::numeric_limits<Index>::max()) {
      return scanner_.error(str_cat("reference ", value, " does not fit in 32 bits"));
    }
    reference = static_cast<Index>(value);
    return absl::OkStatus();
  }

  absl::Status parse_vertices() {
    if (have_vertices_) return scanner_.error("a second 'Vertices' section");
    have_vertices_ = true;
    std::int64_t count = 0;
    AFMESH_RETURN_IF_ERROR(read_count("Vertices", count));
    mesh_.points.reserve(plausible(count, 4));
    for (std::int64_t v = 0; v < count; ++v) {
      Point& point = mesh_.points.emplace_back();
      for (double& coordinate : point) {
        AFMESH_RETURN_IF_ERROR(scanner_.read_double(coordinate, "a vertex coordinate"));
      }
      Index reference = 0;
      AFMESH_RETURN_IF_ERROR(read_reference(reference));
      if (reference != 0) ++nonzero_vertex_refs_;
    }
    return absl::OkStatus();
  }

  // `count` rows of N 1-based vertex indices and a reference.
  template <std::size_t N>
  absl::Status parse_elements(std::string_view section, std::vector<std::array<Index, N>>& elements,
                              std::vector<Index>& tags) {
    if (!have_vertices_) {
      return scanner_.error(str_cat("section '", section, "' before 'Vertices'"));
    }
    if (!elements.empty()) return scanner_.error(str_cat("a second '", section, "' section"));
    std::int64_t count = 0;
    AFMESH_RETURN_IF_ERROR(read_count(section, count));
    elements.reserve(plausible(count, N + 1));
    tags.reserve(plausible(count, N + 1));
    const auto num_points = static_cast<std::int64_t>(mesh_.points.size());
    for (std::int64_t e = 0; e < count; ++e) {
      std::array<Index, N>& element = elements.emplace_back();
      for (Index& corner : element) {
        std::int64_t index = 0;
        AFMESH_RETURN_IF_ERROR(scanner_.read_int(index, "a vertex index"));
        if (index < 1 || index > num_points) {
          return scanner_.error(
              str_cat("vertex index ", index, " is out of range [1, ", num_points, "]"));
        }
        corner = static_cast<Index>(index - 1);
      }
      AFMESH_RETURN_IF_ERROR(read_reference(tags.emplace_back()));
    }
    return absl::OkStatus();
  }

  absl::Status skip_section(const SkippedSection& section) {
    std::int64_t count = 0;
    AFMESH_RETURN_IF_ERROR(read_count(section.keyword, count));
    for (std::int64_t i = 0; i < count * section.values; ++i) {
      double real = 0;
      std::int64_t integer = 0;
      AFMESH_RETURN_IF_ERROR(section.reals ? scanner_.read_any_double(real, section.keyword)
                                           : scanner_.read_int(integer, section.keyword));
    }
    notes_.push_back(str_cat("skipped Medit section ", section.keyword, " (", count,
                             count == 1 ? " entry)" : " entries)"));
    return absl::OkStatus();
  }

  TextScanner scanner_;
  Mesh mesh_;
  bool have_vertices_ = false;
  std::int64_t nonzero_vertex_refs_ = 0;
  std::vector<std::string> notes_;
};

template <std::size_t N>
void write_elements(std::string_view keyword, const std::vector<std::array<Index, N>>& elements,
                    const std::vector<Index>& tags, OutputBuffer& out) {
  if (elements.empty()) return;
  out.put(str_cat("\n", keyword, "\n", elements.size(), "\n"));
  for (std::size_t e = 0; e < elements.size(); ++e) {
    for (const Index v : elements[e]) {
      out.put_int(std::int64_t{v} + 1);
      out.put(' ');
    }
    out.put_int(tags[e]);
    out.put('\n');
  }
}

}  // namespace

absl::StatusOr<Mesh> parse_medit(std::string_view text, std::string_view source_name,
                                 ReadReport* report) {
  return MeditParser(text, source_name).parse(report);
}

absl::Status write_medit(const Mesh& mesh, OutputBuffer& out) {
  AFMESH_RETURN_IF_ERROR(check_mesh_for_writing(mesh));
  out.put(str_cat("MeshVersionFormatted 2\nDimension 3\n\nVertices\n", mesh.points.size(), "\n"));
  for (const Point& p : mesh.points) {
    out.put_double(p[0]);
    out.put(' ');
    out.put_double(p[1]);
    out.put(' ');
    out.put_double(p[2]);
    out.put(" 0\n");
  }
  write_elements("Triangles", mesh.triangles, mesh.triangle_tags, out);
  write_elements("Tetrahedra", mesh.tets, mesh.tet_tags, out);
  out.put("\nEnd\n");
  return out.flush();
}

}  // namespace afmesh
