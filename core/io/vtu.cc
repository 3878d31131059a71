#include "core/io/vtu.h"

#include <cstdint>

#include "core/io/mesh_checks.h"
#include "core/io/return_if_error.h"
#include "core/io/string_util.h"

namespace afmesh {
namespace {

// VTK cell type codes, one per line.
constexpr std::string_view kVtkTriangleLine = "5\n";
constexpr std::string_view kVtkTetraLine = "10\n";

void open_array(std::string_view type, std::string_view name, int components, OutputBuffer& out) {
  out.put(str_cat("        <DataArray type=\"", type, "\" Name=\"", name, "\""));
  if (components > 1) out.put(str_cat(" NumberOfComponents=\"", components, "\""));
  out.put(" format=\"ascii\">\n");
}

void close_array(OutputBuffer& out) { out.put("        </DataArray>\n"); }

void write_points(const Mesh& mesh, OutputBuffer& out) {
  out.put("      <Points>\n");
  open_array("Float64", "Points", 3, out);
  for (const Point& p : mesh.points) {
    out.put_double(p[0]);
    out.put(' ');
    out.put_double(p[1]);
    out.put(' ');
    out.put_double(p[2]);
    out.put('\n');
  }
  close_array(out);
  out.put("      </Points>\n");
}

template <typename Element>
void write_connectivity(const std::vector<Element>& elements, OutputBuffer& out) {
  for (const Element& element : elements) {
    for (std::size_t i = 0; i < element.size(); ++i) {
      if (i > 0) out.put(' ');
      out.put_int(element[i]);
    }
    out.put('\n');
  }
}

void write_cells(const Mesh& mesh, OutputBuffer& out) {
  out.put("      <Cells>\n");
  open_array("Int32", "connectivity", 1, out);
  write_connectivity(mesh.triangles, out);
  write_connectivity(mesh.tets, out);
  close_array(out);
  open_array("Int64", "offsets", 1, out);
  std::int64_t offset = 0;
  for (std::size_t i = 0; i < mesh.triangles.size(); ++i) {
    offset += 3;
    out.put_int(offset);
    out.put('\n');
  }
  for (std::size_t i = 0; i < mesh.tets.size(); ++i) {
    offset += 4;
    out.put_int(offset);
    out.put('\n');
  }
  close_array(out);
  open_array("UInt8", "types", 1, out);
  for (std::size_t i = 0; i < mesh.triangles.size(); ++i) out.put(kVtkTriangleLine);
  for (std::size_t i = 0; i < mesh.tets.size(); ++i) out.put(kVtkTetraLine);
  close_array(out);
  out.put("      </Cells>\n");
}

void write_tags(const Mesh& mesh, OutputBuffer& out) {
  out.put("      <CellData Scalars=\"tag\">\n");
  open_array("Int32", "tag", 1, out);
  for (const Index tag : mesh.triangle_tags) {
    out.put_int(tag);
    out.put('\n');
  }
  for (const Index tag : mesh.tet_tags) {
    out.put_int(tag);
    out.put('\n');
  }
  close_array(out);
  out.put("      </CellData>\n");
}

}  // namespace

absl::Status write_vtu(const Mesh& mesh, OutputBuffer& out) {
  AFMESH_RETURN_IF_ERROR(check_mesh_for_writing(mesh));
  out.put(
      "<?xml version=\"1.0\"?>\n"
      "<VTKFile type=\"UnstructuredGrid\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
      "  <UnstructuredGrid>\n");
  out.put(str_cat("    <Piece NumberOfPoints=\"", mesh.points.size(), "\" NumberOfCells=\"",
                  mesh.triangles.size() + mesh.tets.size(), "\">\n"));
  write_points(mesh, out);
  write_cells(mesh, out);
  write_tags(mesh, out);
  out.put("    </Piece>\n  </UnstructuredGrid>\n</VTKFile>\n");
  return out.flush();
}

}  // namespace afmesh
