#include "core/io/sized_grid.h"

#include <cerrno>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <memory>
#include <system_error>

#include "core/io/file_bytes.h"
#include "core/io/medit.h"
#include "core/io/mesh_checks.h"
#include "core/io/msh.h"
#include "core/io/output_buffer.h"
#include "core/io/return_if_error.h"
#include "core/io/string_util.h"

namespace afmesh {
namespace {

enum class GridFormat { kMsh, kMedit };

struct FileCloser {
  void operator()(std::FILE* file) const { std::fclose(file); }
};

std::string lowercase_extension(const std::string& path) {
  return ascii_lowercase(std::filesystem::path(path).extension().string());
}

absl::StatusOr<GridFormat> grid_format(const std::string& path) {
  const std::string extension = lowercase_extension(path);
  if (extension == ".msh") return GridFormat::kMsh;
  if (extension == ".mesh") return GridFormat::kMedit;
  const std::string hint =
      extension == ".sol" || extension == ".solb"
          ? std::string(" (name the .mesh file; its sizes are read from the .sol beside it)")
          : std::string();
  return absl::InvalidArgumentError(
      str_cat("cannot tell the background grid format of '", path,
              "' from its extension: expected .msh (gmsh, sizes in a $NodeData view) or .mesh "
              "(Medit, sizes in the .sol of the same name beside it)",
              hint));
}

bool file_exists(const std::string& path) {
  std::error_code ignored;
  return std::filesystem::exists(path, ignored);
}

// The sizes of the Medit grid `mesh_path` with `num_vertices` vertices, from its .sol.
absl::StatusOr<std::vector<double>> read_medit_sizes(const std::string& mesh_path,
                                                     std::size_t num_vertices) {
  const std::string sol_path = medit_sol_path(mesh_path);
  if (!file_exists(sol_path)) {
    const std::string solb_path = sol_path + "b";
    if (file_exists(solb_path)) {
      return absl::InvalidArgumentError(str_cat(
          solb_path, ": binary Medit solutions (.solb) are not read; save the sizes as ascii '",
          sol_path, "' (SolAtVertices, one scalar per vertex)"));
    }
    return absl::NotFoundError(str_cat("'", mesh_path, "' needs its sizes in '", sol_path,
                                       "' (Medit SolAtVertices, one scalar per vertex), which "
                                       "does not exist"));
  }
  absl::StatusOr<std::string> text = read_file_bytes(sol_path);
  if (!text.ok()) return text.status();
  return parse_medit_sol(*text, sol_path, num_vertices);
}

absl::StatusOr<SizedGrid> read_grid_file(const std::string& path, GridFormat format,
                                         ReadReport* report) {
  absl::StatusOr<std::string> bytes = read_file_bytes(path);
  if (!bytes.ok()) return bytes.status();
  if (format == GridFormat::kMsh) return parse_msh_sized_grid(*bytes, path, report);
  SizedGrid grid;
  absl::StatusOr<Mesh> mesh = parse_medit(*bytes, path, report);
  if (!mesh.ok()) return mesh.status();
  grid.mesh = *std::move(mesh);
  absl::StatusOr<std::vector<double>> sizes = read_medit_sizes(path, grid.mesh.points.size());
  if (!sizes.ok()) return sizes.status();
  grid.sizes = *std::move(sizes);
  return grid;
}

// Writes one file through `write`, removing it when writing fails.
absl::Status write_file(const std::string& path,
                        const std::function<absl::Status(OutputBuffer&)>& write) {
  std::unique_ptr<std::FILE, FileCloser> file(std::fopen(path.c_str(), "wb"));
  if (file == nullptr) return file_error("create", path, errno);
  OutputBuffer out(file.get(), path);
  absl::Status status = write(out);
  if (std::fclose(file.release()) != 0 && status.ok()) status = file_error("write", path, errno);
  if (!status.ok()) std::remove(path.c_str());
  return status;
}

}  // namespace

std::string medit_sol_path(const std::string& mesh_path) {
  return std::filesystem::path(mesh_path).replace_extension(".sol").string();
}

absl::StatusOr<SizedGrid> read_sized_grid(const std::string& path, ReadReport* report) {
  absl::StatusOr<GridFormat> format = grid_format(path);
  if (!format.ok()) return format.status();
  absl::StatusOr<SizedGrid> grid = read_grid_file(path, *format, report);
  if (!grid.ok()) return grid.status();
  if (grid->mesh.tets.empty()) {
    return absl::InvalidArgumentError(
        str_cat(path, ": no tetrahedra: a background grid is a tetrahedral mesh"));
  }
  if (!grid->mesh.triangles.empty()) {
    add_note(report, str_cat("ignored the ", grid->mesh.triangles.size(), " triangles of '", path,
                             "' (a background grid uses its tetrahedra)"));
    grid->mesh.triangles.clear();
    grid->mesh.triangle_tags.clear();
  }
  return grid;
}

absl::Status write_sized_grid(const Mesh& mesh, std::span<const double> sizes,
                              const std::string& path) {
  absl::StatusOr<GridFormat> format = grid_format(path);
  if (!format.ok()) return format.status();
  AFMESH_RETURN_IF_ERROR(check_mesh_for_writing(mesh));
  AFMESH_RETURN_IF_ERROR(check_sizes_for_writing(sizes, mesh.points.size()));
  if (*format == GridFormat::kMsh) {
    return write_file(path,
                      [&](OutputBuffer& out) { return write_msh_sized_grid(mesh, sizes, out); });
  }
  AFMESH_RETURN_IF_ERROR(
      write_file(path, [&](OutputBuffer& out) { return write_medit(mesh, out); }));
  const absl::Status sol = write_file(
      medit_sol_path(path), [&](OutputBuffer& out) { return write_medit_sol(sizes, out); });
  if (!sol.ok()) std::remove(path.c_str());
  return sol;
}

}  // namespace afmesh
