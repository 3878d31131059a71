// The discretely defined surface of paper §3: the input triangulation that the surface front
// grids over, with what steps S2, S3 and S8 need.
//
//   S2  the input face ("host face", IFADS) that contains or is closest to a point:
//       `locate(x, hint)` walks neighbour to neighbour from the host face stored for a nearby
//       point, as the paper advises ("by storing this 'host face' for every point, an efficient
//       neighbour-to-neighbour search procedure can be constructed"); `nearest_face(x)` asks the
//       AABB tree (core/spatial/aabb_tree.h) when there is no hint, and is the walk's fallback.
//   S3  the unit normal n_fds of a face: `normal(face)`.
//   S8  repositioning a new point on the surface: `project(x, hint)`, the closest point of the
//       located face.
//
// Local frame. Terrain and survey data come in coordinates like UTM (~5e6 m) where a double
// resolves ~1e-9 m; differences of such numbers lose the digits that matter. The surface keeps
// its points relative to a local origin, the centre of the input's bounding box (our choice; any
// point inside the model serves), and every query below takes and returns points in that local
// frame: convert with to_local / to_global where data enters and leaves. For points within a
// factor 2 of the origin the subtraction is exact (Sterbenz), so the local copy is the input.
//
// The walk. From the hint face, move to the edge neighbour whose closest point is strictly
// nearer to x (the nearest, ties to the smaller id). Where no edge neighbour is nearer, the face
// is a local minimum of the distance to x unless its closest point is one of its corners (the
// nearer face may then be two edges away round that vertex) or it has an open or non-manifold
// edge (faces beyond it are no edge neighbours): then look at the faces round those corners and
// go on from the nearest if it is strictly nearer. (The paper names the walk, not its rules:
// these are ours.) Distances strictly decrease, so the walk never
// cycles, and it stops at a local minimum of the distance from x to the surface. On a surface
// whose distance to x has one local minimum near x (x close to a smooth part of the surface,
// nearer than the local feature size) that is the nearest face; where it has several (x between
// two sheets, hint on the wrong one) the walk may return a locally nearest face; `nearest_face`
// is exact there.
#pragma once

#include <algorithm>
#include <cmath>
#include <span>
#include <vector>

#include "absl/status/statusor.h"
#include "core/common/progress.h"
#include "core/geometry/vec.h"
#include "core/mesh/mesh.h"
#include "core/quality/mesh_topology.h"
#include "core/spatial/aabb_tree.h"

namespace afmesh {

// A face (triangle) of the input triangulation, by its position in Mesh::triangles. A distinct
// type so that a face cannot be passed where a point index is meant.
enum class FaceId : Index {};
inline constexpr FaceId kNoFace{kInvalidIndex};
inline constexpr Index index_of(FaceId f) { return static_cast<Index>(f); }

struct DiscreteSurfaceParams {
  // The longest walk (faces moved to) before `locate` gives up and asks the tree. With a hint
  // one to three input edges away, walks take ~5 steps (at most 24 on the bunny scan; figures in
  // tests/surface/discrete_surface_test.cc), so 64 leaves room for hints ~10 edges away, i.e.
  // input faces ~10× finer than the target size, while a bad hint costs at most ~2 distance
  // evaluations per step (~130), a bounded multiple of a tree query (~5 evaluations near the
  // surface plus O(log M) box tests).
  int max_walk_steps = 64;
  // Build the AABB tree with the surface. Without it `nearest_face` scans every face (O(M) a
  // query, the same answer) until build_tree() is called: for a surface asked for a handful of
  // nearest faces, where the tree would cost more than the scans (not in the paper).
  bool tree = true;
};

// The face found for a point and how it was found.
struct Located {
  FaceId face = kNoFace;
  Point closest{0.0, 0.0, 0.0};   // closest point of `face` to x, local frame
  double squared_distance = 0.0;  // |x - closest|^2
  int walk_steps = 0;             // faces moved to by the walk (0 for nearest_face)
  bool used_tree = false;         // nearest_face answered (for a walk: it did not settle)
  int evaluations = 0;            // point-triangle distances computed (walk and tree)
};

class DiscreteSurface {
 public:
  // Builds the surface over mesh.points (N×3), mesh.triangles (M×3, M >= 1) and
  // mesh.triangle_tags (M, or empty: all 0); tets are ignored. Edge adjacency comes from
  // triangle_edge_neighbours (core/quality/mesh_topology.h), normals from the corners in the
  // local frame. O(M log M). INVALID_ARGUMENT, naming the element, for: no triangles, a point
  // with a non-finite coordinate, a triangle index out of range or repeated in a triangle, a
  // tag array of another length. Degenerate (zero-area) triangles are accepted: their normal
  // is the zero vector.
  // CANCELLED soon after progress.cancelled() turns true (looked at between the steps, while the
  // edges are sorted and while the AABB tree is built).
  // `neighbours`: the edge neighbours of mesh.triangles when the caller has them
  // (triangle_edge_neighbours' answer; repair_front gives them), else empty: found here.
  static absl::StatusOr<DiscreteSurface> build(const Mesh& mesh,
                                               const DiscreteSurfaceParams& params = {},
                                               Progress& progress = no_progress(),
                                               EdgeNeighbours neighbours = {});

  Index point_count() const { return static_cast<Index>(points_.size()); }
  Index face_count() const { return static_cast<Index>(triangles_.size()); }

  // The local origin (centre of the input's bounding box), global coordinates.
  const Point& origin() const { return origin_; }
  Point to_local(const Point& global) const;
  Point to_global(const Point& local) const;
  // Length of the bounding box's diagonal: the model size that tolerances scale with.
  double size() const { return size_; }

  // The input points in the local frame (N×3) and the input triangles (M×3) and tags (M).
  const std::vector<Point>& local_points() const { return points_; }
  const std::vector<Triangle>& triangles() const { return triangles_; }
  const std::vector<Index>& tags() const { return tags_; }
  const Triangle& triangle(FaceId f) const { return triangles_[index_of(f)]; }
  Index tag(FaceId f) const { return tags_[index_of(f)]; }

  // Edge adjacency (M×3; edge k of a face runs from corner k to corner k+1).
  const EdgeNeighbours& neighbours() const { return neighbours_; }
  // The faces using point `vertex` (0 <= vertex < N), ascending.
  std::span<const Index> faces_at(Index vertex) const;
  // The faces at edge (a, b): `forward` those traversing it a→b (the edge has them on its
  // left), `backward` those traversing it b→a; each ascending.
  void faces_at_edge(Index a, Index b, std::vector<Index>& forward,
                     std::vector<Index>& backward) const;
  // The host face of a point on edge (a, b) (a line's point, say): the first face traversing it
  // a→b, else the first traversing it b→a (faces_at_edge's forward[0], else backward[0]);
  // kNoFace when no face has the edge.
  FaceId face_at_edge(Index a, Index b) const;

  // S3: the unit normal of face f, (b-a)x(c-a) normalised; zero for a degenerate face.
  const Point& normal(FaceId f) const { return normals_[index_of(f)]; }
  // The centroid of face f, (a + (b + c)) / 3 in the local frame.
  const Point& centroid(FaceId f) const { return balls_[index_of(f)].centroid; }
  Index degenerate_face_count() const { return degenerate_faces_; }

  // |x - the closest point of face f to x|^2 (x in the local frame): the distance the walk and
  // the tree compare, bit for bit. With `closest`, that closest point too. Every search over
  // faces (this class's and the surface front's walk within a patch) measures with this one.
  double squared_distance_to_face(const Point& x, FaceId f) const;
  double squared_distance_to_face(const Point& x, FaceId f, Point& closest) const;
  // True only when squared_distance_to_face(x, f) > squared_distance, as computed: x is
  // farther from the ball round face f (its centroid, out to its farthest corner) than
  // sqrt(squared_distance), by a margin of 1e-9 of the coordinates' magnitude (the distances
  // round by a few units in their last place); never for a sliver face, whose closest point can
  // round off it. A fraction of the distance's cost: a walk uses it to pass over the faces
  // round it that cannot be nearer. False says nothing.
  bool cannot_be_nearer(const Point& x, FaceId f, double squared_distance) const {
    return cannot_be_nearer(x, ball_margin(x), f, squared_distance);
  }
  // The same test with the margin at x, ball_margin(x), worked out by the caller: a search that
  // tests many faces against one x works it out once.
  bool cannot_be_nearer(const Point& x, double margin, FaceId f, double squared_distance) const {
    const Ball& ball = balls_[index_of(f)];
    const double gap = distance(x, ball.centroid) - ball.radius - margin;
    return gap > 0.0 && gap * gap * (1.0 - 1e-9) > squared_distance;
  }
  // The margin of cannot_be_nearer at x: kBallMargin of the coordinates' magnitude.
  double ball_margin(const Point& x) const {
    return kBallMargin * (size_ + std::max({std::abs(x[0]), std::abs(x[1]), std::abs(x[2])}));
  }
  // The bounding box of the ball of face f that cannot_be_nearer tests (its centroid, out to
  // its farthest corner): all of space for a sliver.
  Box ball_box(FaceId f) const;
  // A box round x that the ball_box of every face for which cannot_be_nearer(x, f,
  // squared_distance) is false meets: x ± (sqrt(squared_distance) + twice the test's margin),
  // widened by a relative 1e-6 for rounding. So the faces that can be as near to x as a face
  // known to be sqrt(squared_distance) away (the nearest among them) have their balls there.
  Box reach_box(const Point& x, double squared_distance) const;

  // The face nearest to x (local frame) by the AABB tree, ties to the smaller face id.
  // O(log M) for x near the surface. Without the tree (params.tree false, build_tree not
  // called), the same face by a scan of all faces, O(M).
  Located nearest_face(const Point& x) const;

  // Calls visit(f) for every face whose bounding box overlaps `box` (local frame), by the AABB
  // tree (which must be built: has_tree()). O(log M + the faces visited).
  void for_each_face_overlapping(const Box& box, absl::FunctionRef<void(FaceId)> visit) const;

  // Whether the AABB tree is built; builds it (O(M log M)) for a surface built without. With
  // `cancel`, stopped partway when cancel->stopped() turns true: the caller drops the surface.
  bool has_tree() const { return tree_.size() == face_count(); }
  void build_tree(CancelCheck* cancel = nullptr);

  // S2: the face nearest to x (local frame) by the walk from `hint` (see the header comment);
  // with hint == kNoFace, or when the walk has not settled after params.max_walk_steps moves,
  // the tree's answer (used_tree = true).
  Located locate(const Point& x, FaceId hint) const;

  // S8: x (local frame) moved onto the surface: the closest point of locate(x, hint).face.
  Located project(const Point& x, FaceId hint) const { return locate(x, hint); }

 private:
  DiscreteSurface() = default;
  // The ball's margin, in units of the coordinates' magnitude: ~10^7 times the rounding of the
  // distances of the faces that have a ball.
  static constexpr double kBallMargin = 1e-9;
  // Squared distance from x to face f and its closest point; counts into at.evaluations.
  double squared_distance_to(const Point& x, FaceId f, Point& closest, Located& at) const;
  // Walk as far as a local minimum; false when it took more than max_walk_steps moves.
  bool walk(const Point& x, Located& at) const;
  // Where no edge neighbour is nearer: moves `at` to the nearest face around the corners where
  // a nearer face may hide, if one is strictly nearer; false at a local minimum.
  bool step_around_vertices(const Point& x, Located& at) const;

  DiscreteSurfaceParams params_;
  Point origin_{0.0, 0.0, 0.0};
  double size_ = 0.0;
  std::vector<Point> points_;        // N×3, local frame
  std::vector<Triangle> triangles_;  // M×3
  std::vector<Index> tags_;          // M
  std::vector<Point> normals_;       // M×3 unit (or zero)
  // A face's ball for cannot_be_nearer: its centroid and the largest distance from it to a
  // corner (infinite for a sliver). One array, so that a walk's test of a face reads one cache
  // line, not two (the tests' misses were most of their time on the 1M sphere).
  struct Ball {
    Point centroid;
    double radius = 0.0;
  };
  std::vector<Ball> balls_;  // M
  Index degenerate_faces_ = 0;
  EdgeNeighbours neighbours_;
  std::vector<Index> face_offsets_;  // N + 1: faces_at(v) = vertex_faces_[offsets[v], [v + 1])
  std::vector<Index> vertex_faces_;  // 3M
  AabbTree tree_;                    // over the faces' boxes, local frame (or empty: !has_tree())
};

}  // namespace afmesh
