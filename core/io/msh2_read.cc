// MSH 2.x ascii sections: $Nodes (tag x y z), $Elements (tag type ntags tags... nodes...) and
// $NodeData (msh_node_data.cc).
#include <cstdint>
#include <limits>

#include "core/io/msh_readers.h"
#include "core/io/return_if_error.h"
#include "core/io/string_util.h"

namespace afmesh::msh {
namespace {

constexpr std::int64_t kMaxCount = std::numeric_limits<Index>::max();
constexpr std::int64_t kMaxElementTags = 1024;  // gmsh writes 2 to 4

class Msh2Reader {
 public:
  Msh2Reader(TextScanner& scanner, MeshBuilder& builder) : scanner_(scanner), builder_(builder) {}

  absl::Status read_sections() {
    while (!scanner_.at_end()) {
      const std::string_view header = scanner_.next_token();
      if (header.size() < 2 || header[0] != '$') {
        return scanner_.unexpected("a section header such as '$Nodes'", header);
      }
      AFMESH_RETURN_IF_ERROR(read_section(header.substr(1)));
    }
    return absl::OkStatus();
  }

 private:
  absl::Status read_section(std::string_view name) {
    if (name == "Nodes") {
      AFMESH_RETURN_IF_ERROR(read_nodes());
    } else if (name == "Elements") {
      AFMESH_RETURN_IF_ERROR(read_elements());
    } else if (name == "NodeData") {
      return read_node_data_section(scanner_, false, builder_);
    } else if (name == "MeshFormat") {
      return scanner_.error("a second $MeshFormat section");
    } else {
      if (name != "Comments") builder_.add_note(str_cat("skipped MSH section $", name));
      return skip_section(scanner_, name);
    }
    return expect_section_end(scanner_, name);
  }

  absl::Status read_count(std::string_view what, std::int64_t& count) {
    AFMESH_RETURN_IF_ERROR(scanner_.read_int(count, what));
    if (count < 0 || count > kMaxCount) {
      return scanner_.error(str_cat(what, " ", count, " is out of range [0, ", kMaxCount, "]"));
    }
    return absl::OkStatus();
  }

  absl::Status read_tag(std::string_view what, std::uint64_t& tag) {
    std::int64_t value = 0;
    AFMESH_RETURN_IF_ERROR(scanner_.read_int(value, what));
    if (value < 0) return scanner_.error(str_cat(what, " ", value, " is negative"));
    tag = static_cast<std::uint64_t>(value);
    return absl::OkStatus();
  }

  absl::Status read_nodes() {
    if (builder_.has_nodes()) return scanner_.error("a second $Nodes section");
    std::int64_t count = 0;
    AFMESH_RETURN_IF_ERROR(read_count("the node count", count));
    const std::size_t plausible = plausible_count(scanner_, count, 8);
    builder_.nodes() = NodeTagMap(4 * plausible + 1024);
    std::vector<Point>& points = builder_.mesh().points;
    points.reserve(plausible);
    for (std::int64_t i = 0; i < count; ++i) {
      std::uint64_t tag = 0;
      AFMESH_RETURN_IF_ERROR(read_tag("a node tag", tag));
      if (!builder_.nodes().insert(tag, static_cast<Index>(i))) {
        return scanner_.error(str_cat("node tag ", tag, " appears twice"));
      }
      Point& point = points.emplace_back();
      for (double& coordinate : point) {
        AFMESH_RETURN_IF_ERROR(scanner_.read_double(coordinate, "a node coordinate"));
      }
    }
    builder_.set_has_nodes();
    return absl::OkStatus();
  }

  absl::Status read_elements() {
    if (!builder_.has_nodes()) return scanner_.error("$Elements before $Nodes");
    if (builder_.has_elements()) return scanner_.error("a second $Elements section");
    std::int64_t count = 0;
    AFMESH_RETURN_IF_ERROR(read_count("the element count", count));
    for (std::int64_t i = 0; i < count; ++i) AFMESH_RETURN_IF_ERROR(read_element());
    builder_.set_has_elements();
    return absl::OkStatus();
  }

  // elm-number elm-type number-of-tags tag... node-number...; the first tag is the physical.
  absl::Status read_element() {
    std::uint64_t element_tag = 0;
    std::int64_t type = 0, num_tags = 0;
    AFMESH_RETURN_IF_ERROR(read_tag("an element tag", element_tag));
    AFMESH_RETURN_IF_ERROR(scanner_.read_int(type, "an element type"));
    const ElementType element = element_type(type);
    if (element.kind == ElementKind::kUnsupported) {
      return scanner_.error(unsupported_element_message(type));
    }
    AFMESH_RETURN_IF_ERROR(scanner_.read_int(num_tags, "the number of element tags"));
    if (num_tags < 0 || num_tags > kMaxElementTags) {
      return scanner_.error(str_cat("number of element tags ", num_tags, " is out of range [0, ",
                                    kMaxElementTags, "]"));
    }
    Index physical = 0;
    for (std::int64_t t = 0; t < num_tags; ++t) {
      std::int64_t value = 0;
      AFMESH_RETURN_IF_ERROR(scanner_.read_int(value, "an element tag value"));
      if (t > 0) continue;
      if (value < std::numeric_limits<Index>::min() || value > std::numeric_limits<Index>::max()) {
        return scanner_.error(str_cat("physical tag ", value, " does not fit in 32 bits"));
      }
      physical = static_cast<Index>(value);
    }
    std::array<Index, 4> corners{};
    for (int k = 0; k < element.num_nodes; ++k) {
      std::uint64_t node_tag = 0;
      AFMESH_RETURN_IF_ERROR(read_tag("a node tag", node_tag));
      corners[k] = builder_.nodes().find(node_tag);
      if (corners[k] == kInvalidIndex) {
        return scanner_.error(str_cat("element ", element_tag, " refers to node tag ", node_tag,
                                      ", which $Nodes does not define"));
      }
    }
    switch (element.kind) {
      case ElementKind::kTriangle:
        builder_.add_triangle(element_tag, {corners[0], corners[1], corners[2]}, physical);
        break;
      case ElementKind::kTet:
        builder_.add_tet(element_tag, corners, physical);
        break;
      default:
        builder_.skip_elements(element.kind, 1);
    }
    return absl::OkStatus();
  }

  TextScanner& scanner_;
  MeshBuilder& builder_;
};

}  // namespace

absl::Status read_msh2_sections(TextScanner& scanner, MeshBuilder& builder) {
  return Msh2Reader(scanner, builder).read_sections();
}

}  // namespace afmesh::msh
