// parse_msh: the $MeshFormat header, then the version-specific section readers.
#include <cstdint>

#include "core/io/little_endian.h"
#include "core/io/msh.h"
#include "core/io/msh_readers.h"
#include "core/io/return_if_error.h"
#include "core/io/string_util.h"

namespace afmesh {
namespace {

enum class MshVersion { k41, k2 };

struct MshHeader {
  MshVersion version = MshVersion::k41;
  bool binary = false;
};

// `$MeshFormat` / `version file-type data-size` [binary one] / `$EndMeshFormat`.
absl::Status read_header(TextScanner& scanner, MshHeader& header) {
  const std::string_view first = scanner.next_token();
  if (first != "$MeshFormat") {
    return scanner.unexpected("'$MeshFormat' (the first line of a gmsh MSH file)", first);
  }
  const std::string_view version = scanner.next_token();
  if (version == "4.1") {
    header.version = MshVersion::k41;
  } else if (version == "2" || version == "2.0" || version == "2.1" || version == "2.2") {
    header.version = MshVersion::k2;
  } else {
    return scanner.error(
        str_cat("MSH version '", version, "' is not supported (afmesh reads 4.1 and 2.2)"));
  }
  std::int64_t file_type = 0;
  std::int64_t data_size = 0;
  AFMESH_RETURN_IF_ERROR(scanner.read_int(file_type, "the file type (0 ascii, 1 binary)"));
  AFMESH_RETURN_IF_ERROR(scanner.read_int(data_size, "the data size"));
  if (file_type != 0 && file_type != 1) {
    return scanner.error(str_cat("file type ", file_type, " is neither 0 (ascii) nor 1 (binary)"));
  }
  header.binary = file_type == 1;
  if (header.binary && header.version == MshVersion::k2) {
    return scanner.error(
        "binary MSH 2 is not supported: save as MSH 4.1 (ascii or binary) or "
        "MSH 2.2 ascii");
  }
  if (header.binary) {
    if (data_size != 8) {
      return scanner.error(
          str_cat("binary MSH with data size ", data_size, " is not supported (expected 8)"));
    }
    scanner.report_offsets();
    scanner.skip_line();
    const char* one = nullptr;
    AFMESH_RETURN_IF_ERROR(scanner.take_bytes(4, "the endianness check (int 1)", one));
    if (load_little_endian<std::int32_t>(one) != 1) {
      return scanner.error("big-endian binary MSH is not supported (the check value is not 1)");
    }
  }
  return msh::expect_section_end(scanner, "MeshFormat");
}

// Reads the whole file into `builder`, checking that it holds $Nodes and $Elements.
absl::Status read_msh(TextScanner& scanner, msh::MeshBuilder& builder) {
  MshHeader header;
  AFMESH_RETURN_IF_ERROR(read_header(scanner, header));
  if (header.version == MshVersion::k41) {
    AFMESH_RETURN_IF_ERROR(msh::read_msh41_sections(scanner, header.binary, builder));
  } else {
    AFMESH_RETURN_IF_ERROR(msh::read_msh2_sections(scanner, builder));
  }
  if (!builder.has_nodes()) return scanner.error("the file has no $Nodes section");
  if (!builder.has_elements()) return scanner.error("the file has no $Elements section");
  return absl::OkStatus();
}

}  // namespace

absl::StatusOr<Mesh> parse_msh(std::string_view bytes, std::string_view source_name,
                               ReadReport* report) {
  if (bytes.empty()) {
    return absl::InvalidArgumentError(str_cat(source_name, ": the file is empty"));
  }
  TextScanner scanner(bytes, source_name);
  msh::MeshBuilder builder;
  AFMESH_RETURN_IF_ERROR(read_msh(scanner, builder));
  return builder.finish(report);
}

absl::StatusOr<SizedGrid> parse_msh_sized_grid(std::string_view bytes,
                                               std::string_view source_name, ReadReport* report) {
  if (bytes.empty()) {
    return absl::InvalidArgumentError(str_cat(source_name, ": the file is empty"));
  }
  TextScanner scanner(bytes, source_name);
  msh::MeshBuilder builder;
  builder.want_node_sizes();
  AFMESH_RETURN_IF_ERROR(read_msh(scanner, builder));
  if (!builder.has_node_sizes()) {
    return absl::InvalidArgumentError(
        str_cat(source_name,
                ": no $NodeData section: a background grid needs a size at every node (a "
                "$NodeData view with one component, as gmsh saves a view with "
                "PostProcessing.SaveMesh = 1)"));
  }
  SizedGrid grid;
  grid.sizes = std::move(builder.node_sizes());
  grid.mesh = builder.finish(report);
  return grid;
}

}  // namespace afmesh
