// Delaunay tetrahedralisation, flip recovery of the front, and the inner side kept
// (conforming_fill.h).
#include "core/delaunay/conforming_fill.h"

#include <algorithm>
#include <array>
#include <cmath>

#include "absl/container/flat_hash_map.h"
#include "absl/strings/str_format.h"
#include "core/delaunay/delaunay_3d.h"
#include "core/delaunay/recover_faces.h"
#include "core/geometry/predicates.h"
#include "core/geometry/vec.h"
#include "core/quality/mesh_topology.h"
#include "core/quality/tet_complex.h"

namespace afmesh {
namespace {

using FaceKey = Triangle;  // sorted: an unoriented face

enum class Side : std::uint8_t { kUnknown, kInside, kOutside };

// Rounds of conforming_fill: a first with every point, then again without the points inside
// near the triangles still missing, and last with the front's corners alone.
constexpr int kDropRounds = 3;

// The levels of fills within fills (a region of a cavity filled as a front of its own,
// recover_faces_by_cavities).
constexpr int kMaxDepth = 3;

absl::StatusOr<ConformingFill> fill_region(std::span<const Point> points,
                                           std::span<const Triangle> front,
                                           std::int64_t max_tests, CancelCheck& stop, int depth);

// The Delaunay tetrahedralisation of the points `kept` (the front's corners are always kept),
// with the front's triangles recovered by flips; its elements in the numbering of `points`.
// Returns the triangles (indices into `front`) that are still missing.
absl::StatusOr<std::vector<Index>> recovered_delaunay(std::span<const Point> points,
                                                      std::span<const Triangle> front,
                                                      const std::vector<bool>& kept,
                                                      std::int64_t max_tests, CancelCheck& stop,
                                                      int depth, std::vector<Tet>& tets,
                                                      std::vector<Point>& steiner) {
  std::vector<Point> x;
  std::vector<Index> point_of, local(points.size(), kInvalidIndex);
  for (std::size_t p = 0; p < points.size(); ++p)
    if (kept[p]) {
      local[p] = static_cast<Index>(x.size());
      point_of.push_back(static_cast<Index>(p));
      x.push_back(points[p]);
    }
  absl::StatusOr<DelaunayTets> delaunay = delaunay_tetrahedralise(x);
  if (!delaunay.ok()) return delaunay.status();
  std::vector<Triangle> faces;
  for (const Triangle& f : front) {
    Triangle g;
    for (int i = 0; i < 3; ++i) {
      g[i] = local[static_cast<std::size_t>(f[i])];
      if (delaunay->vertex_of_point[static_cast<std::size_t>(g[i])] != g[i])
        return absl::InvalidArgumentError(absl::StrFormat(
            "front point %d coincides with point %d", f[i],
            point_of[static_cast<std::size_t>(
                delaunay->vertex_of_point[static_cast<std::size_t>(g[i])])]));
    }
    faces.push_back(g);
  }
  tets = std::move(delaunay->tets);
  if (stop.look()) return absl::CancelledError("volume meshing cancelled");
  std::vector<Index> missing = recover_faces_by_flips(x, tets, faces, max_tests, &stop);
  if (stop.stopped()) return absl::CancelledError("volume meshing cancelled");
  steiner.clear();
  if (!missing.empty()) {
    // A region of a cavity no point sees whole is filled as a front of its own, one level down.
    const RegionFill fill = [&](std::vector<Point>& corners, std::span<const Triangle> sides)
        -> std::optional<std::vector<Tet>> {
      if (depth + 1 >= kMaxDepth) return std::nullopt;
      const std::int64_t work = kFillTestsPerTriangle * static_cast<std::int64_t>(sides.size());
      absl::StatusOr<ConformingFill> region = fill_region(corners, sides, work, stop, depth + 1);
      if (!region.ok()) return std::nullopt;
      corners.insert(corners.end(), region->steiner.begin(), region->steiner.end());
      return std::move(region->tets);
    };
    missing = recover_faces_by_cavities(x, tets, faces, missing, &stop, fill);
    if (stop.stopped()) return absl::CancelledError("volume meshing cancelled");
    for (std::size_t i = point_of.size(); i < x.size(); ++i) {
      point_of.push_back(static_cast<Index>(points.size() + steiner.size()));
      steiner.push_back(x[i]);
    }
  }
  for (Tet& t : tets)
    for (Index& q : t) q = point_of[static_cast<std::size_t>(q)];
  return missing;
}

// Not kept any more: the points that are no front corner and lie in the ball about a missing
// triangle's centroid through its farthest corner (they keep it from being a Delaunay face).
// Returns how many were dropped.
std::int64_t drop_points_near(std::span<const Point> points, std::span<const Triangle> front,
                              const std::vector<Index>& missing,
                              const std::vector<Index>& by_x, std::vector<bool>& kept,
                              const std::vector<bool>& corner) {
  std::int64_t dropped = 0;
  for (const Index i : missing) {
    const Triangle& f = front[static_cast<std::size_t>(i)];
    const Point& a = points[static_cast<std::size_t>(f[0])];
    const Point& b = points[static_cast<std::size_t>(f[1])];
    const Point& c = points[static_cast<std::size_t>(f[2])];
    const Point m = scale(add(a, add(b, c)), 1.0 / 3.0);
    const double r2 = std::max({squared_norm(sub(a, m)), squared_norm(sub(b, m)),
                                squared_norm(sub(c, m))});
    const double r = std::sqrt(r2);
    auto it = std::lower_bound(by_x.begin(), by_x.end(), m[0] - r, [&](Index p, double x) {
      return points[static_cast<std::size_t>(p)][0] < x;
    });
    for (; it != by_x.end() && points[static_cast<std::size_t>(*it)][0] <= m[0] + r; ++it) {
      const auto p = static_cast<std::size_t>(*it);
      if (corner[p] || !kept[p] || squared_norm(sub(points[p], m)) >= r2) continue;
      kept[p] = false;
      ++dropped;
    }
  }
  return dropped;
}

absl::StatusOr<ConformingFill> fill_region(std::span<const Point> points,
                                           std::span<const Triangle> front,
                                           std::int64_t max_tests, CancelCheck& stop, int depth) {
  std::vector<bool> corner(points.size(), false), kept(points.size(), true);
  for (const Triangle& f : front)
    for (Index q : f) corner[static_cast<std::size_t>(q)] = true;
  std::vector<Index> by_x;  // the points that are no corner, by x
  for (std::size_t p = 0; p < points.size(); ++p)
    if (!corner[p]) by_x.push_back(static_cast<Index>(p));
  std::sort(by_x.begin(), by_x.end(), [&](Index p, Index q) {
    return points[static_cast<std::size_t>(p)][0] < points[static_cast<std::size_t>(q)][0];
  });
  std::vector<Tet> recovered;
  std::vector<Point> steiner;
  for (int round = 0;; ++round) {
    absl::StatusOr<std::vector<Index>> missing =
        recovered_delaunay(points, front, kept, max_tests, stop, depth, recovered, steiner);
    if (!missing.ok()) return missing.status();
    if (missing->empty()) break;
    // Points inside near a missing triangle may be what keeps it out: tried again without them,
    // and the last time with the front's corners alone.
    std::int64_t dropped = 0;
    if (round + 2 < kDropRounds)
      dropped = drop_points_near(points, front, *missing, by_x, kept, corner);
    if (round + 1 < kDropRounds && dropped == 0)
      for (Index p : by_x) {
        dropped += kept[static_cast<std::size_t>(p)] ? 1 : 0;
        kept[static_cast<std::size_t>(p)] = false;
      }
    if (dropped == 0)
      return absl::FailedPreconditionError(absl::StrFormat(
          "%d of the %d front triangles are not faces of the Delaunay tetrahedralisation of its "
          "points and could not be recovered by flips nor by refilling their cavities",
          missing->size(), front.size()));
  }

  // The front's triangles by their corners, and the elements' face adjacency.
  absl::flat_hash_map<FaceKey, Index> front_faces;
  for (std::size_t i = 0; i < front.size(); ++i) {
    front_faces.emplace(sorted_triangle(front[i]), static_cast<Index>(i));
  }
  Mesh fill;
  fill.points.assign(points.begin(), points.end());
  fill.points.insert(fill.points.end(), steiner.begin(), steiner.end());
  fill.tets = std::move(recovered);
  absl::StatusOr<TetComplex> complex = TetComplex::build(fill);
  if (!complex.ok()) return complex.status();
  const std::vector<Point>& x = fill.points;

  // Regions of elements joined through faces that are not the front's; each is inside (on the
  // inner side of a front triangle) or outside (on its outer side, or on the hull).
  const std::vector<Tet>& tets = fill.tets;
  std::vector<Index> region(tets.size(), kInvalidIndex);
  std::vector<Side> side;
  std::vector<Index> todo;
  for (std::size_t seed = 0; seed < tets.size(); ++seed) {
    if (region[seed] != kInvalidIndex) continue;
    const Index r = static_cast<Index>(side.size());
    side.push_back(Side::kUnknown);
    region[seed] = r;
    todo.assign(1, static_cast<Index>(seed));
    const auto learn = [&](Side s) {
      if (side[static_cast<std::size_t>(r)] != Side::kUnknown &&
          side[static_cast<std::size_t>(r)] != s)
        return false;
      side[static_cast<std::size_t>(r)] = s;
      return true;
    };
    while (!todo.empty()) {
      const Index t = todo.back();
      todo.pop_back();
      const Tet& e = tets[static_cast<std::size_t>(t)];
      for (int k = 0; k < 4; ++k) {
        const FaceKey key = tet_face_key(e, k);
        if (const auto f = front_faces.find(key); f != front_faces.end()) {
          const Triangle& v = front[static_cast<std::size_t>(f->second)];
          const int o = orient3d(x[static_cast<std::size_t>(v[0])],
                                 x[static_cast<std::size_t>(v[1])],
                                 x[static_cast<std::size_t>(v[2])],
                                 x[static_cast<std::size_t>(e[k])]);
          if (!learn(o < 0 ? Side::kInside : Side::kOutside))
            return absl::FailedPreconditionError(absl::StrFormat(
                "the elements on both sides of front triangle %d are joined without crossing "
                "the front",
                f->second));
          continue;
        }
        const Index u = complex->neighbour(t, k);
        if (u == kInvalidIndex) {
          if (!learn(Side::kOutside))
            return absl::FailedPreconditionError(
                "elements on the inner side of the front reach the hull of its points");
          continue;
        }
        if (region[static_cast<std::size_t>(u)] != kInvalidIndex) continue;
        region[static_cast<std::size_t>(u)] = r;
        todo.push_back(u);
      }
    }
  }

  std::vector<Tet> inside;
  for (std::size_t t = 0; t < tets.size(); ++t)
    if (side[static_cast<std::size_t>(region[t])] == Side::kInside) inside.push_back(tets[t]);
  // Each front triangle bounds exactly one element inside, on its inner side.
  std::vector<int> bounded(front.size(), 0);
  for (const Tet& e : inside)
    for (int k = 0; k < 4; ++k)
      if (const auto f = front_faces.find(tet_face_key(e, k)); f != front_faces.end())
        ++bounded[static_cast<std::size_t>(f->second)];
  for (std::size_t i = 0; i < front.size(); ++i)
    if (bounded[i] != 1)
      return absl::FailedPreconditionError(absl::StrFormat(
          "front triangle %d bounds %d elements of the fill, not one", i, bounded[i]));
  return ConformingFill{std::move(steiner), std::move(inside)};
}

}  // namespace

absl::StatusOr<ConformingFill> conforming_fill(std::span<const Point> points,
                                               std::span<const Triangle> front,
                                               std::int64_t max_tests, Progress& progress) {
  CancelCheck stop(progress, 64);
  return fill_region(points, front, max_tests, stop, 0);
}

}  // namespace afmesh
