#include "tests/io/io_test_support.h"

#include <stdlib.h>

#include <algorithm>
#include <bit>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <map>

#include "gtest/gtest.h"

namespace afmesh::io_test {
namespace {

double orientation(const Mesh& mesh, const Tet& t) {
  const Point& a = mesh.points[t[0]];
  const Point& b = mesh.points[t[1]];
  const Point& c = mesh.points[t[2]];
  const Point& d = mesh.points[t[3]];
  const double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
  const double v[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
  const double w[3] = {d[0] - a[0], d[1] - a[1], d[2] - a[2]};
  return u[0] * (v[1] * w[2] - v[2] * w[1]) - u[1] * (v[0] * w[2] - v[2] * w[0]) +
         u[2] * (v[0] * w[1] - v[1] * w[0]);
}

// Faces of the positive tet (a, b, c, d) with outward normals.
std::array<Triangle, 4> outward_faces(const Tet& t) {
  return {{{t[0], t[2], t[1]}, {t[0], t[1], t[3]}, {t[0], t[3], t[2]}, {t[1], t[2], t[3]}}};
}

// Box face 1..6 of a boundary triangle of the unit-cube corner numbering (bit 0: x, 1: y, 2: z).
Index box_face(const Triangle& t) {
  for (int axis = 0; axis < 3; ++axis) {
    const int bit = 1 << axis;
    if ((t[0] & bit) == (t[1] & bit) && (t[1] & bit) == (t[2] & bit)) {
      return 1 + 2 * axis + ((t[0] & bit) ? 1 : 0);
    }
  }
  return 0;
}

}  // namespace

Mesh tagged_box() {
  Mesh mesh;
  const Point origin = {0.1, -1.0 / 3.0, 2.5e-3};
  const Point size = {1.0 / 3.0, 0.7, 1e5 / 7.0};
  for (int corner = 0; corner < 8; ++corner) {
    mesh.points.push_back({origin[0] + ((corner & 1) ? size[0] : 0.0),
                           origin[1] + ((corner & 2) ? size[1] : 0.0),
                           origin[2] + ((corner & 4) ? size[2] : 0.0)});
  }
  // Kuhn triangulation: one tet per path 0 -> a -> a+b -> 7 along the axes.
  const int axes[6][2] = {{1, 2}, {1, 4}, {2, 1}, {2, 4}, {4, 1}, {4, 2}};
  for (int k = 0; k < 6; ++k) {
    Tet t = {0, axes[k][0], axes[k][0] | axes[k][1], 7};
    if (orientation(mesh, t) < 0) std::swap(t[2], t[3]);
    mesh.tets.push_back(t);
    mesh.tet_tags.push_back(k % 2 == 0 ? 7 : 8);
  }
  std::map<std::array<Index, 3>, std::pair<Triangle, int>> faces;
  for (const Tet& t : mesh.tets) {
    for (const Triangle& f : outward_faces(t)) {
      std::array<Index, 3> key = f;
      std::sort(key.begin(), key.end());
      auto& [face, count] = faces[key];
      face = f;
      ++count;
    }
  }
  std::vector<std::vector<Triangle>> by_face(7);
  for (const auto& [key, face_count] : faces) {
    if (face_count.second == 1) by_face[box_face(face_count.first)].push_back(face_count.first);
  }
  for (int round = 0; round < 2; ++round) {
    for (Index tag = 1; tag <= 6; ++tag) {
      mesh.triangles.push_back(by_face[tag][round]);
      mesh.triangle_tags.push_back(tag);
    }
  }
  return mesh;
}

Mesh tagged_box_surface() {
  Mesh mesh = tagged_box();
  mesh.tets.clear();
  mesh.tet_tags.clear();
  return mesh;
}

Mesh rounded_to_float(Mesh mesh) {
  for (Point& p : mesh.points) {
    for (double& c : p) c = static_cast<float>(c);
  }
  return mesh;
}

std::vector<std::array<Point, 3>> triangle_corners(const Mesh& mesh) {
  std::vector<std::array<Point, 3>> corners;
  for (const Triangle& t : mesh.triangles) {
    corners.push_back({mesh.points[t[0]], mesh.points[t[1]], mesh.points[t[2]]});
  }
  return corners;
}

bool same_bits(double a, double b) {
  return std::bit_cast<std::uint64_t>(a) == std::bit_cast<std::uint64_t>(b);
}

void expect_same_mesh(const Mesh& actual, const Mesh& expected) {
  ASSERT_EQ(actual.points.size(), expected.points.size());
  for (std::size_t i = 0; i < expected.points.size(); ++i) {
    for (int axis = 0; axis < 3; ++axis) {
      EXPECT_TRUE(same_bits(actual.points[i][axis], expected.points[i][axis]))
          << "point " << i << " axis " << axis << ": " << actual.points[i][axis] << " vs "
          << expected.points[i][axis];
    }
  }
  EXPECT_EQ(actual.triangles, expected.triangles);
  EXPECT_EQ(actual.triangle_tags, expected.triangle_tags);
  EXPECT_EQ(actual.tets, expected.tets);
  EXPECT_EQ(actual.tet_tags, expected.tet_tags);
}

std::string written(const std::function<absl::Status(OutputBuffer&)>& write) {
  std::string bytes;
  OutputBuffer out(&bytes);
  const absl::Status status = write(out);
  EXPECT_TRUE(status.ok()) << status;
  return bytes;
}

TempDir::TempDir() {
  std::string pattern = ::testing::TempDir() + "afmesh_io_XXXXXX";
  const char* made = mkdtemp(pattern.data());
  EXPECT_NE(made, nullptr) << "cannot create a directory from " << pattern;
  path_ = pattern;
}

TempDir::~TempDir() {
  std::error_code ignored;
  std::filesystem::remove_all(path_, ignored);
}

void write_file(const std::string& path, const std::string& bytes) {
  std::ofstream file(path, std::ios::binary);
  file.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  ASSERT_TRUE(file.good()) << "cannot write " << path;
}

std::string data_file(const std::string& name) {
  return std::string(AFMESH_SOURCE_DIR) + "/tests/data/" + name;
}

}  // namespace afmesh::io_test
