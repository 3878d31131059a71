#include "core/io/stl.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>

#include "core/geometry/vec.h"
#include "core/io/exact_point_merger.h"
#include "core/io/little_endian.h"
#include "core/io/mesh_checks.h"
#include "core/io/return_if_error.h"
#include "core/io/string_util.h"
#include "core/io/text_scanner.h"

namespace afmesh {
namespace {

constexpr std::size_t kBinaryHeaderBytes = 84;  // 80-byte header + uint32 triangle count
constexpr std::size_t kBinaryFacetBytes = 50;   // normal, 3 corners (12 floats), uint16
constexpr std::uint64_t kMaxTriangles = std::numeric_limits<Index>::max() / 3;

// True when `bytes` starts (after blanks) with "solid" and its first kilobyte is text: no
// control bytes other than whitespace. Binary data almost always holds a zero byte there (the
// high byte of the triangle count at offset 83, to begin with).
bool looks_like_ascii_stl(std::string_view bytes) {
  const std::string_view head = bytes.substr(0, 1024);
  for (const char c : head) {
    const auto u = static_cast<unsigned char>(c);
    if ((u < 0x20 && c != '\n' && c != '\r' && c != '\t' && c != '\f' && c != '\v') || u == 0x7f) {
      return false;
    }
  }
  const std::size_t start = head.find_first_not_of(" \t\r\n\f\v");
  return start != std::string_view::npos && starts_with_ignore_case(head.substr(start), "solid");
}

// Notes how many corners merged into how many points, and how many triangles came out with a
// repeated corner (kept as they are: the file describes them so).
void note_merging(const Mesh& mesh, ReadReport* report) {
  if (report == nullptr || mesh.triangles.empty()) return;
  add_note(report, str_cat("merged ", 3 * mesh.triangles.size(), " STL triangle corners into ",
                           mesh.points.size(), " points (identical coordinates only)"));
  const auto degenerate =
      std::count_if(mesh.triangles.begin(), mesh.triangles.end(),
                    [](const Triangle& t) { return t[0] == t[1] || t[1] == t[2] || t[2] == t[0]; });
  if (degenerate > 0) {
    add_note(report, str_cat(degenerate, " triangles have two identical corners"));
  }
}

// Binary STL: `bytes` is exactly 84 + 50 n bytes long (checked by the caller).
absl::StatusOr<Mesh> parse_binary_stl(std::string_view bytes, std::string_view source_name,
                                      std::uint32_t num_triangles) {
  if (num_triangles > kMaxTriangles) {
    return binary_error(source_name, 80,
                        str_cat("binary STL declares ", num_triangles, " triangles; at most ",
                                kMaxTriangles, " are supported"));
  }
  Mesh mesh;
  mesh.triangles.resize(num_triangles);
  mesh.triangle_tags.assign(num_triangles, 0);
  ExactPointMerger merger(mesh.points, num_triangles / 2 + 4);
  for (std::uint32_t t = 0; t < num_triangles; ++t) {
    const std::size_t facet = kBinaryHeaderBytes + std::size_t{t} * kBinaryFacetBytes;
    for (int corner = 0; corner < 3; ++corner) {
      const std::size_t offset = facet + 12 + 12 * corner;  // after the normal's 3 floats
      double xyz[3];
      for (int axis = 0; axis < 3; ++axis) {
        xyz[axis] = load_little_endian<float>(bytes.data() + offset + 4 * axis);
        if (!std::isfinite(xyz[axis])) {
          return binary_error(source_name, offset + 4 * axis,
                              str_cat("expected a finite coordinate for corner ", corner + 1,
                                      " of triangle ", t + 1, ", found ", xyz[axis]));
        }
      }
      mesh.triangles[t][corner] = merger.insert(xyz[0], xyz[1], xyz[2]);
    }
  }
  return mesh;
}

// One `facet normal ... endfacet` block; the keyword "facet" has been read.
absl::Status parse_ascii_facet(TextScanner& scanner, ExactPointMerger& merger, Triangle& triangle) {
  AFMESH_RETURN_IF_ERROR(scanner.expect_keyword("normal"));
  for (int axis = 0; axis < 3; ++axis) {
    double ignored = 0;
    AFMESH_RETURN_IF_ERROR(scanner.read_any_double(ignored, "a facet normal component"));
  }
  AFMESH_RETURN_IF_ERROR(scanner.expect_keyword("outer"));
  AFMESH_RETURN_IF_ERROR(scanner.expect_keyword("loop"));
  for (int corner = 0; corner < 3; ++corner) {
    AFMESH_RETURN_IF_ERROR(scanner.expect_keyword("vertex"));
    double xyz[3];
    for (double& coordinate : xyz) {
      AFMESH_RETURN_IF_ERROR(scanner.read_double(coordinate, "a vertex coordinate"));
    }
    triangle[corner] = merger.insert(xyz[0], xyz[1], xyz[2]);
  }
  AFMESH_RETURN_IF_ERROR(scanner.expect_keyword("endloop"));
  return scanner.expect_keyword("endfacet");
}

// Ascii STL: one or more `solid [name] ... endsolid [name]` blocks.
absl::StatusOr<Mesh> parse_ascii_stl(std::string_view bytes, std::string_view source_name) {
  TextScanner scanner(bytes, source_name);
  Mesh mesh;
  // About 250 bytes per facet in typical files; a guess used only to size the tables.
  ExactPointMerger merger(mesh.points, bytes.size() / 500 + 4);
  Index solid = 0;
  while (!scanner.at_end()) {
    AFMESH_RETURN_IF_ERROR(scanner.expect_keyword("solid"));
    scanner.rest_of_line();  // the solid's name
    ++solid;
    for (;;) {
      const std::string_view token = scanner.next_token();
      if (equals_ignore_case(token, "endsolid")) {
        scanner.rest_of_line();
        break;
      }
      if (!equals_ignore_case(token, "facet")) {
        return scanner.unexpected("'facet' or 'endsolid'", token);
      }
      if (mesh.triangles.size() >= kMaxTriangles) {
        return scanner.error(str_cat("more than ", kMaxTriangles, " triangles"));
      }
      Triangle triangle;
      AFMESH_RETURN_IF_ERROR(parse_ascii_facet(scanner, merger, triangle));
      mesh.triangles.push_back(triangle);
      mesh.triangle_tags.push_back(solid);
    }
  }
  return mesh;
}

// Chooses the encoding (see stl.h) and explains why a file is neither.
absl::StatusOr<Mesh> parse_stl_bytes(std::string_view bytes, std::string_view source_name) {
  if (bytes.empty()) {
    return absl::InvalidArgumentError(str_cat(source_name, ": the file is empty"));
  }
  const bool ascii = looks_like_ascii_stl(bytes);
  if (bytes.size() < kBinaryHeaderBytes) {
    if (ascii) return parse_ascii_stl(bytes, source_name);
    return binary_error(source_name, 0,
                        str_cat("not an STL file: ascii STL starts with 'solid', and "
                                "binary STL needs an 84-byte header, but the file has ",
                                bytes.size(), " bytes"));
  }
  const std::uint32_t count = load_little_endian<std::uint32_t>(bytes.data() + 80);
  const std::uint64_t binary_size = kBinaryHeaderBytes + std::uint64_t{count} * kBinaryFacetBytes;
  if (!ascii && binary_size == bytes.size()) return parse_binary_stl(bytes, source_name, count);
  if (ascii) return parse_ascii_stl(bytes, source_name);
  return binary_error(
      source_name, 80,
      str_cat("binary STL header declares ", count, " triangles, which take ", binary_size,
              " bytes, but the file has ", bytes.size(), " bytes (truncated or not an STL file)"));
}

// Unit normal of the triangle (a, b, c) in float, or zero when it is degenerate.
std::array<float, 3> float_unit_normal(const Point& a, const Point& b, const Point& c) {
  const Point n = unit_normal(a, b, c);
  return {static_cast<float>(n[0]), static_cast<float>(n[1]), static_cast<float>(n[2])};
}

void write_binary_stl(const Mesh& mesh, OutputBuffer& out) {
  std::string header = "afmesh binary STL";
  header.resize(80, ' ');
  out.put(header);
  out.put_little_endian(static_cast<std::uint32_t>(mesh.triangles.size()));
  for (const Triangle& t : mesh.triangles) {
    const Point& a = mesh.points[t[0]];
    const Point& b = mesh.points[t[1]];
    const Point& c = mesh.points[t[2]];
    for (const float component : float_unit_normal(a, b, c)) out.put_little_endian(component);
    for (const Point* p : {&a, &b, &c}) {
      for (const double coordinate : *p) out.put_little_endian(static_cast<float>(coordinate));
    }
    out.put_little_endian(std::uint16_t{0});
  }
}

void write_ascii_facet(const Mesh& mesh, const Triangle& t, OutputBuffer& out) {
  const std::array<float, 3> normal =
      float_unit_normal(mesh.points[t[0]], mesh.points[t[1]], mesh.points[t[2]]);
  out.put("  facet normal ");
  for (int axis = 0; axis < 3; ++axis) {
    if (axis > 0) out.put(' ');
    out.put_float(normal[axis]);
  }
  out.put("\n    outer loop\n");
  for (const Index v : t) {
    out.put("      vertex ");
    const Point& p = mesh.points[v];
    out.put_double(p[0]);
    out.put(' ');
    out.put_double(p[1]);
    out.put(' ');
    out.put_double(p[2]);
    out.put('\n');
  }
  out.put("    endloop\n  endfacet\n");
}

void write_ascii_stl(const Mesh& mesh, OutputBuffer& out) {
  if (mesh.triangles.empty()) {
    out.put("solid empty\nendsolid empty\n");
    return;
  }
  std::size_t run_start = 0;
  while (run_start < mesh.triangles.size()) {
    const Index tag = mesh.triangle_tags[run_start];
    std::size_t run_end = run_start;
    while (run_end < mesh.triangles.size() && mesh.triangle_tags[run_end] == tag) ++run_end;
    const std::string name = str_cat("tag_", tag);
    out.put("solid ");
    out.put(name);
    out.put('\n');
    for (std::size_t i = run_start; i < run_end; ++i)
      write_ascii_facet(mesh, mesh.triangles[i], out);
    out.put("endsolid ");
    out.put(name);
    out.put('\n');
    run_start = run_end;
  }
}

}  // namespace

absl::StatusOr<Mesh> parse_stl(std::string_view bytes, std::string_view source_name,
                               ReadReport* report) {
  absl::StatusOr<Mesh> mesh = parse_stl_bytes(bytes, source_name);
  if (mesh.ok()) note_merging(*mesh, report);
  return mesh;
}

absl::Status write_stl(const Mesh& mesh, StlEncoding encoding, OutputBuffer& out) {
  AFMESH_RETURN_IF_ERROR(check_mesh_for_writing(mesh));
  AFMESH_RETURN_IF_ERROR(check_triangles_only(mesh, "STL"));
  if (encoding == StlEncoding::kBinary) {
    write_binary_stl(mesh, out);
  } else {
    write_ascii_stl(mesh, out);
  }
  return out.flush();
}

}  // namespace afmesh
