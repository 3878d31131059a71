// $NodeData as a size per node (background-grid files), for MSH 4.1 (ascii, binary) and 2.x.
//
// A section is: numStringTags, one quoted string per line (the view name first); numRealTags and
// the reals (the time first); numIntegerTags and the integers (time step, components, node count,
// [partition]); then `node-tag value...` per node. The tags are ascii in every version; in binary
// files the entries are an int32 node tag and `components` doubles.
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

#include "core/io/little_endian.h"
#include "core/io/msh_common.h"
#include "core/io/return_if_error.h"
#include "core/io/string_util.h"

namespace afmesh::msh {
namespace {

constexpr std::int64_t kMaxTags = 1024;  // gmsh writes 1 to 4 of each kind

// What the integer tags of a view say.
struct ViewHeader {
  std::int64_t components = 0;
  std::int64_t entries = 0;
};

absl::Status read_tag_count(TextScanner& scanner, std::string_view what, std::int64_t& count) {
  AFMESH_RETURN_IF_ERROR(scanner.read_int(count, what));
  if (count < 0 || count > kMaxTags) {
    return scanner.error(str_cat(what, " ", count, " is out of range [0, ", kMaxTags, "]"));
  }
  return absl::OkStatus();
}

// The tags before the entries. String tags are whole lines (a quoted name may hold blanks).
absl::Status read_view_header(TextScanner& scanner, ViewHeader& header) {
  std::int64_t count = 0;
  AFMESH_RETURN_IF_ERROR(read_tag_count(scanner, "the number of string tags", count));
  scanner.skip_line();
  for (std::int64_t i = 0; i < count; ++i) {
    if (scanner.at_end()) return scanner.unexpected("a string tag (a quoted view name)", "");
    scanner.rest_of_line();
    scanner.skip_line();
  }
  AFMESH_RETURN_IF_ERROR(read_tag_count(scanner, "the number of real tags", count));
  for (std::int64_t i = 0; i < count; ++i) {
    double ignored = 0;
    AFMESH_RETURN_IF_ERROR(scanner.read_any_double(ignored, "a real tag"));
  }
  AFMESH_RETURN_IF_ERROR(read_tag_count(scanner, "the number of integer tags", count));
  if (count < 3) {
    return scanner.error(
        str_cat("a $NodeData view needs at least 3 integer tags (time step, "
                "number of components, number of nodes), found ",
                count));
  }
  for (std::int64_t i = 0; i < count; ++i) {
    std::int64_t value = 0;
    AFMESH_RETURN_IF_ERROR(scanner.read_int(value, "an integer tag"));
    if (i == 1) header.components = value;
    if (i == 2) header.entries = value;
  }
  return absl::OkStatus();
}

// One `node-tag size` entry: ascii tokens, or int32 and double in a binary file.
absl::Status read_entry(TextScanner& scanner, bool binary, std::int64_t& tag, double& size) {
  if (!binary) {
    AFMESH_RETURN_IF_ERROR(scanner.read_int(tag, "a node tag"));
    return scanner.read_any_double(size, "the size of a node");
  }
  const char* bytes = nullptr;
  AFMESH_RETURN_IF_ERROR(scanner.take_bytes(4, "a node tag (int32)", bytes));
  tag = load_little_endian<std::int32_t>(bytes);
  AFMESH_RETURN_IF_ERROR(scanner.take_bytes(8, "the size of a node (double)", bytes));
  size = load_little_endian<double>(bytes);
  return absl::OkStatus();
}

// The entries of the view: every node of $Nodes exactly once, each size finite and > 0.
absl::Status read_sizes(TextScanner& scanner, bool binary, MeshBuilder& builder,
                        std::int64_t entries) {
  std::vector<double>& sizes = builder.node_sizes();
  sizes.assign(builder.mesh().points.size(), std::numeric_limits<double>::quiet_NaN());
  if (binary) scanner.skip_line();  // the binary entries start on the next line
  for (std::int64_t i = 0; i < entries; ++i) {
    std::int64_t tag = 0;
    double size = 0;
    AFMESH_RETURN_IF_ERROR(read_entry(scanner, binary, tag, size));
    const Index point =
        tag < 0 ? kInvalidIndex : builder.nodes().find(static_cast<std::uint64_t>(tag));
    if (point == kInvalidIndex) {
      return scanner.error(
          str_cat("$NodeData gives a size for node tag ", tag, ", which $Nodes does not define"));
    }
    if (!std::isnan(sizes[point])) {
      return scanner.error(str_cat("$NodeData gives node tag ", tag, " a second size"));
    }
    if (!std::isfinite(size) || size <= 0.0) {
      return scanner.error(
          str_cat("the size of node tag ", tag, " must be finite and > 0, found ", size));
    }
    sizes[point] = size;
  }
  return absl::OkStatus();
}

absl::Status read_node_sizes(TextScanner& scanner, bool binary, MeshBuilder& builder) {
  if (!builder.has_nodes()) {
    return scanner.error("$NodeData before $Nodes: the sizes must follow the mesh they belong to");
  }
  ViewHeader header;
  AFMESH_RETURN_IF_ERROR(read_view_header(scanner, header));
  if (header.components != 1) {
    return scanner.error(str_cat("the $NodeData view has ", header.components,
                                 " components per node; a size field needs 1 (a scalar)"));
  }
  const std::size_t nodes = builder.mesh().points.size();
  if (header.entries < 0 || static_cast<std::uint64_t>(header.entries) != nodes) {
    return scanner.error(str_cat("the $NodeData view gives values for ", header.entries,
                                 " nodes, but $Nodes defines ", nodes,
                                 ": a background grid needs one size per node"));
  }
  AFMESH_RETURN_IF_ERROR(read_sizes(scanner, binary, builder, header.entries));
  builder.set_has_node_sizes();
  return expect_section_end(scanner, "NodeData");
}

}  // namespace

absl::Status read_node_data_section(TextScanner& scanner, bool binary, MeshBuilder& builder) {
  if (builder.wants_node_sizes() && !builder.has_node_sizes()) {
    return read_node_sizes(scanner, binary, builder);
  }
  builder.add_note(builder.wants_node_sizes()
                       ? "skipped a later $NodeData section (the sizes are the first view's)"
                       : "skipped MSH section $NodeData");
  return skip_section(scanner, "NodeData");
}

}  // namespace afmesh::msh
