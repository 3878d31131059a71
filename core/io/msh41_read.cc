// MSH 4.1 sections, ascii and binary: one reader templated on how fields are decoded.
#include <cmath>
#include <cstdint>
#include <limits>

#include "absl/container/flat_hash_map.h"
#include "core/io/little_endian.h"
#include "core/io/msh_readers.h"
#include "core/io/return_if_error.h"
#include "core/io/string_util.h"

namespace afmesh::msh {
namespace {

// Fields of an ascii file: whitespace-separated tokens.
class AsciiFields {
 public:
  static constexpr std::size_t kMinNodeBytes = 8;  // "1\n0 0 0\n"

  explicit AsciiFields(TextScanner& scanner) : scanner_(scanner) {}

  absl::Status size(std::uint64_t& value, std::string_view what) {
    std::int64_t read = 0;
    AFMESH_RETURN_IF_ERROR(scanner_.read_int(read, what));
    if (read < 0) {
      return scanner_.error(str_cat("expected a non-negative integer (", what, "), found ", read));
    }
    value = static_cast<std::uint64_t>(read);
    return absl::OkStatus();
  }
  absl::Status integer(std::int32_t& value, std::string_view what) {
    std::int64_t read = 0;
    AFMESH_RETURN_IF_ERROR(scanner_.read_int(read, what));
    if (read < std::numeric_limits<std::int32_t>::min() ||
        read > std::numeric_limits<std::int32_t>::max()) {
      return scanner_.error(str_cat(what, " ", read, " does not fit in 32 bits"));
    }
    value = static_cast<std::int32_t>(read);
    return absl::OkStatus();
  }
  absl::Status real(double& value, std::string_view what) {
    return scanner_.read_double(value, what);
  }
  absl::Status any_real(double& value, std::string_view what) {
    return scanner_.read_any_double(value, what);
  }
  absl::Status error(std::string_view message) const { return scanner_.error(message); }
  TextScanner& scanner() { return scanner_; }

 private:
  TextScanner& scanner_;
};

// Fields of a binary file: int32, 8-byte size_t and double, little-endian.
class BinaryFields {
 public:
  static constexpr std::size_t kMinNodeBytes = 32;  // tag + 3 doubles

  explicit BinaryFields(TextScanner& scanner) : scanner_(scanner) {}

  absl::Status size(std::uint64_t& value, std::string_view what) { return load(value, what); }
  absl::Status integer(std::int32_t& value, std::string_view what) { return load(value, what); }
  absl::Status real(double& value, std::string_view what) {
    AFMESH_RETURN_IF_ERROR(load(value, what));
    if (!std::isfinite(value)) {
      return scanner_.error(str_cat("expected a finite number (", what, "), found ", value));
    }
    return absl::OkStatus();
  }
  absl::Status any_real(double& value, std::string_view what) { return load(value, what); }
  absl::Status error(std::string_view message) const { return scanner_.error(message); }
  TextScanner& scanner() { return scanner_; }

 private:
  template <typename T>
  absl::Status load(T& value, std::string_view what) {
    const char* bytes = nullptr;
    AFMESH_RETURN_IF_ERROR(scanner_.take_bytes(sizeof(T), what, bytes));
    value = load_little_endian<T>(bytes);
    return absl::OkStatus();
  }

  TextScanner& scanner_;
};

// Physical tag of each entity, keyed by (dimension, entity tag).
class EntityPhysicals {
 public:
  void set(std::int32_t dim, std::int32_t tag, Index physical) {
    physical_[key(dim, tag)] = physical;
  }
  bool find(std::int32_t dim, std::int32_t tag, Index& physical) const {
    const auto it = physical_.find(key(dim, tag));
    if (it == physical_.end()) return false;
    physical = it->second;
    return true;
  }

 private:
  static std::int64_t key(std::int32_t dim, std::int32_t tag) {
    return (std::int64_t{dim} << 32) | static_cast<std::uint32_t>(tag);
  }
  absl::flat_hash_map<std::int64_t, Index> physical_;
};

constexpr const char* kDimensionNames[] = {"point", "curve", "surface", "volume"};

template <typename Fields>
class Msh41Reader {
 public:
  Msh41Reader(TextScanner& scanner, MeshBuilder& builder)
      : scanner_(scanner), fields_(scanner), builder_(builder) {}

  absl::Status read_sections(bool binary) {
    binary_ = binary;
    while (!scanner_.at_end()) {
      const std::string_view header = scanner_.next_token();
      if (header.size() < 2 || header[0] != '$') {
        return scanner_.unexpected("a section header such as '$Nodes'", header);
      }
      const std::string_view name = header.substr(1);
      if (binary) scanner_.skip_line();  // binary data starts on the next line
      AFMESH_RETURN_IF_ERROR(read_section(name));
    }
    return absl::OkStatus();
  }

 private:
  absl::Status read_section(std::string_view name) {
    if (name == "Entities") {
      AFMESH_RETURN_IF_ERROR(read_entities());
    } else if (name == "Nodes") {
      AFMESH_RETURN_IF_ERROR(read_nodes());
    } else if (name == "Elements") {
      AFMESH_RETURN_IF_ERROR(read_elements());
    } else if (name == "NodeData") {
      return read_node_data_section(scanner_, binary_, builder_);
    } else if (name == "PartitionedEntities") {
      return scanner_.error("partitioned MSH files are not supported (save unpartitioned)");
    } else if (name == "MeshFormat") {
      return scanner_.error("a second $MeshFormat section");
    } else {
      if (name != "Comments") builder_.add_note(str_cat("skipped MSH section $", name));
      return skip_section(scanner_, name);
    }
    return expect_section_end(scanner_, name);
  }

  // numPoints numCurves numSurfaces numVolumes, then per entity: tag, bounding box,
  // physical tags and (curves and up) bounding entities.
  absl::Status read_entities() {
    if (has_entities_) return scanner_.error("a second $Entities section");
    has_entities_ = true;
    std::uint64_t counts[4];
    for (std::uint64_t& count : counts) {
      AFMESH_RETURN_IF_ERROR(fields_.size(count, "an entity count"));
    }
    std::uint64_t several_physicals = 0;
    for (int dim = 0; dim < 4; ++dim) {
      for (std::uint64_t e = 0; e < counts[dim]; ++e) {
        std::int32_t tag = 0;
        AFMESH_RETURN_IF_ERROR(fields_.integer(tag, "an entity tag"));
        for (int i = 0; i < (dim == 0 ? 3 : 6); ++i) {
          double ignored = 0;
          AFMESH_RETURN_IF_ERROR(fields_.any_real(ignored, "an entity bounding box coordinate"));
        }
        std::uint64_t num_physicals = 0;
        AFMESH_RETURN_IF_ERROR(fields_.size(num_physicals, "a physical tag count"));
        Index first = 0;
        for (std::uint64_t p = 0; p < num_physicals; ++p) {
          std::int32_t physical = 0;
          AFMESH_RETURN_IF_ERROR(fields_.integer(physical, "a physical tag"));
          if (p == 0) first = physical;
        }
        if (num_physicals > 1) ++several_physicals;
        entities_.set(dim, tag, first);
        if (dim > 0) AFMESH_RETURN_IF_ERROR(skip_bounding_entities());
      }
    }
    if (several_physicals > 0) {
      builder_.add_note(str_cat(several_physicals,
                                " entities have several physical tags; their elements "
                                "take the first"));
    }
    return absl::OkStatus();
  }

  absl::Status skip_bounding_entities() {
    std::uint64_t count = 0;
    AFMESH_RETURN_IF_ERROR(fields_.size(count, "a bounding entity count"));
    for (std::uint64_t b = 0; b < count; ++b) {
      std::int32_t ignored = 0;
      AFMESH_RETURN_IF_ERROR(fields_.integer(ignored, "a bounding entity tag"));
    }
    return absl::OkStatus();
  }

  // numEntityBlocks numNodes minNodeTag maxNodeTag, then blocks of tags and coordinates.
  absl::Status read_nodes() {
    if (builder_.has_nodes()) return scanner_.error("a second $Nodes section");
    std::uint64_t num_blocks = 0, num_nodes = 0, min_tag = 0, max_tag = 0;
    AFMESH_RETURN_IF_ERROR(fields_.size(num_blocks, "the node block count"));
    AFMESH_RETURN_IF_ERROR(fields_.size(num_nodes, "the node count"));
    AFMESH_RETURN_IF_ERROR(fields_.size(min_tag, "the smallest node tag"));
    AFMESH_RETURN_IF_ERROR(fields_.size(max_tag, "the largest node tag"));
    if (num_nodes > static_cast<std::uint64_t>(std::numeric_limits<Index>::max())) {
      return fields_.error(str_cat(num_nodes, " nodes are more than afmesh supports"));
    }
    const std::size_t plausible = plausible_count(scanner_, num_nodes, Fields::kMinNodeBytes);
    builder_.nodes() = NodeTagMap(std::min<std::uint64_t>(max_tag + 1, 4 * plausible + 1024));
    builder_.mesh().points.reserve(plausible);
    for (std::uint64_t b = 0; b < num_blocks; ++b) {
      AFMESH_RETURN_IF_ERROR(read_node_block(num_nodes));
    }
    if (builder_.mesh().points.size() != num_nodes) {
      return fields_.error(str_cat("the $Nodes header declares ", num_nodes,
                                   " nodes, but its blocks hold ", builder_.mesh().points.size()));
    }
    builder_.set_has_nodes();
    return absl::OkStatus();
  }

  // entityDim entityTag parametric numNodesInBlock, node tags, then x y z [u [v [w]]] each.
  absl::Status read_node_block(std::uint64_t declared_nodes) {
    std::int32_t dim = 0, entity = 0, parametric = 0;
    std::uint64_t count = 0;
    AFMESH_RETURN_IF_ERROR(fields_.integer(dim, "the entity dimension"));
    AFMESH_RETURN_IF_ERROR(fields_.integer(entity, "the entity tag"));
    AFMESH_RETURN_IF_ERROR(fields_.integer(parametric, "the parametric flag"));
    AFMESH_RETURN_IF_ERROR(fields_.size(count, "the number of nodes in the block"));
    if (dim < 0 || dim > 3)
      return fields_.error(str_cat("entity dimension ", dim, " is not 0 to 3"));
    if (parametric != 0 && parametric != 1) {
      return fields_.error(str_cat("parametric flag ", parametric, " is not 0 or 1"));
    }
    std::vector<Point>& points = builder_.mesh().points;
    const std::size_t first = points.size();
    if (count > declared_nodes - first) {
      return fields_.error(str_cat("node blocks hold more nodes than the ", declared_nodes,
                                   " the $Nodes header declares"));
    }
    for (std::uint64_t i = 0; i < count; ++i) {
      std::uint64_t tag = 0;
      AFMESH_RETURN_IF_ERROR(fields_.size(tag, "a node tag"));
      if (!builder_.nodes().insert(tag, static_cast<Index>(first + i))) {
        return fields_.error(str_cat("node tag ", tag, " appears twice"));
      }
    }
    const int extra = parametric == 1 ? dim : 0;
    if (extra > 0) ++parametric_blocks_;
    for (std::uint64_t i = 0; i < count; ++i) {
      Point& point = points.emplace_back();
      for (double& coordinate : point) {
        AFMESH_RETURN_IF_ERROR(fields_.real(coordinate, "a node coordinate"));
      }
      for (int k = 0; k < extra; ++k) {
        double ignored = 0;
        AFMESH_RETURN_IF_ERROR(fields_.any_real(ignored, "a parametric coordinate"));
      }
    }
    return absl::OkStatus();
  }

  // numEntityBlocks numElements minElementTag maxElementTag, then blocks of elements.
  absl::Status read_elements() {
    if (!builder_.has_nodes()) return scanner_.error("$Elements before $Nodes");
    if (builder_.has_elements()) return scanner_.error("a second $Elements section");
    std::uint64_t num_blocks = 0, num_elements = 0, min_tag = 0, max_tag = 0;
    AFMESH_RETURN_IF_ERROR(fields_.size(num_blocks, "the element block count"));
    AFMESH_RETURN_IF_ERROR(fields_.size(num_elements, "the element count"));
    AFMESH_RETURN_IF_ERROR(fields_.size(min_tag, "the smallest element tag"));
    AFMESH_RETURN_IF_ERROR(fields_.size(max_tag, "the largest element tag"));
    std::uint64_t read = 0;
    for (std::uint64_t b = 0; b < num_blocks; ++b) {
      AFMESH_RETURN_IF_ERROR(read_element_block(num_elements, read));
    }
    if (read != num_elements) {
      return fields_.error(str_cat("the $Elements header declares ", num_elements,
                                   " elements, but its blocks hold ", read));
    }
    if (!has_entities_ && num_elements > 0) {
      builder_.add_note("no $Entities section: every element gets tag 0");
    }
    if (parametric_blocks_ > 0) {
      builder_.add_note(
          str_cat("ignored the parametric coordinates of ", parametric_blocks_, " node blocks"));
    }
    builder_.set_has_elements();
    return absl::OkStatus();
  }

  // entityDim entityTag elementType numElementsInBlock, then elementTag nodeTag... each.
  absl::Status read_element_block(std::uint64_t declared, std::uint64_t& read) {
    std::int32_t dim = 0, entity = 0, type = 0;
    std::uint64_t count = 0;
    AFMESH_RETURN_IF_ERROR(fields_.integer(dim, "the entity dimension"));
    AFMESH_RETURN_IF_ERROR(fields_.integer(entity, "the entity tag"));
    AFMESH_RETURN_IF_ERROR(fields_.integer(type, "the element type"));
    AFMESH_RETURN_IF_ERROR(fields_.size(count, "the number of elements in the block"));
    const ElementType element = element_type(type);
    if (element.kind == ElementKind::kUnsupported) {
      return fields_.error(unsupported_element_message(type));
    }
    if (dim < 0 || dim > 3)
      return fields_.error(str_cat("entity dimension ", dim, " is not 0 to 3"));
    Index physical = 0;
    if (has_entities_ && !entities_.find(dim, entity, physical)) {
      return fields_.error(str_cat("the element block refers to ", kDimensionNames[dim], " entity ",
                                   entity, ", which $Entities does not declare"));
    }
    if (count > declared - read) {
      return fields_.error(str_cat("element blocks hold more elements than the ", declared,
                                   " the $Elements header declares"));
    }
    for (std::uint64_t i = 0; i < count; ++i) {
      AFMESH_RETURN_IF_ERROR(read_element(element, physical));
    }
    if (element.kind == ElementKind::kPoint || element.kind == ElementKind::kLine) {
      builder_.skip_elements(element.kind, count);
    }
    read += count;
    return absl::OkStatus();
  }

  absl::Status read_element(const ElementType& element, Index physical) {
    std::uint64_t element_tag = 0;
    AFMESH_RETURN_IF_ERROR(fields_.size(element_tag, "an element tag"));
    std::array<Index, 4> corners{};
    for (int k = 0; k < element.num_nodes; ++k) {
      std::uint64_t node_tag = 0;
      AFMESH_RETURN_IF_ERROR(fields_.size(node_tag, "a node tag"));
      if (element.kind != ElementKind::kTriangle && element.kind != ElementKind::kTet) continue;
      corners[k] = builder_.nodes().find(node_tag);
      if (corners[k] == kInvalidIndex) {
        return fields_.error(str_cat("element ", element_tag, " refers to node tag ", node_tag,
                                     ", which $Nodes does not define"));
      }
    }
    if (element.kind == ElementKind::kTriangle) {
      builder_.add_triangle(element_tag, {corners[0], corners[1], corners[2]}, physical);
    } else if (element.kind == ElementKind::kTet) {
      builder_.add_tet(element_tag, corners, physical);
    }
    return absl::OkStatus();
  }

  TextScanner& scanner_;
  Fields fields_;
  MeshBuilder& builder_;
  EntityPhysicals entities_;
  bool has_entities_ = false;
  bool binary_ = false;
  std::uint64_t parametric_blocks_ = 0;
};

}  // namespace

absl::Status read_msh41_sections(TextScanner& scanner, bool binary, MeshBuilder& builder) {
  if (binary) return Msh41Reader<BinaryFields>(scanner, builder).read_sections(true);
  return Msh41Reader<AsciiFields>(scanner, builder).read_sections(false);
}

}  // namespace afmesh::msh
