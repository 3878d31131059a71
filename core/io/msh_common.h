// Pieces shared by the MSH 4.1 and 2.x readers (internal to core/io): the element type table,
// the node-tag map and the builder that collects elements and orders them by element tag.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "absl/container/flat_hash_map.h"
#include "absl/status/status.h"
#include "core/io/read_report.h"
#include "core/io/text_scanner.h"
#include "core/mesh/mesh.h"

namespace afmesh::msh {

// What the readers do with a gmsh element type.
enum class ElementKind { kTriangle, kTet, kPoint, kLine, kUnsupported };

struct ElementType {
  ElementKind kind = ElementKind::kUnsupported;
  int num_nodes = 0;  // nodes per element; 0 when unsupported
};

// The handling of gmsh element type `gmsh_type` (2 -> triangle, 4 -> tet, 15 -> point,
// 1 -> line; everything else unsupported).
ElementType element_type(std::int64_t gmsh_type);

// "element type 11 (10-node tetrahedron) is not supported: ..." for an unsupported type.
std::string unsupported_element_message(std::int64_t gmsh_type);

// Node tag -> point index. Tags below a bound go in a direct table, larger ones in a hash map,
// so dense numberings cost 4 bytes per tag and sparse ones stay proportional to the node count.
class NodeTagMap {
 public:
  // Tags in [0, dense_limit) use the direct table (allocated on first use).
  explicit NodeTagMap(std::uint64_t dense_limit = 0) : dense_limit_(dense_limit) {}
  // Records `tag` -> `index`; false when `tag` is already there.
  bool insert(std::uint64_t tag, Index index);
  // The index recorded for `tag`, or kInvalidIndex.
  Index find(std::uint64_t tag) const;

 private:
  std::uint64_t dense_limit_;
  std::vector<Index> dense_;
  absl::flat_hash_map<std::uint64_t, Index> sparse_;
};

// Collects points and elements while a file is read, then hands out the Mesh with elements in
// increasing element-tag order.
class MeshBuilder {
 public:
  Mesh& mesh() { return mesh_; }
  NodeTagMap& nodes() { return nodes_; }
  // Whether the $Nodes / $Elements section has been read (each must appear exactly once).
  bool has_nodes() const { return has_nodes_; }
  void set_has_nodes() { has_nodes_ = true; }
  bool has_elements() const { return has_elements_; }
  void set_has_elements() { has_elements_ = true; }

  void add_triangle(std::uint64_t element_tag, const Triangle& triangle, Index tag) {
    mesh_.triangles.push_back(triangle);
    mesh_.triangle_tags.push_back(tag);
    triangle_keys_.push_back(element_tag);
  }
  void add_tet(std::uint64_t element_tag, const Tet& tet, Index tag) {
    mesh_.tets.push_back(tet);
    mesh_.tet_tags.push_back(tag);
    tet_keys_.push_back(element_tag);
  }
  // Counts `count` elements of a kind that is passed over (points, lines).
  void skip_elements(ElementKind kind, std::uint64_t count);

  // Node sizes (background-grid files): when asked for, the first $NodeData section is read
  // into node_sizes() (one per point, in point order) by read_node_data_section; later ones are
  // skipped with a note. Otherwise every $NodeData section is skipped with a note.
  void want_node_sizes() { wants_node_sizes_ = true; }
  bool wants_node_sizes() const { return wants_node_sizes_; }
  bool has_node_sizes() const { return has_node_sizes_; }
  void set_has_node_sizes() { has_node_sizes_ = true; }
  std::vector<double>& node_sizes() { return node_sizes_; }
  void add_note(std::string note) { notes_.push_back(std::move(note)); }

  // The mesh, elements sorted by element tag (stable), and the notes appended to `report`.
  Mesh finish(ReadReport* report);

 private:
  Mesh mesh_;
  NodeTagMap nodes_;
  bool has_nodes_ = false;
  bool has_elements_ = false;
  std::vector<std::uint64_t> triangle_keys_;
  std::vector<std::uint64_t> tet_keys_;
  bool wants_node_sizes_ = false;
  bool has_node_sizes_ = false;
  std::vector<double> node_sizes_;
  std::uint64_t skipped_points_ = 0;
  std::uint64_t skipped_lines_ = 0;
  std::vector<std::string> notes_;
};

// Reads or skips a $NodeData section whose header was just read, through its $EndNodeData.
// Read when builder.wants_node_sizes() and it is the first: string, real and integer tags (ascii
// in every MSH version), then one `node-tag size` entry per node (ascii; binary: int32 tag and
// double, little-endian, as gmsh writes them). Checks one component, an entry for every node of
// $Nodes and no other, finite sizes > 0; errors name the line (or byte offset) and what was
// expected. Skipped, with a note, otherwise.
absl::Status read_node_data_section(TextScanner& scanner, bool binary, MeshBuilder& builder);

// Moves `scanner` past the marker "$End<name>" of the section `name` whose header was just
// read, without reading its content; error when the marker is missing.
absl::Status skip_section(TextScanner& scanner, std::string_view name);

// Reads the next token and checks it is "$End<name>".
absl::Status expect_section_end(TextScanner& scanner, std::string_view name);

// Room to reserve for `count` items of at least `min_bytes` each in what remains of the text:
// a corrupt count must not allocate more than the file could describe.
std::size_t plausible_count(const TextScanner& scanner, std::uint64_t count, std::size_t min_bytes);

}  // namespace afmesh::msh
