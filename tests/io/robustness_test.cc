// Malformed input never crashes a reader and never yields a silently shortened mesh: every
// prefix of a valid file (a truncated download) and many randomly damaged copies are read,
// and each read either fails with INVALID_ARGUMENT naming the source or gives a whole mesh.
#include <algorithm>
#include <cstdio>
#include <functional>
#include <random>
#include <string>

#include "core/io/medit.h"
#include "core/io/msh.h"
#include "core/io/obj.h"
#include "core/io/stl.h"
#include "gtest/gtest.h"
#include "tests/io/io_test_support.h"

namespace afmesh {
namespace {

using io_test::tagged_box;
using io_test::tagged_box_surface;
using io_test::written;

using Parser = std::function<absl::StatusOr<Mesh>(std::string_view, std::string_view)>;

struct Format {
  std::string name;
  Parser parse;
  std::string bytes;
  // False for OBJ and multi-solid ascii STL: they have no counts and no end-of-file marker, so
  // a file cut at a line (OBJ) or solid (STL) boundary reads as a smaller, well-formed mesh.
  bool has_end_marker = true;
  std::size_t truncation_step = 1;  // try every step-th prefix length
};

std::string file_bytes(const std::string& path) {
  std::string bytes;
  std::FILE* file = std::fopen(path.c_str(), "rb");
  EXPECT_NE(file, nullptr) << path;
  if (file == nullptr) return bytes;
  char buffer[4096];
  while (const std::size_t got = std::fread(buffer, 1, sizeof buffer, file))
    bytes.append(buffer, got);
  std::fclose(file);
  return bytes;
}

std::vector<Format> formats() {
  const Mesh box = tagged_box();
  const Mesh surface = tagged_box_surface();
  auto stl = [](std::string_view b, std::string_view n) { return parse_stl(b, n); };
  return {
      {"box.msh", [](std::string_view b, std::string_view n) { return parse_msh(b, n); },
       written([&](OutputBuffer& out) { return write_msh(box, out); })},
      {"box.mesh", [](std::string_view b, std::string_view n) { return parse_medit(b, n); },
       written([&](OutputBuffer& out) { return write_medit(box, out); })},
      {"ascii.stl", stl,
       written([&](OutputBuffer& out) { return write_stl(surface, StlEncoding::kAscii, out); }),
       false},
      {"binary.stl", stl,
       written([&](OutputBuffer& out) { return write_stl(surface, StlEncoding::kBinary, out); })},
      {"box.obj", [](std::string_view b, std::string_view n) { return parse_obj(b, n); },
       written([&](OutputBuffer& out) { return write_obj(surface, out); }), false},
      {"gmsh_binary.msh", [](std::string_view b, std::string_view n) { return parse_msh(b, n); },
       file_bytes(io_test::data_file("gmsh_box_41_binary.msh")), true, 37},
  };
}

bool same_mesh(const Mesh& a, const Mesh& b) {
  return a.points == b.points && a.triangles == b.triangles && a.tets == b.tets &&
         a.triangle_tags == b.triangle_tags && a.tet_tags == b.tet_tags;
}

// True when `part` holds the first triangles of `whole`, corner for corner.
bool is_leading_part(const Mesh& part, const Mesh& whole) {
  const auto part_corners = io_test::triangle_corners(part);
  const auto whole_corners = io_test::triangle_corners(whole);
  return part.tets.empty() && part_corners.size() <= whole_corners.size() &&
         std::equal(part_corners.begin(), part_corners.end(), whole_corners.begin());
}

void expect_error_names_source(const absl::Status& status, const std::string& name) {
  EXPECT_EQ(status.code(), absl::StatusCode::kInvalidArgument) << status;
  EXPECT_EQ(std::string(status.message()).rfind(name, 0), 0u) << status;
}

TEST(Robustness, EveryTruncationFailsOrGivesTheWholeMesh) {
  for (const Format& format : formats()) {
    const absl::StatusOr<Mesh> whole = format.parse(format.bytes, format.name);
    ASSERT_TRUE(whole.ok()) << whole.status();
    for (std::size_t size = 0; size < format.bytes.size(); size += format.truncation_step) {
      const absl::StatusOr<Mesh> cut =
          format.parse(std::string_view(format.bytes).substr(0, size), format.name);
      if (!cut.ok()) {
        expect_error_names_source(cut.status(), format.name);
      } else if (format.has_end_marker) {
        EXPECT_TRUE(same_mesh(*cut, *whole)) << format.name << " cut to " << size << " bytes";
      } else {
        EXPECT_TRUE(is_leading_part(*cut, *whole)) << format.name << " cut to " << size;
      }
    }
  }
}

TEST(Robustness, DamagedBytesNeverCrash) {
  std::mt19937 random(12345);
  const std::string noise = " \n0123456789-+.eE$/#abcxyz\x01\xff";
  for (const Format& format : formats()) {
    for (int trial = 0; trial < 2000; ++trial) {
      std::string damaged = format.bytes;
      const int changes = 1 + static_cast<int>(random() % 4);
      for (int c = 0; c < changes; ++c) {
        damaged[random() % damaged.size()] = noise[random() % noise.size()];
      }
      const absl::StatusOr<Mesh> read = format.parse(damaged, format.name);
      if (!read.ok()) {
        expect_error_names_source(read.status(), format.name);
      } else {
        EXPECT_EQ(read->triangle_tags.size(), read->triangles.size());
        EXPECT_EQ(read->tet_tags.size(), read->tets.size());
        for (const Triangle& t : read->triangles) {
          for (const Index v : t)
            ASSERT_TRUE(v >= 0 && v < static_cast<Index>(read->points.size()));
        }
        for (const Tet& t : read->tets) {
          for (const Index v : t)
            ASSERT_TRUE(v >= 0 && v < static_cast<Index>(read->points.size()));
        }
      }
    }
  }
}

}  // namespace
}  // namespace afmesh
