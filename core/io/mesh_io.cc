#include "core/io/mesh_io.h"

#include <cerrno>
#include <cstdio>
#include <memory>

#include "core/io/file_bytes.h"
#include "core/io/medit.h"
#include "core/io/mesh_checks.h"
#include "core/io/msh.h"
#include "core/io/obj.h"
#include "core/io/output_buffer.h"
#include "core/io/return_if_error.h"
#include "core/io/stl.h"
#include "core/io/string_util.h"
#include "core/io/vtu.h"

namespace afmesh {
namespace {

struct FileCloser {
  void operator()(std::FILE* file) const { std::fclose(file); }
};

// The status `status` with "cannot write '<path>': " in front of its message.
absl::Status with_write_context(const absl::Status& status, const std::string& path) {
  return absl::Status(status.code(), str_cat("cannot write '", path, "': ", status.message()));
}

// What the format can hold, checked before the file is created.
absl::Status check_format_can_hold(const Mesh& mesh, MeshFormat format) {
  AFMESH_RETURN_IF_ERROR(check_mesh_for_writing(mesh));
  if (format == MeshFormat::kStl) return check_triangles_only(mesh, "STL");
  if (format == MeshFormat::kObj) return check_triangles_only(mesh, "OBJ");
  return absl::OkStatus();
}

absl::Status write_format(const Mesh& mesh, MeshFormat format, const WriteOptions& options,
                          OutputBuffer& out) {
  switch (format) {
    case MeshFormat::kStl:
      return write_stl(mesh, options.binary_stl ? StlEncoding::kBinary : StlEncoding::kAscii, out);
    case MeshFormat::kObj:
      return write_obj(mesh, out);
    case MeshFormat::kMsh:
      return write_msh(mesh, out);
    case MeshFormat::kMedit:
      return write_medit(mesh, out);
    case MeshFormat::kVtu:
      return write_vtu(mesh, out);
  }
  return absl::InternalError("unknown mesh format");
}

}  // namespace

absl::StatusOr<MeshFormat> format_from_path(std::string_view path) {
  const std::size_t slash = path.find_last_of('/');
  const std::string_view name = slash == std::string_view::npos ? path : path.substr(slash + 1);
  const std::size_t dot = name.find_last_of('.');
  const std::string extension =
      dot == std::string_view::npos ? std::string() : ascii_lowercase(name.substr(dot));
  if (extension == ".stl") return MeshFormat::kStl;
  if (extension == ".obj") return MeshFormat::kObj;
  if (extension == ".msh") return MeshFormat::kMsh;
  if (extension == ".mesh") return MeshFormat::kMedit;
  if (extension == ".vtu") return MeshFormat::kVtu;
  return absl::InvalidArgumentError(
      str_cat("cannot tell the mesh format of '", path,
              "' from its extension: expected .stl, .obj, .msh, .mesh or .vtu"));
}

absl::StatusOr<Mesh> read_mesh(const std::string& path, ReadReport* report) {
  absl::StatusOr<MeshFormat> format = format_from_path(path);
  if (!format.ok()) return format.status();
  if (*format == MeshFormat::kVtu) {
    return absl::UnimplementedError(
        str_cat("cannot read '", path,
                "': reading .vtu is not supported (afmesh writes .vtu for viewing; "
                "convert to .msh or .mesh to read)"));
  }
  absl::StatusOr<std::string> bytes = read_file_bytes(path);
  if (!bytes.ok()) return bytes.status();
  switch (*format) {
    case MeshFormat::kStl:
      return parse_stl(*bytes, path, report);
    case MeshFormat::kObj:
      return parse_obj(*bytes, path, report);
    case MeshFormat::kMsh:
      return parse_msh(*bytes, path, report);
    case MeshFormat::kMedit:
      return parse_medit(*bytes, path, report);
    case MeshFormat::kVtu:
      break;
  }
  return absl::InternalError("unknown mesh format");
}

absl::Status write_mesh(const Mesh& mesh, const std::string& path, const WriteOptions& options) {
  absl::StatusOr<MeshFormat> format = format_from_path(path);
  if (!format.ok()) return format.status();
  if (absl::Status s = check_format_can_hold(mesh, *format); !s.ok()) {
    return with_write_context(s, path);
  }
  std::unique_ptr<std::FILE, FileCloser> file(std::fopen(path.c_str(), "wb"));
  if (file == nullptr) return file_error("create", path, errno);
  OutputBuffer out(file.get(), path);
  absl::Status status = write_format(mesh, *format, options, out);
  if (std::fclose(file.release()) != 0 && status.ok()) status = file_error("write", path, errno);
  if (!status.ok()) {
    std::remove(path.c_str());
    return status.message().find(path) == std::string_view::npos ? with_write_context(status, path)
                                                                 : status;
  }
  return absl::OkStatus();
}

}  // namespace afmesh
