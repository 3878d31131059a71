#include "bench/tetgen_files.h"

#include <cerrno>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <memory>

#include "absl/strings/str_cat.h"
#include "core/io/output_buffer.h"

namespace afmesh::bench {
namespace {

struct FileCloser {
  void operator()(std::FILE* file) const { std::fclose(file); }
};
using File = std::unique_ptr<std::FILE, FileCloser>;

enum class FacetStyle { kSmesh, kPoly };

// Part 1 of both formats: "<#points> 3 0 0" then "index x y z", 1-based.
void put_nodes(const Mesh& surface, OutputBuffer& out) {
  out.put("# nodes: count, dimension, attributes, boundary markers\n");
  out.put_int(static_cast<std::int64_t>(surface.points.size()));
  out.put(" 3 0 0\n");
  for (std::size_t p = 0; p < surface.points.size(); ++p) {
    out.put_int(static_cast<std::int64_t>(p) + 1);
    for (const double x : surface.points[p]) {
      out.put(' ');
      out.put_double(x);
    }
    out.put('\n');
  }
}

// The three 1-based corners of `t`, each after a space.
void put_corners(const Triangle& t, OutputBuffer& out) {
  for (const Index v : t) {
    out.put(' ');
    out.put_int(std::int64_t{v} + 1);
  }
}

// Part 2: one facet per triangle, with its tag as boundary marker.
void put_facets(const Mesh& surface, FacetStyle style, OutputBuffer& out) {
  out.put("# facets: count, boundary markers\n");
  out.put_int(static_cast<std::int64_t>(surface.triangles.size()));
  out.put(" 1\n");
  for (std::size_t t = 0; t < surface.triangles.size(); ++t) {
    const std::int64_t marker = t < surface.triangle_tags.size() ? surface.triangle_tags[t] : 0;
    if (style == FacetStyle::kSmesh) {
      out.put('3');
      put_corners(surface.triangles[t], out);
      out.put(' ');
      out.put_int(marker);
    } else {
      out.put("1 0 ");
      out.put_int(marker);
      out.put("\n3");
      put_corners(surface.triangles[t], out);
    }
    out.put('\n');
  }
}

absl::Status write_tetgen_file(const Mesh& surface, const std::string& path, FacetStyle style) {
  File file(std::fopen(path.c_str(), "wb"));
  if (!file) {
    return absl::InternalError(
        absl::StrCat("cannot create '", path, "': ", std::strerror(errno)));
  }
  OutputBuffer out(file.get(), path);
  put_nodes(surface, out);
  put_facets(surface, style, out);
  out.put("# holes\n0\n# regions\n0\n");
  absl::Status status = out.flush();
  file.reset();
  if (!status.ok()) std::remove(path.c_str());
  return status;
}

}  // namespace

absl::Status write_tetgen_smesh(const Mesh& surface, const std::string& path) {
  return write_tetgen_file(surface, path, FacetStyle::kSmesh);
}

absl::Status write_tetgen_poly(const Mesh& surface, const std::string& path) {
  return write_tetgen_file(surface, path, FacetStyle::kPoly);
}

}  // namespace afmesh::bench
