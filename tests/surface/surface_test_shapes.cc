#include "tests/surface/surface_test_shapes.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <numbers>
#include <utility>

#include "core/io/mesh_io.h"

namespace afmesh::testing {
namespace {

constexpr double kPi = std::numbers::pi;

// Appends the two triangles of quad (a, b, c, d), counter-clockwise seen from its front.
void add_quad(Mesh& mesh, Index a, Index b, Index c, Index d, Index tag = 0) {
  mesh.triangles.push_back({a, b, c});
  mesh.triangles.push_back({a, c, d});
  mesh.triangle_tags.push_back(tag);
  mesh.triangle_tags.push_back(tag);
}

void add_triangle(Mesh& mesh, Index a, Index b, Index c, Index tag = 0) {
  mesh.triangles.push_back({a, b, c});
  mesh.triangle_tags.push_back(tag);
}

// Appends `around` points on the circle of radius r around (cx, cy) at height z(x, y); returns
// the first one's index.
Index add_circle(Mesh& mesh, double cx, double cy, double r, int around,
                 const std::function<double(double, double)>& z) {
  const auto first = static_cast<Index>(mesh.points.size());
  for (int j = 0; j < around; ++j) {
    const double phi = 2.0 * kPi * j / around;
    const double x = cx + r * std::cos(phi), y = cy + r * std::sin(phi);
    mesh.points.push_back({x, y, z(x, y)});
  }
  return first;
}

}  // namespace

Mesh uv_sphere(const Point& centre, double radius, int around, int rings) {
  Mesh mesh;
  mesh.points.push_back({centre[0], centre[1], centre[2] - radius});  // south pole, 0
  for (int i = 1; i <= rings; ++i) {
    const double theta = kPi * i / (rings + 1) - kPi / 2;  // latitude
    const double r = radius * std::cos(theta);
    // The middle ring lies exactly at the centre's height.
    const double z = 2 * i == rings + 1 ? centre[2] : centre[2] + radius * std::sin(theta);
    add_circle(mesh, centre[0], centre[1], r, around, [z](double, double) { return z; });
  }
  const auto north = static_cast<Index>(mesh.points.size());
  mesh.points.push_back({centre[0], centre[1], centre[2] + radius});
  const auto ring = [&](int i, int j) { return 1 + (i - 1) * around + (j % around); };
  const auto tag_of = [&](int i) { return 2 * i <= rings ? Index{2} : Index{1}; };
  for (int j = 0; j < around; ++j) {
    add_triangle(mesh, 0, ring(1, j + 1), ring(1, j), 2);
    for (int i = 1; i < rings; ++i) {
      add_quad(mesh, ring(i, j), ring(i, j + 1), ring(i + 1, j + 1), ring(i + 1, j), tag_of(i));
    }
    add_triangle(mesh, north, ring(rings, j), ring(rings, j + 1), 1);
  }
  return mesh;
}

Mesh closed_cylinder(double radius, double height, int around, int layers) {
  Mesh mesh;
  for (int i = 0; i <= layers; ++i) {
    const double z = height * i / layers;
    add_circle(mesh, 0, 0, radius, around, [z](double, double) { return z; });
  }
  const auto at = [&](int i, int j) { return i * around + (j % around); };
  for (int i = 0; i < layers; ++i) {
    for (int j = 0; j < around; ++j)
      add_quad(mesh, at(i, j), at(i, j + 1), at(i + 1, j + 1), at(i + 1, j));
  }
  const auto bottom = static_cast<Index>(mesh.points.size());
  mesh.points.push_back({0, 0, 0});
  const auto top = static_cast<Index>(mesh.points.size());
  mesh.points.push_back({0, 0, height});
  for (int j = 0; j < around; ++j) {
    add_triangle(mesh, bottom, at(0, j + 1), at(0, j));
    add_triangle(mesh, top, at(layers, j), at(layers, j + 1));
  }
  return mesh;
}

Mesh terrain_disk(double cx, double cy, double radius, int rings, int around,
                  const std::function<double(double, double)>& height) {
  Mesh mesh;
  mesh.points.push_back({cx, cy, height(cx, cy)});
  for (int i = 1; i <= rings; ++i) add_circle(mesh, cx, cy, radius * i / rings, around, height);
  const auto ring = [&](int i, int j) { return 1 + (i - 1) * around + (j % around); };
  for (int j = 0; j < around; ++j) {
    add_triangle(mesh, 0, ring(1, j), ring(1, j + 1));
    for (int i = 1; i < rings; ++i)
      add_quad(mesh, ring(i, j), ring(i + 1, j), ring(i + 1, j + 1), ring(i, j + 1));
  }
  return mesh;
}

Mesh terrain_grid(double x0, double y0, double width, double depth, int n,
                  const std::function<double(double, double)>& height) {
  Mesh mesh;
  for (int j = 0; j <= n; ++j) {
    for (int i = 0; i <= n; ++i) {
      const double x = x0 + width * i / n, y = y0 + depth * j / n;
      mesh.points.push_back({x, y, height(x, y)});
    }
  }
  const auto at = [&](int i, int j) { return j * (n + 1) + i; };
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i)
      add_quad(mesh, at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1));
  }
  return mesh;
}

Mesh three_sheet_t(int n) {
  Mesh mesh;
  // Sheet s maps grid (u, v) in [0, 1]^2 to a point; all three share u = 0 along the y axis.
  const auto point = [](int sheet, double u, double v) -> Point {
    if (sheet == 0) return {-u, v, 0.0};
    if (sheet == 1) return {u, v, 0.0};
    return {0.0, v, u};
  };
  for (int sheet = 0; sheet < 3; ++sheet) {
    const auto first = static_cast<Index>(mesh.points.size());
    for (int j = 0; j <= n; ++j) {
      for (int i = 0; i <= n; ++i) {
        // The shared column u = 0 is stored once, by sheet 0.
        if (sheet > 0 && i == 0) continue;
        mesh.points.push_back(point(sheet, static_cast<double>(i) / n, static_cast<double>(j) / n));
      }
    }
    const auto at = [&](int i, int j) -> Index {
      if (i == 0) return j * (n + 1);  // sheet 0's column u = 0
      return sheet == 0 ? first + j * (n + 1) + i : first + j * n + (i - 1);
    };
    for (int j = 0; j < n; ++j) {
      for (int i = 0; i < n; ++i)
        add_quad(mesh, at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1));
    }
  }
  return mesh;
}

Mesh corpus_mesh(const std::string& name) {
  const std::filesystem::path path =
      std::filesystem::path(AFMESH_SOURCE_DIR) / ".." / "shared" / "corpus" / name;
  absl::StatusOr<Mesh> mesh = read_mesh(path.string());
  EXPECT_TRUE(mesh.ok()) << mesh.status();
  return mesh.ok() ? *std::move(mesh) : Mesh{};
}

SurfaceModel surface_model(const Mesh& mesh, const FeatureParams& params) {
  absl::StatusOr<DiscreteSurface> surface = DiscreteSurface::build(mesh);
  EXPECT_TRUE(surface.ok()) << surface.status();
  absl::StatusOr<SurfaceFeatures> features = find_surface_features(*surface, params);
  EXPECT_TRUE(features.ok()) << features.status();
  return {*std::move(surface), features.ok() ? *std::move(features) : SurfaceFeatures{}};
}

}  // namespace afmesh::testing
