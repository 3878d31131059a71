// Shared helpers for the geometry tests: exact integer references and random point generators.
#pragma once

#include <array>
#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

#include "core/mesh/mesh.h"

namespace afmesh::testing {

__extension__ typedef __int128 Int128;
__extension__ typedef unsigned __int128 UInt128;

inline int sign_of(Int128 x) { return (x > 0) - (x < 0); }

using IntPoint = std::array<std::int64_t, 3>;

inline Point to_point(const IntPoint& p, double scale = 1.0) {
  return {double(p[0]) * scale, double(p[1]) * scale, double(p[2]) * scale};
}

// Exact sign of det[b-a, c-a, d-a] for integer points with |coordinate| <= 2^40.
inline int orient3d_reference(const IntPoint& a, const IntPoint& b, const IntPoint& c,
                              const IntPoint& d) {
  const Int128 ux = b[0] - a[0], uy = b[1] - a[1], uz = b[2] - a[2];
  const Int128 vx = c[0] - a[0], vy = c[1] - a[1], vz = c[2] - a[2];
  const Int128 wx = d[0] - a[0], wy = d[1] - a[1], wz = d[2] - a[2];
  return sign_of(ux * (vy * wz - vz * wy) - uy * (vx * wz - vz * wx) + uz * (vx * wy - vy * wx));
}

// Exact sign of det[b-a, c-a] for 2-D integer points with |coordinate| <= 2^60.
inline int orient2d_reference(std::int64_t ax, std::int64_t ay, std::int64_t bx, std::int64_t by,
                              std::int64_t cx, std::int64_t cy) {
  const Int128 ux = Int128(bx) - ax, uy = Int128(by) - ay;
  const Int128 vx = Int128(cx) - ax, vy = Int128(cy) - ay;
  return sign_of(ux * vy - uy * vx);
}

// Determinant of an n×n Int128 matrix by cofactor expansion along the first row (n <= 4).
inline Int128 determinant(const std::vector<std::vector<Int128>>& m) {
  const std::size_t n = m.size();
  if (n == 1) return m[0][0];
  Int128 total = 0;
  for (std::size_t column = 0; column < n; ++column) {
    std::vector<std::vector<Int128>> minor;
    for (std::size_t row = 1; row < n; ++row) {
      std::vector<Int128> entries;
      for (std::size_t k = 0; k < n; ++k) {
        if (k != column) entries.push_back(m[row][k]);
      }
      minor.push_back(entries);
    }
    const Int128 term = m[0][column] * determinant(minor);
    total += column % 2 == 0 ? term : -term;
  }
  return total;
}

// The documented insphere sign for integer points with |coordinate| <= 2^19: minus the sign of
// det of the rows (p - e, |p - e|^2), p = a, b, c, d.
inline int insphere_reference(const IntPoint& a, const IntPoint& b, const IntPoint& c,
                              const IntPoint& d, const IntPoint& e) {
  std::vector<std::vector<Int128>> rows;
  for (const IntPoint* p : {&a, &b, &c, &d}) {
    const Int128 x = (*p)[0] - e[0], y = (*p)[1] - e[1], z = (*p)[2] - e[2];
    rows.push_back({x, y, z, x * x + y * y + z * z});
  }
  return -sign_of(determinant(rows));
}

inline IntPoint random_int_point(std::mt19937_64& rng, std::int64_t bound) {
  std::uniform_int_distribution<std::int64_t> coordinate(-bound, bound);
  return {coordinate(rng), coordinate(rng), coordinate(rng)};
}

inline Point random_point(std::mt19937_64& rng, double low = -1.0, double high = 1.0) {
  std::uniform_real_distribution<double> coordinate(low, high);
  return {coordinate(rng), coordinate(rng), coordinate(rng)};
}

// a + s (b - a) + t (c - a), rounded: near (usually not exactly on) the plane of a, b, c.
inline Point near_plane_point(const Point& a, const Point& b, const Point& c, double s, double t) {
  Point p;
  for (int k = 0; k < 3; ++k) p[k] = a[k] + s * (b[k] - a[k]) + t * (c[k] - a[k]);
  return p;
}

}  // namespace afmesh::testing
