#include "tests/quality/test_meshes.h"

#include <algorithm>
#include <cstdint>
#include <map>
#include <numeric>
#include <utility>

#include "core/quality/mesh_topology.h"

namespace afmesh::testing {
namespace {

// det[b-a, c-a, d-a]: exact for the small integer and half-integer coordinates used here.
double orientation(const std::vector<Point>& p, const Tet& t) {
  double u[3], v[3], w[3];
  for (int k = 0; k < 3; ++k) {
    u[k] = p[t[1]][k] - p[t[0]][k];
    v[k] = p[t[2]][k] - p[t[0]][k];
    w[k] = p[t[3]][k] - p[t[0]][k];
  }
  return u[0] * (v[1] * w[2] - v[2] * w[1]) - u[1] * (v[0] * w[2] - v[2] * w[0]) +
         u[2] * (v[0] * w[1] - v[1] * w[0]);
}

}  // namespace

std::vector<Point> unit_cube_points() {
  std::vector<Point> points;
  for (int i = 0; i < 8; ++i) {
    points.push_back({static_cast<double>(i & 1), static_cast<double>((i >> 1) & 1),
                      static_cast<double>((i >> 2) & 1)});
  }
  return points;
}

Mesh tet_mesh(std::vector<Point> points, std::vector<Tet> tets) {
  Mesh m;
  m.points = std::move(points);
  for (Tet t : tets) {
    if (orientation(m.points, t) < 0) std::swap(t[2], t[3]);
    m.tets.push_back(t);
  }
  m.tet_tags.assign(m.tets.size(), 0);
  return m;
}

Mesh surface_mesh(std::vector<Point> points, std::vector<Triangle> triangles) {
  Mesh m;
  m.points = std::move(points);
  m.triangles = std::move(triangles);
  m.triangle_tags.assign(m.triangles.size(), 0);
  return m;
}

Mesh five_tet_cube() {
  return tet_mesh(unit_cube_points(),
                  {{0, 1, 2, 4}, {3, 1, 2, 7}, {5, 1, 4, 7}, {6, 2, 4, 7}, {1, 2, 4, 7}});
}

Mesh five_tet_cube_boundary() {
  return surface_mesh(unit_cube_points(), {{0, 2, 1},
                                           {1, 2, 3},  // z = 0
                                           {0, 1, 4},
                                           {1, 5, 4},  // y = 0
                                           {0, 4, 2},
                                           {2, 4, 6},  // x = 0
                                           {4, 5, 7},
                                           {4, 7, 6},  // z = 1
                                           {2, 6, 7},
                                           {2, 7, 3},  // y = 1
                                           {1, 3, 7},
                                           {1, 7, 5}});  // x = 1
}

Mesh six_tet_cube() {
  return tet_mesh(unit_cube_points(), {{0, 1, 3, 7},
                                       {0, 3, 2, 7},
                                       {0, 2, 6, 7},
                                       {0, 6, 4, 7},
                                       {0, 4, 5, 7},
                                       {0, 5, 1, 7}});
}

Mesh six_tet_cube_boundary() {
  return surface_mesh(unit_cube_points(), {{0, 3, 1},
                                           {0, 2, 3},  // z = 0
                                           {0, 1, 5},
                                           {0, 5, 4},  // y = 0
                                           {0, 6, 2},
                                           {0, 4, 6},  // x = 0
                                           {4, 5, 7},
                                           {4, 7, 6},  // z = 1
                                           {2, 6, 7},
                                           {2, 7, 3},  // y = 1
                                           {1, 3, 7},
                                           {1, 7, 5}});  // x = 1
}

Mesh two_tet_mesh() {
  return tet_mesh({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0.25, 0.25, 1}, {0.25, 0.25, -1}},
                  {{0, 1, 2, 3}, {0, 2, 1, 4}});
}

Mesh octahedron() {
  return surface_mesh({{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}},
                      {{0, 2, 4},
                       {2, 1, 4},
                       {1, 3, 4},
                       {3, 0, 4},
                       {2, 0, 5},
                       {1, 2, 5},
                       {3, 1, 5},
                       {0, 3, 5}});
}

Mesh merge(const Mesh& a, const Mesh& b) {
  Mesh m = a;
  const Index shift = static_cast<Index>(a.points.size());
  m.points.insert(m.points.end(), b.points.begin(), b.points.end());
  for (Triangle t : b.triangles) {
    for (Index& v : t) v += shift;
    m.triangles.push_back(t);
  }
  for (Tet t : b.tets) {
    for (Index& v : t) v += shift;
    m.tets.push_back(t);
  }
  m.triangle_tags.assign(m.triangles.size(), 0);
  m.tet_tags.assign(m.tets.size(), 0);
  return m;
}

Mesh translated(Mesh m, const Point& offset) {
  for (Point& p : m.points) {
    for (int k = 0; k < 3; ++k) p[k] += offset[k];
  }
  return m;
}

Mesh cube_grid(int n, std::array<int, 3> hole) {
  const int side = n + 1;
  const Index point_count = side * side * side;
  // Point (x, y, z) gets number scramble(x + side (y + side z)): multiplying by a number coprime
  // to the count permutes the numbers.
  Index multiplier = 7919;
  while (std::gcd(multiplier, point_count) != 1) ++multiplier;
  auto scramble = [&](Index i) {
    return static_cast<Index>((static_cast<std::int64_t>(i) * multiplier) % point_count);
  };
  std::vector<Point> points(point_count);
  for (int z = 0; z < side; ++z) {
    for (int y = 0; y < side; ++y) {
      for (int x = 0; x < side; ++x) {
        points[scramble(x + side * (y + side * z))] = {static_cast<double>(x),
                                                      static_cast<double>(y),
                                                      static_cast<double>(z)};
      }
    }
  }
  const Mesh unit = six_tet_cube();
  std::vector<Tet> tets;
  for (int z = 0; z < n; ++z) {
    for (int y = 0; y < n; ++y) {
      for (int x = 0; x < n; ++x) {
        if (std::array<int, 3>{x, y, z} == hole) continue;
        for (const Tet& local : unit.tets) {
          Tet tet;
          for (int k = 0; k < 4; ++k) {
            const Index c = local[k];  // unit cube corner c = dx + 2 dy + 4 dz
            tet[k] = scramble((x + (c & 1)) + side * ((y + ((c >> 1) & 1)) + side * (z + (c >> 2))));
          }
          tets.push_back(tet);
        }
      }
    }
  }
  // Scramble the tet order the same way, and rotate corners 1..3 (an even permutation).
  std::vector<Tet> scrambled(tets.size());
  Index tet_multiplier = 104729;
  while (std::gcd(tet_multiplier, static_cast<Index>(tets.size())) != 1) ++tet_multiplier;
  for (std::size_t i = 0; i < tets.size(); ++i) {
    Tet t = tets[i];
    for (std::size_t r = 0; r < i % 3; ++r) t = {t[0], t[2], t[3], t[1]};
    scrambled[(static_cast<std::int64_t>(i) * tet_multiplier) % tets.size()] = t;
  }
  return tet_mesh(std::move(points), std::move(scrambled));
}

Mesh boundary_by_brute_force(const Mesh& mesh) {
  std::map<Triangle, std::vector<Triangle>> faces;  // sorted triple -> oriented uses
  for (const Tet& tet : mesh.tets) {
    for (int corner = 0; corner < 4; ++corner) {
      const Triangle face = tet_face(tet, corner);
      Triangle key = face;
      std::sort(key.begin(), key.end());
      faces[key].push_back(face);
    }
  }
  std::vector<Triangle> triangles;
  for (const auto& [key, uses] : faces) {
    if (uses.size() == 1) triangles.push_back(uses[0]);
  }
  return surface_mesh(mesh.points, std::move(triangles));
}

}  // namespace afmesh::testing
