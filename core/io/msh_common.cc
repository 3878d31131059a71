#include "core/io/msh_common.h"

#include <algorithm>
#include <numeric>

#include "core/io/string_util.h"

namespace afmesh::msh {
namespace {

struct NamedType {
  std::int64_t type;
  std::string_view name;
};

// The common gmsh element types that afmesh does not read, named for error messages.
constexpr NamedType kUnsupportedTypes[] = {
    {3, "4-node quadrangle"},
    {5, "8-node hexahedron"},
    {6, "6-node prism"},
    {7, "5-node pyramid"},
    {8, "3-node second order line"},
    {9, "6-node second order triangle"},
    {10, "9-node second order quadrangle"},
    {11, "10-node second order tetrahedron"},
    {12, "27-node second order hexahedron"},
    {13, "18-node second order prism"},
    {14, "14-node second order pyramid"},
    {16, "8-node second order quadrangle"},
    {17, "20-node second order hexahedron"},
    {18, "15-node second order prism"},
    {19, "13-node second order pyramid"},
};

std::string_view element_name(std::int64_t gmsh_type) {
  for (const NamedType& named : kUnsupportedTypes) {
    if (named.type == gmsh_type) return named.name;
  }
  return "unknown to afmesh";
}

// Reorders `elements` and `tags` so that `keys` increase (stable for equal keys).
template <typename Element>
void sort_by_keys(std::vector<std::uint64_t>& keys, std::vector<Element>& elements,
                  std::vector<Index>& tags) {
  if (std::is_sorted(keys.begin(), keys.end())) return;
  std::vector<std::size_t> order(keys.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::stable_sort(order.begin(), order.end(),
                   [&keys](std::size_t a, std::size_t b) { return keys[a] < keys[b]; });
  std::vector<Element> sorted_elements(elements.size());
  std::vector<Index> sorted_tags(tags.size());
  for (std::size_t i = 0; i < order.size(); ++i) {
    sorted_elements[i] = elements[order[i]];
    sorted_tags[i] = tags[order[i]];
  }
  elements.swap(sorted_elements);
  tags.swap(sorted_tags);
}

}  // namespace

ElementType element_type(std::int64_t gmsh_type) {
  switch (gmsh_type) {
    case 1:
      return {ElementKind::kLine, 2};
    case 2:
      return {ElementKind::kTriangle, 3};
    case 4:
      return {ElementKind::kTet, 4};
    case 15:
      return {ElementKind::kPoint, 1};
    default:
      return {};
  }
}

std::string unsupported_element_message(std::int64_t gmsh_type) {
  return str_cat("element type ", gmsh_type, " (", element_name(gmsh_type),
                 ") is not supported: afmesh reads 3-node triangles (type 2) and 4-node "
                 "tetrahedra (type 4), and skips points (15) and 2-node lines (1)");
}

bool NodeTagMap::insert(std::uint64_t tag, Index index) {
  if (tag < dense_limit_) {
    if (dense_.empty()) dense_.assign(dense_limit_, kInvalidIndex);
    if (dense_[tag] != kInvalidIndex) return false;
    dense_[tag] = index;
    return true;
  }
  return sparse_.try_emplace(tag, index).second;
}

Index NodeTagMap::find(std::uint64_t tag) const {
  if (tag < dense_limit_) return dense_.empty() ? kInvalidIndex : dense_[tag];
  const auto it = sparse_.find(tag);
  return it == sparse_.end() ? kInvalidIndex : it->second;
}

void MeshBuilder::skip_elements(ElementKind kind, std::uint64_t count) {
  if (kind == ElementKind::kPoint) skipped_points_ += count;
  if (kind == ElementKind::kLine) skipped_lines_ += count;
}

Mesh MeshBuilder::finish(ReadReport* report) {
  sort_by_keys(triangle_keys_, mesh_.triangles, mesh_.triangle_tags);
  sort_by_keys(tet_keys_, mesh_.tets, mesh_.tet_tags);
  if (skipped_points_ > 0) {
    afmesh::add_note(report,
                     str_cat("skipped ", skipped_points_, " point elements (gmsh type 15)"));
  }
  if (skipped_lines_ > 0) {
    afmesh::add_note(report, str_cat("skipped ", skipped_lines_, " line elements (gmsh type 1)"));
  }
  for (std::string& note : notes_) afmesh::add_note(report, std::move(note));
  return std::move(mesh_);
}

absl::Status skip_section(TextScanner& scanner, std::string_view name) {
  const std::string end_marker = str_cat("$End", name);
  const std::size_t found = scanner.text().find(end_marker, scanner.offset());
  if (found == std::string_view::npos) {
    return scanner.error(str_cat("section $", name, " has no ", end_marker));
  }
  scanner.seek(found);
  return expect_section_end(scanner, name);
}

absl::Status expect_section_end(TextScanner& scanner, std::string_view name) {
  const std::string_view token = scanner.next_token();
  if (token.size() != name.size() + 4 || token.substr(0, 4) != "$End" || token.substr(4) != name) {
    return scanner.unexpected(str_cat("'$End", name, "'"), token);
  }
  return absl::OkStatus();
}

std::size_t plausible_count(const TextScanner& scanner, std::uint64_t count,
                            std::size_t min_bytes) {
  const std::size_t remaining = scanner.text().size() - scanner.offset();
  return static_cast<std::size_t>(std::min<std::uint64_t>(count, remaining / min_bytes + 1));
}

}  // namespace afmesh::msh
