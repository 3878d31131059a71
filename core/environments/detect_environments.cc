// --envs auto: thin pairs, sides, growth, numbering, separation (detect_environments.h,
// paper §2).
#include "core/environments/detect_environments.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "absl/strings/str_format.h"
#include "core/geometry/closest_points.h"
#include "core/geometry/intersect.h"
#include "core/geometry/predicates.h"
#include "core/geometry/vec.h"
#include "core/spatial/aabb_tree.h"
#include "core/spatial/box.h"

namespace afmesh {
namespace {

// Pairs tested between two looks at progress.cancelled().
constexpr std::size_t kCancelCheckInterval = 4096;

// Unit normal and local size of each face.
struct FaceFrames {
  std::vector<Point> normal;   // M unit normals, (b-a)x(c-a) normalised
  std::vector<double> size;    // M mean edge lengths h
};

enum class PairKind { kCrossing, kClose };

struct ThinPair {
  Index f = 0;  // f < g
  Index g = 0;
  PairKind kind = PairKind::kCrossing;
  double distance = 0.0;  // 0 for crossing pairs
};

// A union-find over face ids whose representative is the smallest id of its set, so that the
// result depends only on which unions happen, not on their order.
class SmallestIdSets {
 public:
  explicit SmallestIdSets(std::size_t n) { reset(n); }
  // n singletons again (the storage is kept).
  void reset(std::size_t n) {
    parent_.resize(n);
    for (std::size_t i = 0; i < n; ++i) parent_[i] = static_cast<Index>(i);
  }
  Index find(Index i) {
    while (parent_[i] != i) {
      parent_[i] = parent_[parent_[i]];
      i = parent_[i];
    }
    return i;
  }
  void unite(Index a, Index b) {
    a = find(a);
    b = find(b);
    if (a < b) std::swap(a, b);
    parent_[a] = b;  // the larger root joins the smaller
  }

 private:
  std::vector<Index> parent_;
};

// Preconditions of the rule: indices in range, finite coordinates, no degenerate triangle
// (exact), parameters in range.
absl::Status check_auto_input(const Mesh& front, const AutoEnvironmentParams& params) {
  if (!std::isfinite(params.closeness) || params.closeness < 0.0) {
    return absl::InvalidArgumentError(absl::StrFormat(
        "automatic environments: closeness must be finite and >= 0, got %g", params.closeness));
  }
  if (params.grow_rings < 0) {
    return absl::InvalidArgumentError(absl::StrFormat(
        "automatic environments: grow_rings must be >= 0, got %d", params.grow_rings));
  }
  if (!(params.fold_angle_deg > 0.0 && params.fold_angle_deg < 180.0)) {
    return absl::InvalidArgumentError(absl::StrFormat(
        "automatic environments: fold angle must be in (0, 180) degrees, got %g",
        params.fold_angle_deg));
  }
  for (std::size_t p = 0; p < front.points.size(); ++p) {
    for (const double c : front.points[p]) {
      if (!std::isfinite(c)) {
        return absl::InvalidArgumentError(
            absl::StrFormat("point %d has a non-finite coordinate", p));
      }
    }
  }
  const auto point_count = static_cast<Index>(front.points.size());
  for (std::size_t t = 0; t < front.triangles.size(); ++t) {
    const Triangle& tri = front.triangles[t];
    for (const Index p : tri) {
      if (p < 0 || p >= point_count) {
        return absl::InvalidArgumentError(absl::StrFormat(
            "triangle %d refers to point %d, but the front has %d points", t, p, point_count));
      }
    }
    if (tri[0] == tri[1] || tri[1] == tri[2] || tri[0] == tri[2] ||
        collinear(front.points[tri[0]], front.points[tri[1]], front.points[tri[2]])) {
      return absl::InvalidArgumentError(absl::StrFormat(
          "triangle %d (%d,%d,%d) is degenerate: it has no normal to tell its side by", t,
          tri[0], tri[1], tri[2]));
    }
  }
  return absl::OkStatus();
}

FaceFrames face_frames(const Mesh& front) {
  FaceFrames frames;
  frames.normal.reserve(front.triangles.size());
  frames.size.reserve(front.triangles.size());
  for (const Triangle& t : front.triangles) {
    const Point& a = front.points[t[0]];
    const Point& b = front.points[t[1]];
    const Point& c = front.points[t[2]];
    const Point n = cross(sub(b, a), sub(c, a));
    const double length = norm(n);
    frames.normal.push_back(length > 0.0 ? scale(n, 1.0 / length) : Point{0.0, 0.0, 0.0});
    frames.size.push_back((distance(a, b) + distance(b, c) + distance(c, a)) / 3.0);
  }
  return frames;
}

int shared_vertex_count(const Triangle& t, const Triangle& u) {
  int shared = 0;
  for (const Index a : t) shared += static_cast<int>(std::count(u.begin(), u.end(), a));
  return shared;
}

// The cosine of an angle in degrees (the fold angle's, compared with dot products of normals).
double cosine_of_degrees(double degrees) { return std::cos(degrees * std::numbers::pi / 180.0); }

// True when triangles t and u, projected along the coordinate axis nearest `facing`, overlap in
// more than a line or a point: they lie over each other, seen from where they face. Exact
// (orient2d_projected); a triangle seen edge-on covers nothing. Two convex polygons whose
// interiors are disjoint are parted by the line through an edge of one of them (separating
// axes).
bool lie_over_each_other(const Mesh& front, const Triangle& t, const Triangle& u,
                         const Point& facing) {
  int axis = 0;
  for (int k = 1; k < 3; ++k)
    if (std::abs(facing[k]) > std::abs(facing[axis])) axis = k;
  const auto& x = front.points;
  const auto parted_by_an_edge_of = [&](const Triangle& a, const Triangle& b) {
    const int turn = orient2d_projected(x[a[0]], x[a[1]], x[a[2]], axis);
    if (turn == 0) return true;
    for (int e = 0; e < 3; ++e) {
      const Point& p = x[a[e]];
      const Point& q = x[a[(e + 1) % 3]];
      if (std::all_of(b.begin(), b.end(), [&](Index c) {
            return turn * orient2d_projected(p, q, x[c], axis) <= 0;
          }))
        return true;
    }
    return false;
  };
  return !parted_by_an_edge_of(t, u) && !parted_by_an_edge_of(u, t);
}

// Step 1, rule (b): f and g (sharing no vertex, not intersecting) nearly touch from the two
// sides of a thin solid; `fold_cosine` is that of params.fold_angle_deg. Sets `distance` when
// they do.
bool nearly_touch_back_to_back(const Mesh& front, const FaceFrames& frames,
                               const AutoEnvironmentParams& params, double fold_cosine, Index f,
                               Index g, double& distance_out) {
  const Point& nf = frames.normal[f];
  const Point& ng = frames.normal[g];
  // Not folded against each other: a thin region's two sides look nearly opposite ways (more
  // than the fold angle apart, as where they meet, step 2); faces at a corner of the front, a
  // side and the narrow strip closing its rim, say, do not.
  if (!(dot(nf, ng) < fold_cosine)) return false;
  const Triangle& t = front.triangles[f];
  const Triangle& u = front.triangles[g];
  const ClosestPair closest =
      closest_points_triangles(front.points[t[0]], front.points[t[1]], front.points[t[2]],
                               front.points[u[0]], front.points[u[1]], front.points[u[2]]);
  const double d = std::sqrt(closest.squared_distance);
  if (!(d < params.closeness * std::min(frames.size[f], frames.size[g]))) return false;
  const Point v = sub(closest.second, closest.first);
  if (!(dot(nf, v) > 0.0 && dot(ng, v) < 0.0)) return false;  // a gap of the domain
  // The two sides of a thin region lie over each other. Faces that are near and face each
  // other but lie side by side, seen from where they face, do not (not in the paper): facets
  // 20 and 15 long of two cylinders of netgen_hinge end in the plane x = 34.82, 1 apart and
  // facing each other across the step between them, and were taken for the sides of a gap.
  if (!lie_over_each_other(front, t, u, sub(nf, ng))) return false;
  distance_out = d;
  return true;
}

// Step 1: the thin pairs (f < g), in ascending (f, g) order.
absl::StatusOr<std::vector<ThinPair>> find_thin_pairs(const Mesh& front, const FaceFrames& frames,
                                                      const AutoEnvironmentParams& params,
                                                      Progress& progress) {
  const double fold_cosine = cosine_of_degrees(params.fold_angle_deg);
  std::vector<Box> boxes = triangle_boxes(front.points, front.triangles);
  for (std::size_t t = 0; t < boxes.size(); ++t) {
    boxes[t] = grown(boxes[t], params.closeness * frames.size[t]);
  }
  const std::vector<std::pair<Index, Index>> candidates = AabbTree(std::move(boxes)).overlapping_pairs();
  std::vector<ThinPair> pairs;
  for (std::size_t i = 0; i < candidates.size(); ++i) {
    if (i % kCancelCheckInterval == 0) {
      if (progress.cancelled()) return absl::CancelledError("environment detection cancelled");
      progress.report("environments", 0.9 * static_cast<double>(i) / candidates.size());
    }
    const auto [f, g] = candidates[i];
    const Triangle& t = front.triangles[f];
    const Triangle& u = front.triangles[g];
    if (triangles_intersect_improperly(front.points, t, u)) {
      pairs.push_back({f, g, PairKind::kCrossing, 0.0});
      continue;
    }
    double d = 0.0;
    if (shared_vertex_count(t, u) == 0 &&
        nearly_touch_back_to_back(front, frames, params, fold_cosine, f, g, d)) {
      pairs.push_back({f, g, PairKind::kClose, d});
    }
  }
  return pairs;
}

// The faces around each point, compressed rows with faces ascending: those of point p are
// faces[start[p]] .. faces[start[p + 1] - 1].
struct FacesAroundPoints {
  std::vector<Index> start;
  std::vector<Index> faces;
};

FacesAroundPoints faces_around_points(const Mesh& front) {
  FacesAroundPoints around;
  around.start.assign(front.points.size() + 1, 0);
  for (const Triangle& t : front.triangles) {
    for (const Index p : t) ++around.start[p + 1];
  }
  for (std::size_t p = 0; p < front.points.size(); ++p) around.start[p + 1] += around.start[p];
  around.faces.resize(around.start.back());
  std::vector<Index> fill(around.start.begin(), around.start.end() - 1);
  for (std::size_t t = 0; t < front.triangles.size(); ++t) {
    for (const Index p : front.triangles[t]) around.faces[fill[p]++] = static_cast<Index>(t);
  }
  return around;
}

// The parts of the fan of faces around a point p: its faces (slots 0 .. count - 1 of p's row in
// FacesAroundPoints) joined across edges through p whose two faces do not fold (the angle
// between their normals at most the fold angle, `fold_cosine` its cosine).
class FanParts {
 public:
  void split(const Mesh& front, const FaceFrames& frames, const FacesAroundPoints& around,
             double fold_cosine, Index p) {
    const Index first = around.start[p], count = around.start[p + 1] - first;
    spokes_.clear();
    for (Index i = 0; i < count; ++i) {
      for (const Index q : front.triangles[around.faces[first + i]]) {
        if (q != p) spokes_.emplace_back(q, i);
      }
    }
    std::sort(spokes_.begin(), spokes_.end());
    parts_.reset(count);
    for (std::size_t k = 0; k < spokes_.size(); ++k) {  // faces on one edge (p, q)
      for (std::size_t l = k + 1; l < spokes_.size() && spokes_[l].first == spokes_[k].first;
           ++l) {
        const Index f = around.faces[first + spokes_[k].second];
        const Index g = around.faces[first + spokes_[l].second];
        if (dot(frames.normal[f], frames.normal[g]) >= fold_cosine) {
          parts_.unite(spokes_[k].second, spokes_[l].second);
        }
      }
    }
  }
  // The part of slot i (its smallest slot).
  Index part(Index i) { return parts_.find(i); }

 private:
  std::vector<std::pair<Index, Index>> spokes_;  // (other end of an edge through p, slot)
  SmallestIdSets parts_{0};
};

// Step 2: groups the faces of thin pairs into sides; returns, per face, the smallest face id of
// its side, or kInvalidIndex for faces in no thin pair.
//
// Two marked faces at a point p join when the fan of faces around p (all faces, marked or not)
// leads from one to the other across edges through p that do not fold. Around a point on the
// rim of a thin sheet the fan folds twice (the rim edges), so the sheet's two sides stay apart;
// at a point where several sheets meet only in a point (the apex where the rims of a crossing
// X cross) each sheet's faces form their own part of the fan, even where two of them are
// coplanar.
std::vector<Index> group_sides(const Mesh& front, const FaceFrames& frames,
                               const std::vector<ThinPair>& pairs, double fold_angle_deg) {
  const std::size_t face_count = front.triangles.size();
  std::vector<bool> marked(face_count, false);
  for (const ThinPair& p : pairs) marked[p.f] = marked[p.g] = true;

  const FacesAroundPoints around = faces_around_points(front);
  const std::vector<Index>& start = around.start;
  const std::vector<Index>& faces_at = around.faces;

  const double fold_cosine = cosine_of_degrees(fold_angle_deg);
  SmallestIdSets sides(face_count);
  FanParts fan;
  std::vector<Index> part_face;
  for (std::size_t p = 0; p < front.points.size(); ++p) {
    const Index first = start[p], count = start[p + 1] - first;
    if (count < 2) continue;
    fan.split(front, frames, around, fold_cosine, static_cast<Index>(p));
    part_face.assign(count, kInvalidIndex);  // the first marked face of each part of the fan
    for (Index i = 0; i < count; ++i) {
      const Index f = faces_at[first + i];
      if (!marked[f]) continue;
      Index& seen = part_face[fan.part(i)];
      if (seen == kInvalidIndex) {
        seen = f;
      } else {
        sides.unite(seen, f);
      }
    }
  }
  std::vector<Index> side(face_count, kInvalidIndex);
  for (std::size_t t = 0; t < face_count; ++t) {
    if (marked[t]) side[t] = sides.find(static_cast<Index>(t));
  }
  return side;
}

// Pairs (f, g), both orders, of faces sharing an edge whose normals do not fold (the angle
// between them is at most the fold angle), sorted.
std::vector<std::pair<Index, Index>> non_fold_edge_neighbours(const Mesh& front,
                                                              const FaceFrames& frames,
                                                              double fold_cosine) {
  struct EdgeUse {
    Index a, b, face;
    bool operator<(const EdgeUse& o) const {
      return std::tie(a, b, face) < std::tie(o.a, o.b, o.face);
    }
  };
  std::vector<EdgeUse> uses;
  uses.reserve(3 * front.triangles.size());
  for (Index t = 0; t < static_cast<Index>(front.triangles.size()); ++t) {
    const Triangle& tri = front.triangles[t];
    for (int k = 0; k < 3; ++k) {
      const Index p = tri[k], q = tri[(k + 1) % 3];
      uses.push_back({std::min(p, q), std::max(p, q), t});
    }
  }
  std::sort(uses.begin(), uses.end());
  std::vector<std::pair<Index, Index>> neighbours;
  for (std::size_t first = 0; first < uses.size();) {
    std::size_t last = first + 1;
    while (last < uses.size() && uses[last].a == uses[first].a && uses[last].b == uses[first].b) {
      ++last;
    }
    for (std::size_t i = first; i < last; ++i) {
      for (std::size_t j = first; j < last; ++j) {
        const Index f = uses[i].face, g = uses[j].face;
        if (f != g && dot(frames.normal[f], frames.normal[g]) >= fold_cosine) {
          neighbours.emplace_back(f, g);
        }
      }
    }
    first = last;
  }
  std::sort(neighbours.begin(), neighbours.end());
  return neighbours;
}

// True when face f, in the fan of faces around its point x, is joined across edges through x
// that do not fold (FanParts, as in group_sides) to a face of a side other than `s`.
bool fan_meets_other_side(const Mesh& front, const FaceFrames& frames,
                          const FacesAroundPoints& around, double fold_cosine,
                          const std::vector<Index>& side, Index f, Index x, Index s,
                          FanParts& fan) {
  const Index first = around.start[x], count = around.start[x + 1] - first;
  fan.split(front, frames, around, fold_cosine, x);
  Index of_f = kInvalidIndex;
  for (Index i = 0; i < count && of_f == kInvalidIndex; ++i) {
    if (around.faces[first + i] == f) of_f = fan.part(i);
  }
  for (Index i = 0; i < count; ++i) {
    const Index h = around.faces[first + i];
    if (side[h] != kInvalidIndex && side[h] != s && fan.part(i) == of_f) return true;
  }
  return false;
}

// One ring of growth: the sides after unmarked faces whose marked neighbours all lie on one
// side joined it. A face that the fan around one of its points joins without a fold to a face
// of another side stays unmarked too: the narrow strip closing a plate's rim between its two
// sides (not in the paper, whose sides meet in shared rim points, the fans folding between
// them). Returns false when no face joined.
bool grow_one_ring(const Mesh& front, const FaceFrames& frames, const FacesAroundPoints& around,
                   double fold_cosine, const std::vector<std::pair<Index, Index>>& neighbours,
                   std::vector<Index>& side) {
  std::vector<Index> next = side;
  bool grew = false;
  FanParts fan;
  for (std::size_t first = 0; first < neighbours.size();) {
    const Index f = neighbours[first].first;
    Index joined = kInvalidIndex;
    bool ambiguous = false;
    std::size_t last = first;
    for (; last < neighbours.size() && neighbours[last].first == f; ++last) {
      const Index s = side[neighbours[last].second];
      if (s == kInvalidIndex) continue;
      if (joined == kInvalidIndex) {
        joined = s;
      } else if (joined != s) {
        ambiguous = true;
      }
    }
    if (side[f] == kInvalidIndex && joined != kInvalidIndex && !ambiguous) {
      for (const Index x : front.triangles[f]) {
        ambiguous = ambiguous ||
                    fan_meets_other_side(front, frames, around, fold_cosine, side, f, x, joined,
                                         fan);
      }
      if (!ambiguous) {
        next[f] = joined;
        grew = true;
      }
    }
    first = last;
  }
  side = std::move(next);
  return grew;
}

// Step 3: grows the sides by up to `rings` rings of faces across non-fold edges. In each ring,
// an unmarked face joins a side when its marked edge neighbours that do not fold against it all
// belong to that one side (faces between two sides stay unmarked). Rings are computed from the
// previous ring's state only, so the order of faces does not matter.
void grow_sides(const Mesh& front, const FaceFrames& frames, int rings, double fold_angle_deg,
                std::vector<Index>& side) {
  if (rings == 0) return;
  const double fold_cosine = cosine_of_degrees(fold_angle_deg);
  const std::vector<std::pair<Index, Index>> neighbours =
      non_fold_edge_neighbours(front, frames, fold_cosine);
  const FacesAroundPoints around = faces_around_points(front);
  for (int ring = 0; ring < rings; ++ring) {
    if (!grow_one_ring(front, frames, around, fold_cosine, neighbours, side)) break;
  }
}

// Step 4: environment ids 1, 2, ... in the order of each side's smallest face; 0 elsewhere.
std::vector<std::int32_t> number_sides(const std::vector<Index>& side) {
  std::vector<std::int32_t> environment(side.size(), kNoEnvironment);
  std::vector<std::int32_t> id_of_root(side.size(), kNoEnvironment);
  std::int32_t next = 1;
  for (std::size_t t = 0; t < side.size(); ++t) {
    if (side[t] == kInvalidIndex) continue;
    std::int32_t& id = id_of_root[side[t]];  // first seen at the side's smallest face
    if (id == kNoEnvironment) id = next++;
    environment[t] = id;
  }
  return environment;
}

// Normals of crossing faces more than this far from parallel or opposite (degrees) make a steep
// crossing (check_sides_separated).
constexpr double kSteepCrossingDeg = 30.0;

// Step 5: the two faces of each thin pair lie in different environments.
absl::Status check_sides_separated(const std::vector<ThinPair>& pairs, const FaceFrames& frames,
                                   const std::vector<std::int32_t>& environment) {
  const double steep_cosine = cosine_of_degrees(kSteepCrossingDeg);
  for (const ThinPair& p : pairs) {
    if (environment[p.f] != environment[p.g]) continue;
    // The two sides of a thin region look nearly opposite ways, even where they cross. Faces
    // crossing at a steep angle are surfaces passing through each other (two solids given
    // overlapping, say): no environments can tell them apart; say so, naming a pair (not in
    // the paper).
    for (const ThinPair& q : pairs) {
      if (q.kind != PairKind::kCrossing) continue;
      const double c = dot(frames.normal[q.f], frames.normal[q.g]);
      if (std::abs(c) > steep_cosine) continue;
      return absl::InvalidArgumentError(absl::StrFormat(
          "automatic environments: triangles %d and %d cross at %.0f degrees: not the two sides "
          "of one thin region, which look nearly opposite ways, but surfaces that pass through "
          "each other (two solids given overlapping?), which environments cannot tell apart; "
          "give the boundary of the domain (the union of such solids)",
          q.f, q.g, std::acos(std::clamp(c, -1.0, 1.0)) * 180.0 / std::numbers::pi));
    }
    const std::string how =
        p.kind == PairKind::kCrossing
            ? std::string("cross")
            : absl::StrFormat("are %g apart, back to back", p.distance);
    return absl::InvalidArgumentError(absl::StrFormat(
        "automatic environments: triangles %d and %d %s, but they are joined through faces "
        "without a fold into the same side (environment %d), so the two sides of this thin "
        "region cannot be told apart; mark the environments as triangle tags (--envs tags)",
        p.f, p.g, how, environment[p.f]));
  }
  return absl::OkStatus();
}

}  // namespace

absl::StatusOr<DetectedEnvironments> detect_environments(const Mesh& front,
                                                         const AutoEnvironmentParams& params,
                                                         Progress& progress) {
  if (absl::Status status = check_auto_input(front, params); !status.ok()) return status;
  const FaceFrames frames = face_frames(front);
  absl::StatusOr<std::vector<ThinPair>> pairs = find_thin_pairs(front, frames, params, progress);
  if (!pairs.ok()) return pairs.status();
  std::vector<Index> side = group_sides(front, frames, *pairs, params.fold_angle_deg);
  grow_sides(front, frames, params.grow_rings, params.fold_angle_deg, side);

  DetectedEnvironments result;
  result.environments.face = number_sides(side);
  if (absl::Status status = check_sides_separated(*pairs, frames, result.environments.face);
      !status.ok()) {
    return status;
  }
  result.environments.point =
      point_environments(front.points.size(), front.triangles, result.environments.face);
  for (const ThinPair& p : *pairs) {
    ++(p.kind == PairKind::kCrossing ? result.stats.crossing_pairs : result.stats.close_pairs);
  }
  result.stats.marked_faces = std::count_if(side.begin(), side.end(),
                                            [](Index s) { return s != kInvalidIndex; });
  result.stats.environment_count = count_environments(result.environments.face);
  progress.report("environments", 1.0);
  return result;
}

}  // namespace afmesh
