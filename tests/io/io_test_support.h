// Shared pieces of the io tests: sample meshes with tags, exact comparisons, in-memory writing
// and a temporary directory.
#pragma once

#include <array>
#include <functional>
#include <string>
#include <vector>

#include "absl/status/status.h"
#include "core/io/output_buffer.h"
#include "core/mesh/mesh.h"

namespace afmesh::io_test {

// A box with awkward coordinates (0.1, 1/3, 2.5e-3, ... : not exact in binary) split into 6
// positive tetrahedra (tags 7, 8, 7, 8, 7, 8) and its 12 outward boundary triangles, tagged by
// box face 1..6 and ordered so that equal tags are not adjacent (1 2 3 4 5 6 1 2 3 4 5 6).
// 8 points, 12 triangles, 6 tets.
Mesh tagged_box();

// tagged_box() without its tetrahedra.
Mesh tagged_box_surface();

// `mesh` with every coordinate rounded to float (what binary STL stores).
Mesh rounded_to_float(Mesh mesh);

// The corner coordinates of each triangle (M×3×3), for comparing meshes whose point order may
// differ (STL renumbers points by first use).
std::vector<std::array<Point, 3>> triangle_corners(const Mesh& mesh);

// Checks points bit for bit (so -0.0 differs from 0.0), then connectivity and tags.
void expect_same_mesh(const Mesh& actual, const Mesh& expected);

// True when the two doubles have the same bits.
bool same_bits(double a, double b);

// The bytes `write` produces into an in-memory OutputBuffer; the test fails if it returns an
// error.
std::string written(const std::function<absl::Status(OutputBuffer&)>& write);

// A fresh directory under the test temp dir, removed with its contents on destruction.
class TempDir {
 public:
  TempDir();
  ~TempDir();
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;

  const std::string& path() const { return path_; }
  // `path()/name`.
  std::string file(const std::string& name) const { return path_ + "/" + name; }

 private:
  std::string path_;
};

// Writes `bytes` to the file `path` (test setup).
void write_file(const std::string& path, const std::string& bytes);

// Absolute path of `name` in tests/data.
std::string data_file(const std::string& name);

}  // namespace afmesh::io_test
