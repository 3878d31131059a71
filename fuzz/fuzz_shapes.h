// Small shapes built from fuzz input bytes, shared by the mesher targets (fuzz_volume_mesher,
// fuzz_surface_mesher): a cube and an octahedron (closed and outward, corners within
// [-1, 1]), a cube cavity, free triangles on a lattice, and byte-driven corner moves and flips.
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <utility>

#include "core/mesh/mesh.h"

namespace afmesh::fuzz {

// The input bytes read in order; past the end they read as 0.
class Bytes {
 public:
  Bytes(const std::uint8_t* data, std::size_t size) : data_(data), size_(size) {}
  std::uint8_t next() { return at_ < size_ ? data_[at_++] : 0; }
  bool done() const { return at_ >= size_; }

 private:
  const std::uint8_t* data_;
  std::size_t size_;
  std::size_t at_ = 0;
};

// The cube [-half, half]^3: 8 points, 12 triangles, outward.
inline Mesh cube(double half) {
  Mesh m;
  for (int i = 0; i < 8; ++i) {
    m.points.push_back({(i & 1) ? half : -half, (i & 2) ? half : -half, (i & 4) ? half : -half});
  }
  m.triangles = {{0, 2, 3}, {0, 3, 1}, {4, 5, 7}, {4, 7, 6}, {0, 1, 5}, {0, 5, 4},
                 {2, 6, 7}, {2, 7, 3}, {0, 4, 6}, {0, 6, 2}, {1, 3, 7}, {1, 7, 5}};
  return m;
}

// The octahedron of corners (±1, 0, 0), (0, ±1, 0), (0, 0, ±1): 6 points, 8 triangles, outward.
inline Mesh octahedron() {
  Mesh m;
  m.points = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  for (int s = 0; s < 8; ++s) {
    const int sx = (s & 1) ? -1 : 1, sy = (s & 2) ? -1 : 1, sz = (s & 4) ? -1 : 1;
    const Index x = sx > 0 ? 0 : 1, y = sy > 0 ? 2 : 3, z = sz > 0 ? 4 : 5;
    if (sx * sy * sz > 0) {
      m.triangles.push_back({x, y, z});
    } else {
      m.triangles.push_back({x, z, y});
    }
  }
  return m;
}

// Appends `inner` to `outer`, its triangles turned inward (a cavity faces out of the domain).
inline void add_cavity(Mesh& outer, const Mesh& inner) {
  const auto offset = static_cast<Index>(outer.points.size());
  outer.points.insert(outer.points.end(), inner.points.begin(), inner.points.end());
  for (const Triangle& t : inner.triangles) {
    outer.triangles.push_back({t[0] + offset, t[2] + offset, t[1] + offset});
  }
}

// 4..11 points on a 1/32 lattice in [-4, 4] (one byte for the count, three per point), then
// triples of point indices until the bytes or 32 triangles run out.
inline Mesh free_triangles(Bytes& in) {
  Mesh m;
  const int n = 4 + in.next() % 8;
  for (int i = 0; i < n; ++i) {
    Point p;
    for (double& c : p) c = static_cast<std::int8_t>(in.next()) / 32.0;
    m.points.push_back(p);
  }
  while (!in.done() && m.triangles.size() < 32) {
    Triangle t;
    for (Index& v : t) v = in.next() % n;
    m.triangles.push_back(t);
  }
  return m;
}

// Moves each corner by 3 bytes (int8 / 256: up to half a unit per axis), then flips triangles
// by the bits of one byte per 8 triangles.
inline void perturb(Mesh& m, Bytes& in) {
  for (Point& p : m.points) {
    for (double& c : p) c += static_cast<std::int8_t>(in.next()) / 256.0;
  }
  std::uint8_t flips = 0;
  for (std::size_t t = 0; t < m.triangles.size(); ++t) {
    if (t % 8 == 0) flips = in.next();
    if (flips & (1u << (t % 8))) std::swap(m.triangles[t][1], m.triangles[t][2]);
  }
}

// The largest side of the points' bounding box (at least one point).
inline double largest_extent(const Mesh& m) {
  double extent = 0.0;
  for (int axis = 0; axis < 3; ++axis) {
    double lo = m.points[0][axis], hi = lo;
    for (const Point& p : m.points) {
      lo = std::min(lo, p[axis]);
      hi = std::max(hi, p[axis]);
    }
    extent = std::max(extent, hi - lo);
  }
  return extent;
}

// The fuzzed surface of the mesher targets: shape 0 a cube, 1 an octahedron (either with a
// cube of half the size inside when `with_cavity`, then perturbed), 2 free triangles; then one
// tag byte per triangle (%3). Reads its bytes from `in` in that order.
inline Mesh shape_from_bytes(Bytes& in, int shape, bool with_cavity) {
  Mesh m = shape == 0 ? cube(1.0) : shape == 1 ? octahedron() : free_triangles(in);
  if (shape != 2) {
    if (with_cavity) add_cavity(m, cube(0.5));
    perturb(m, in);
  }
  m.triangle_tags.resize(m.triangles.size(), 0);
  for (Index& tag : m.triangle_tags) tag = in.next() % 3;
  return m;
}

}  // namespace afmesh::fuzz
