#include "core/sizing/background_grid.h"

#include <Eigen/Dense>
#include <algorithm>
#include <utility>

#include "absl/container/flat_hash_map.h"
#include "core/geometry/predicates.h"
#include "core/geometry/vec.h"

namespace afmesh {
namespace {

// Steps after which a walk gives up (it may cycle in a non-Delaunay grid) and the AABB tree
// answers instead.
constexpr int kMaxWalkSteps = 256;

// The face opposite corner i of tet t, as sorted point indices (a key shared by both sides).
std::array<Index, 3> face_key(const Tet& t, int i) {
  std::array<Index, 3> f;
  int n = 0;
  for (int c = 0; c < 4; ++c) {
    if (c != i) f[n++] = t[c];
  }
  std::sort(f.begin(), f.end());
  return f;
}

}  // namespace

absl::StatusOr<BackgroundGrid> BackgroundGrid::from_arrays(std::vector<Point> points,
                                                           std::vector<Tet> tets,
                                                           std::vector<double> sizes) {
  return from_spec(BackgroundGridSpec{std::move(points), std::move(tets), std::move(sizes)});
}

absl::StatusOr<BackgroundGrid> BackgroundGrid::from_spec(BackgroundGridSpec spec) {
  if (absl::Status s = validate_background_grid(spec, "background"); !s.ok()) return s;
  return BackgroundGrid(std::move(spec));
}

// Corners are numbered x + 2y + 4z (0/1 for low/high). The corners of even parity (0, 3, 5, 6)
// form the central tet; each odd corner forms a corner tet with its three even neighbours.
BackgroundGrid BackgroundGrid::box_grid(const Box& box, double size) {
  BackgroundGridSpec spec;
  for (int c = 0; c < 8; ++c) {
    spec.points.push_back({(c & 1) ? box.hi[0] : box.lo[0], (c & 2) ? box.hi[1] : box.lo[1],
                           (c & 4) ? box.hi[2] : box.lo[2]});
  }
  spec.tets = {{0, 3, 5, 6}, {1, 0, 3, 5}, {2, 0, 3, 6}, {4, 0, 5, 6}, {7, 3, 5, 6}};
  for (Tet& t : spec.tets) {
    const auto& p = spec.points;
    if (orient3d(p[t[0]], p[t[1]], p[t[2]], p[t[3]]) < 0) std::swap(t[2], t[3]);
  }
  spec.sizes.assign(8, size);
  return BackgroundGrid(std::move(spec));
}

BackgroundGrid::BackgroundGrid(BackgroundGridSpec spec)
    : points_(std::move(spec.points)),
      tets_(std::move(spec.tets)),
      sizes_(std::move(spec.sizes)),
      nearest_(points_) {
  uniform_ = std::all_of(sizes_.begin(), sizes_.end(), [&](double s) { return s == sizes_[0]; });
  std::vector<Box> boxes;
  boxes.reserve(tets_.size());
  for (const Tet& t : tets_) {
    Box b = empty_box();
    for (Index v : t) enclose(b, points_[v]);
    boxes.push_back(b);
  }
  tet_tree_ = AabbTree(std::move(boxes));
  build_neighbours();
  build_interpolation();
}

void BackgroundGrid::build_neighbours() {
  neighbours_.assign(tets_.size(), {kInvalidIndex, kInvalidIndex, kInvalidIndex, kInvalidIndex});
  absl::flat_hash_map<std::array<Index, 3>, std::pair<Index, int>> open;
  open.reserve(2 * tets_.size());
  for (Index t = 0; t < static_cast<Index>(tets_.size()); ++t) {
    for (int i = 0; i < 4; ++i) {
      const auto [it, inserted] = open.try_emplace(face_key(tets_[t], i), t, i);
      if (inserted) continue;
      const auto [other, j] = it->second;
      neighbours_[t][i] = other;
      neighbours_[other][j] = t;
    }
  }
}

// Per tet, the inverse of J = [b - a, c - a, d - a]: (l1, l2, l3) = J^-1 (x - a) are the
// barycentric coordinates of x for corners b, c, d.
void BackgroundGrid::build_interpolation() {
  inverse_.resize(tets_.size());
  for (std::size_t t = 0; t < tets_.size(); ++t) {
    const Point& a = points_[tets_[t][0]];
    Eigen::Matrix3d j;
    for (int c = 0; c < 3; ++c) {
      const Point e = sub(points_[tets_[t][c + 1]], a);
      j.col(c) = Eigen::Vector3d(e[0], e[1], e[2]);
    }
    const Eigen::Matrix3d inv = j.inverse();
    for (int r = 0; r < 3; ++r) {
      for (int c = 0; c < 3; ++c) inverse_[t][3 * r + c] = inv(r, c);
    }
  }
}

// Exact side of x relative to the face opposite corner `face` of tet t: +1 on the tet's side,
// 0 on the face's plane, -1 beyond it.
int BackgroundGrid::side(Index t, int face, const Point& x) const {
  std::array<const Point*, 4> q;
  for (int c = 0; c < 4; ++c) q[c] = &points_[tets_[t][c]];
  q[face] = &x;
  return orient3d(*q[0], *q[1], *q[2], *q[3]);
}

// Walks from `start` towards x through faces that x lies beyond (trying faces in a rotating
// order, which breaks most cycles). Returns the tet strictly containing x, or kInvalidIndex when
// the walk cannot decide (x on a face of the tet reached, outside the grid, or too many steps).
Index BackgroundGrid::walk(Index start, const Point& x) const {
  Index t = start;
  for (int step = 0; step < kMaxWalkSteps; ++step) {
    int exit_face = -1;
    bool on_boundary = false;
    for (int k = 0; k < 4 && exit_face < 0; ++k) {
      const int face = (k + step) % 4;
      const int s = side(t, face, x);
      if (s < 0) exit_face = face;
      if (s == 0) on_boundary = true;
    }
    if (exit_face < 0) return on_boundary ? kInvalidIndex : t;
    t = neighbours_[t][exit_face];
    if (t == kInvalidIndex) return kInvalidIndex;
  }
  return kInvalidIndex;
}

Index BackgroundGrid::smallest_containing(const Point& x) const {
  Index best = kInvalidIndex;
  tet_tree_.for_each_overlap(Box{x, x}, [&](Index t) {
    if (best != kInvalidIndex && t > best) return;
    for (int face = 0; face < 4; ++face) {
      if (side(t, face, x) < 0) return;
    }
    best = t;
  });
  return best;
}

Index BackgroundGrid::locate(const Point& x, Hint* hint) const {
  Index t = kInvalidIndex;
  if (hint != nullptr && hint->tet >= 0 && hint->tet < static_cast<Index>(tets_.size())) {
    t = walk(hint->tet, x);
  }
  if (t == kInvalidIndex) t = smallest_containing(x);
  if (hint != nullptr && t != kInvalidIndex) hint->tet = t;
  return t;
}

double BackgroundGrid::interpolate(Index t, const Point& x) const {
  const Tet& v = tets_[t];
  const Point d = sub(x, points_[v[0]]);
  const std::array<double, 9>& m = inverse_[t];
  const double l1 = m[0] * d[0] + m[1] * d[1] + m[2] * d[2];
  const double l2 = m[3] * d[0] + m[4] * d[1] + m[5] * d[2];
  const double l3 = m[6] * d[0] + m[7] * d[1] + m[8] * d[2];
  const double s0 = sizes_[v[0]];
  return s0 + l1 * (sizes_[v[1]] - s0) + l2 * (sizes_[v[2]] - s0) + l3 * (sizes_[v[3]] - s0);
}

double BackgroundGrid::size_at(const Point& x, Hint* hint) const {
  if (uniform_) return sizes_[0];
  const Index t = locate(x, hint);
  if (t != kInvalidIndex) return interpolate(t, x);
  return sizes_[nearest_.nearest(x)];
}

}  // namespace afmesh
