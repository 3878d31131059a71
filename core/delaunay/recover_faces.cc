// Recovery of prescribed triangles by greedy flips and by refilling cavities (recover_faces.h).
#include "core/delaunay/recover_faces.h"

#include <algorithm>
#include <array>
#include <limits>
#include <optional>
#include <utility>

#include <Eigen/Dense>

#include "absl/container/flat_hash_map.h"
#include "absl/container/flat_hash_set.h"
#include "absl/functional/function_ref.h"
#include "core/geometry/intersect.h"
#include "core/geometry/predicates.h"
#include "core/geometry/vec.h"
#include "core/quality/mesh_topology.h"
#include "core/quality/optimise_steps.h"
#include "core/quality/ring_triangulation.h"
#include "core/quality/tet_complex.h"
#include "core/spatial/aabb_tree.h"
#include "core/spatial/box.h"

namespace afmesh {
namespace {

constexpr double kUnusable = -std::numeric_limits<double>::infinity();

std::pair<Index, Index> edge_key(Index a, Index b) { return {std::min(a, b), std::max(a, b)}; }

// True when triangle f (either orientation) is a face of a tet of c; `ball` is scratch.
bool has_face(const TetComplex& c, const Triangle& f, std::vector<Index>& ball) {
  c.ball(f[0], ball);
  for (Index t : ball)
    if (has_corner(c.tet(t), f[1]) && has_corner(c.tet(t), f[2])) return true;
  return false;
}

// True when (a, b) is an edge of a tet of c; `ball` is scratch.
bool has_edge(const TetComplex& c, Index a, Index b, std::vector<Index>& ball) {
  c.ball(a, ball);
  for (Index t : ball)
    if (has_corner(c.tet(t), b)) return true;
  return false;
}

// Scratch for flood_meeting.
struct FloodScratch {
  std::vector<Index> ball, todo;
  absl::flat_hash_set<Index> seen;
};

// Calls meeting(t) for each live tet t of c for which meets(t) holds (a tet meeting triangle f
// improperly), found by a flood through faces from the tets on f's corners, never testing a
// tet twice. Stops, returning false, as soon as meeting() returns false.
bool flood_meeting(const TetComplex& c, const Triangle& f, absl::FunctionRef<bool(Index)> meets,
                   absl::FunctionRef<bool(Index)> meeting, FloodScratch& s) {
  s.seen.clear();
  s.todo.clear();
  for (Index v : f) {
    c.ball(v, s.ball);
    for (Index t : s.ball)
      if (s.seen.insert(t).second) s.todo.push_back(t);
  }
  while (!s.todo.empty()) {
    const Index t = s.todo.back();
    s.todo.pop_back();
    if (!meets(t)) continue;
    if (!meeting(t)) return false;
    for (int k = 0; k < 4; ++k) {
      const Index u = c.neighbour(t, k);
      if (u != kInvalidIndex && s.seen.insert(u).second) s.todo.push_back(u);
    }
  }
  return true;
}

// The recovery of one prescribed triangle after another (recover_faces.h).
class Recovery {
 public:
  Recovery(TetComplex& c, std::span<const Triangle> faces, std::int64_t max_tests,
           CancelCheck* stop)
      : c_(c), max_tests_(max_tests), stop_(stop) {
    for (const Triangle& f : faces) {
      prescribed_.insert(sorted_triangle(f));
      for (int i = 0; i < 3; ++i) prescribed_edges_.insert(edge_key(f[i], f[(i + 1) % 3]));
    }
  }

  bool out_of_work() const { return tests_ >= max_tests_; }

  // Flips until f is a face, no flip reduces the tets meeting f, or the work is spent. True
  // when at least one flip was made.
  bool recover(const Triangle& f) {
    bool flipped = false;
    while (!has_face(c_, f, ball_) && !out_of_work()) {
      if (stop_ != nullptr && stop_->due()) {
        tests_ = max_tests_;
        break;
      }
      if (!flip_once(f)) break;
      flipped = true;
    }
    return flipped;
  }

 private:
  bool meets(const Tet& k, const Triangle& f) {
    ++tests_;
    return tet_triangle_intersect_improperly(c_.points(), k, f);
  }

  // The live tets that meet f improperly (tet_triangle_intersect_improperly).
  void tets_meeting(const Triangle& f) {
    meeting_.clear();
    flood_meeting(
        c_, f, [&](Index t) { return meets(c_.tet(t), f); },
        [&](Index t) {
          meeting_.push_back(t);
          return true;
        },
        flood_);
  }

  // A flip may not remove a prescribed triangle that is a face now.
  bool keeps_prescribed(const TopologyChange& flip) const {
    for (Index t : flip.old)
      for (int k = 0; k < 4; ++k) {
        const Triangle f = tet_face_key(c_.tet(t), k);
        if (!prescribed_.contains(f)) continue;
        bool kept = false;
        for (const Tet& n : flip.fresh)
          for (int j = 0; j < 4 && !kept; ++j) kept = tet_face_key(n, j) == f;
        if (!kept) return false;
      }
    return true;
  }

  // Makes the flip of the tets meeting f that most reduces their number (2-3 flips, edge
  // removals of edges not on the front, inside or on the boundary). False when none does.
  bool flip_once(const Triangle& f) {
    tets_meeting(f);
    // A new tet scores 1 when it misses f, 0 when it meets it, plus a little for its shape.
    const auto score = [&](const Tet& k) {
      return (meets(k, f) ? 0.0 : 1.0) + 1e-3 * tet_min_sine(c_.points(), k);
    };
    int best_gain = 0;
    bool best_on_boundary = false;
    const auto consider = [&](const TopologyChange& candidate, bool on_boundary) {
      int gain = 0;
      for (Index t : candidate.old) gain += meets(c_.tet(t), f) ? 1 : 0;
      for (const Tet& n : candidate.fresh) gain -= meets(n, f) ? 1 : 0;
      if (gain > best_gain && keeps_prescribed(candidate)) {
        best_gain = gain;
        best_ = candidate;
        best_on_boundary = on_boundary;
      }
    };
    edges_seen_.clear();
    for (Index t : meeting_) {
      for (int k = 0; k < 4; ++k)
        if (propose_face_removal(c_, t, k, score, kUnusable, candidate_))
          consider(candidate_, false);
      const Tet v = c_.tet(t);
      for (int i = 0; i < 4; ++i)
        for (int j = i + 1; j < 4; ++j) {
          const auto e = edge_key(v[i], v[j]);
          if (prescribed_edges_.contains(e) || !edges_seen_.insert(e).second) continue;
          if (c_.edge_ring(t, v[i], v[j], kMaxRingSize, ring_)) {
            if (propose_edge_removal(c_, ring_, score, kUnusable, candidate_))
              consider(candidate_, false);
          } else if (c_.edge_fan(t, v[i], v[j], kMaxRingSize - 1, ring_) &&
                     propose_boundary_edge_removal(c_, ring_, score, candidate_)) {
            consider(candidate_, true);
          }
        }
    }
    if (best_gain == 0) return false;
    created_.clear();
    return c_.replace(best_.old, best_.fresh, created_, best_on_boundary);
  }

  TetComplex& c_;
  std::int64_t max_tests_;
  CancelCheck* stop_;
  std::int64_t tests_ = 0;  // tet-triangle tests, the work bounded by max_tests
  absl::flat_hash_set<Triangle> prescribed_;
  absl::flat_hash_set<std::pair<Index, Index>> prescribed_edges_;
  std::vector<Index> ball_, meeting_, created_;
  FloodScratch flood_;
  absl::flat_hash_set<std::pair<Index, Index>> edges_seen_;
  EdgeRing ring_;
  TopologyChange candidate_, best_;
};


// A triangle bounding a region of a cavity, oriented outward from the region: a face of the
// cavity's boundary, or a front triangle inside the cavity as given (the region on its inner
// side) or reversed (on its outer side).
struct Side {
  Triangle f;
  enum Kind : std::uint8_t { kCavity, kFront, kReversed } kind;
  Index twin;  // for a front triangle, the Side of its other orientation; else kInvalidIndex
};

// The most triangles in a group, and tets in a cavity, that recover_faces_by_cavities refills
// at once: a larger cavity is left as it was.
constexpr std::size_t kMaxGroup = 256;
constexpr std::size_t kMaxCavity = 4096;

// A cavity that cannot be refilled is tried again grown by one layer of tets, up to this many.
constexpr int kMoreLayers = 5;

// The constraints whose fours kernel_point solves (C(16, 4) = 1820 small systems at most).
constexpr std::size_t kKernelCandidates = 16;

// The boxes of the triangles `which` of `front` (triangle_box).
std::vector<Box> boxes_of(const std::vector<Point>& x, std::span<const Triangle> front,
                          std::span<const Index> which) {
  std::vector<Box> boxes;
  for (Index i : which) boxes.push_back(triangle_box(x, front[static_cast<std::size_t>(i)]));
  return boxes;
}

// The recovery of groups of missing front triangles by refilling their cavities
// (recover_faces_by_cavities).
class CavityRecovery {
 public:
  CavityRecovery(TetComplex& c, std::span<const Triangle> front, std::span<const Index> missing,
                 const RegionFill& fill, CancelCheck* stop)
      : c_(c),
        front_(front),
        missing_(missing.begin(), missing.end()),
        missing_boxes_(boxes_of(c.points(), front, missing)),
        fill_(fill),
        stop_(stop) {
    for (std::size_t i = 0; i < front.size(); ++i) {
      const Triangle& f = front[i];
      index_of_.emplace(sorted_triangle(f), static_cast<Index>(i));
      for (int k = 0; k < 3; ++k)
        on_edge_[edge_key(f[k], f[(k + 1) % 3])].push_back(static_cast<Index>(i));
    }
  }

  // Recovers the missing triangle `seed` with the missing triangles joined to it through edges
  // that are not edges of the tets. True when they are faces afterwards.
  bool recover(Index seed) {
    if (has_face(c_, front_[static_cast<std::size_t>(seed)], ball_)) return true;
    if (tried_.contains(seed)) return false;  // its group failed already
    bool done = false;
    if (gather_group(seed))
      for (int layers = 0; layers <= kMoreLayers && !done; ++layers) done = refill(layers);
    for (Index g : group_) tried_.insert(g);
    return done;
  }

 private:
  // Refills the group's cavity grown by `layers` layers of tets. True when the group's
  // triangles are faces afterwards.
  bool refill(int layers) {
    if (!gather_cavity(layers) || !gather_sides() || !pair_sides()) return false;
    fresh_.clear();
    std::vector<Index> shell;
    for (std::size_t s = 0; s < sides_.size(); ++s) {
      if (sides_[s].kind != Side::kFront || shell_of_[s] != kInvalidIndex) continue;
      if (!collect_shell(static_cast<Index>(s), shell) || !fill_shell(shell)) {
        drop_new_points();
        return false;
      }
    }
    created_.clear();
    if (!c_.replace(cavity_, fresh_, created_, /*boundary_may_change=*/true)) {
      drop_new_points();
      return false;
    }
    added_.clear();  // used by the new tets: kept
    for (Index g : group_)
      if (!has_face(c_, front_[static_cast<std::size_t>(g)], ball_)) return false;
    return true;
  }

  const Point& at(Index v) const { return c_.point(v); }

  // The missing triangles joined to `seed` through edges no tet has. False when there are
  // more than kMaxGroup.
  bool gather_group(Index seed) {
    group_.assign(1, seed);
    in_group_.clear();
    in_group_.insert(seed);
    for (std::size_t i = 0; i < group_.size(); ++i) {
      const Triangle f = front_[static_cast<std::size_t>(group_[i])];
      for (int k = 0; k < 3; ++k) {
        const Index a = f[k], b = f[(k + 1) % 3];
        if (has_edge(c_, a, b, ball_)) continue;
        for (Index g : on_edge_[edge_key(a, b)])
          if (in_group_.insert(g).second) group_.push_back(g);
      }
      if (group_.size() > kMaxGroup) return false;
    }
    return true;
  }

  // The cavity: the tets that meet a triangle of the group improperly, found by floods through
  // faces from the tets on the triangles' corners; with every missing triangle that meets one
  // of them joined to the group (and its tets to the cavity), since every front triangle
  // through the cavity must bound its regions, or a region taken for outside could hold some
  // of the inside (a face of the tets meets no tet improperly: such a triangle is missing);
  // then grown by `layers` layers of the tets across its faces, each joining its crossing
  // triangles likewise. False when the cavity grows over kMaxCavity tets, or the group over
  // kMaxGroup triangles, or the caller cancels.
  bool gather_cavity(int layers) {
    cavity_.clear();
    in_cavity_.clear();
    std::size_t flooded = 0, checked = 0;
    for (int grown = 0;; ++grown) {
      while (flooded < group_.size()) {
        for (; flooded < group_.size(); ++flooded) {
          if (!flood(front_[static_cast<std::size_t>(group_[flooded])])) return false;
        }
        for (; checked < cavity_.size(); ++checked)
          if (!join_crossing(cavity_[checked])) return false;
      }
      if (grown == layers) return true;
      // One layer more: the tets across the cavity's faces.
      const std::size_t size = cavity_.size();
      for (std::size_t i = 0; i < size; ++i)
        for (int k = 0; k < 4; ++k) {
          const Index u = c_.neighbour(cavity_[i], k);
          if (u != kInvalidIndex && in_cavity_.insert(u).second) cavity_.push_back(u);
        }
      if (cavity_.size() > kMaxCavity) return false;
      for (; checked < cavity_.size(); ++checked)
        if (!join_crossing(cavity_[checked])) return false;
    }
  }

  // Joins to the group the missing triangles that meet tet t improperly. False when the group
  // grows over kMaxGroup or the caller cancels.
  bool join_crossing(Index t) {
    if (stop_ != nullptr && stop_->due()) return false;
    const Tet& k = c_.tet(t);
    bool within = true;
    missing_boxes_.for_each_overlap(tet_box(c_.points(), k), [&](Index i) {
      const Index g = missing_[static_cast<std::size_t>(i)];
      if (!within || in_group_.contains(g) ||
          !tet_triangle_intersect_improperly(c_.points(), k, front_[static_cast<std::size_t>(g)]))
        return;
      in_group_.insert(g);
      group_.push_back(g);
      within = group_.size() <= kMaxGroup;
    });
    return within;
  }

  // Adds the tets meeting f improperly to the cavity. False when it grows over kMaxCavity.
  bool flood(const Triangle& f) {
    return flood_meeting(
        c_, f,
        [&](Index t) { return tet_triangle_intersect_improperly(c_.points(), c_.tet(t), f); },
        [&](Index t) {
          if (in_cavity_.insert(t).second) cavity_.push_back(t);
          return cavity_.size() <= kMaxCavity;
        },
        flood_);
  }

  // The sides of the cavity's regions: its boundary faces, outward, and the front triangles
  // inside it (the group's, and front triangles that are faces of two tets of the cavity) in
  // both orientations. False when a front triangle inside is on the cavity's boundary too.
  bool gather_sides() {
    sides_.clear();
    absl::flat_hash_set<Index> inside;  // front triangles inside the cavity
    for (Index g : group_) inside.insert(g);
    for (Index t : cavity_)
      for (int k = 0; k < 4; ++k) {
        const Index u = c_.neighbour(t, k);
        const Triangle f = tet_face(c_.tet(t), k);
        if (u == kInvalidIndex || !in_cavity_.contains(u)) {
          sides_.push_back({f, Side::kCavity, kInvalidIndex});
          continue;
        }
        if (const auto it = index_of_.find(sorted_triangle(f)); it != index_of_.end())
          inside.insert(it->second);
      }
    std::vector<Index> order(inside.begin(), inside.end());
    std::sort(order.begin(), order.end());  // deterministic, whatever the hashing
    for (Index i : order) {
      const Triangle& f = front_[static_cast<std::size_t>(i)];
      const auto s = static_cast<Index>(sides_.size());
      sides_.push_back({f, Side::kFront, s + 1});
      sides_.push_back({{f[0], f[2], f[1]}, Side::kReversed, s});
    }
    return true;
  }

  // Pairs the sides across each of their edges: at an edge, each side running a -> b is paired
  // with one running b -> a (so the regions' boundaries are closed and consistently oriented),
  // never with its own reverse. Where that alone does not decide (more than two sides each way,
  // or two and either pairing allowed), by their order around the edge (pair_around). False
  // where the sides do not bound regions.
  bool pair_sides() {
    absl::flat_hash_map<std::pair<Index, Index>, std::vector<Index>> running;  // a -> b: sides
    for (std::size_t s = 0; s < sides_.size(); ++s)
      for (int k = 0; k < 3; ++k)
        running[{sides_[s].f[k], sides_[s].f[(k + 1) % 3]}].push_back(static_cast<Index>(s));
    partner_.assign(3 * sides_.size(), kInvalidIndex);
    shell_of_.assign(sides_.size(), kInvalidIndex);
    for (const auto& [edge, forward] : running) {
      if (edge.first > edge.second) continue;  // each edge once, from its smaller end
      const auto back = running.find({edge.second, edge.first});
      if (back == running.end() || back->second.size() != forward.size()) return false;
      const std::vector<Index>& backward = back->second;
      const auto twins = [&](Index s, Index r) { return sides_[s].twin == r; };
      std::array<Index, 2> match;  // backward[match[i]] pairs with forward[i]
      if (forward.size() == 1) {
        if (twins(forward[0], backward[0])) return false;
        match = {0, 0};
      } else if (forward.size() == 2) {
        const bool straight = !twins(forward[0], backward[0]) && !twins(forward[1], backward[1]);
        const bool crossed = !twins(forward[0], backward[1]) && !twins(forward[1], backward[0]);
        if (straight == crossed) {  // both (a side of the cavity's own pinch) or neither
          if (!pair_around(edge.first, edge.second, forward, backward)) return false;
          continue;
        }
        match = straight ? std::array<Index, 2>{0, 1} : std::array<Index, 2>{1, 0};
      } else {
        if (!pair_around(edge.first, edge.second, forward, backward)) return false;
        continue;
      }
      for (std::size_t i = 0; i < forward.size(); ++i) {
        const Index s = forward[i], r = backward[static_cast<std::size_t>(match[i])];
        partner_[3 * s + edge_slot(s, edge.first, edge.second)] = r;
        partner_[3 * r + edge_slot(r, edge.second, edge.first)] = s;
      }
    }
    return true;
  }

  // Pairs the sides at edge (u, v) by their order around it: `forward` run u -> v, `backward`
  // v -> u. Around the axis u -> v, a side running u -> v has its region just before its third
  // corner (turning the negative way), one running v -> u just after; two sides next to each
  // other that both face the wedge between them are paired, and a wedge that only one of its
  // sides faces means the sides do not bound regions. The order is exact (orient3d) except for
  // telling sides in the plane of the first one apart (same way or opposite), and a tie between
  // two sides at one angle fails.
  bool pair_around(Index u, Index v, const std::vector<Index>& forward,
                   const std::vector<Index>& backward) {
    struct Around {
      Index side, w;
      bool forward;
      int half;  // 0: on the first side's half-plane; 1: (0, pi); 2: opposite it; 3: (pi, 2 pi)
    };
    std::vector<Around> around;
    const auto third = [&](Index s) {
      for (Index w : sides_[static_cast<std::size_t>(s)].f)
        if (w != u && w != v) return w;
      return kInvalidIndex;
    };
    for (Index s : forward) around.push_back({s, third(s), true, 0});
    for (Index s : backward) around.push_back({s, third(s), false, 0});
    const Index w0 = around.front().w;
    const Point axis = sub(at(v), at(u));
    const auto across = [&](Index w) {  // the part of w - u across the axis
      const Point d = sub(at(w), at(u));
      return sub(d, scale(axis, dot(d, axis) / dot(axis, axis)));
    };
    for (Around& a : around) {
      if (a.w == w0) continue;
      const int o = orient3d(at(u), at(v), at(w0), at(a.w));
      a.half = o > 0 ? 1 : o < 0 ? 3 : dot(across(w0), across(a.w)) > 0 ? 0 : 2;
    }
    bool tie = false;
    std::sort(around.begin(), around.end(), [&](const Around& x, const Around& y) {
      if (x.half != y.half) return x.half < y.half;
      if (x.w == y.w) return x.forward && !y.forward;  // twins: the one running u -> v first
      const int o = x.half % 2 == 1 ? orient3d(at(u), at(v), at(x.w), at(y.w)) : 0;
      if (o == 0) {
        tie = true;
        return x.w < y.w;
      }
      return o > 0;
    });
    if (tie) return false;
    for (std::size_t i = 0; i < around.size(); ++i) {
      const Around& x = around[i];
      const Around& y = around[(i + 1) % around.size()];
      const bool x_faces = !x.forward, y_faces = y.forward;
      if (x_faces != y_faces) return false;
      if (!x_faces) continue;
      partner_[3 * static_cast<std::size_t>(x.side) + edge_slot(x.side, v, u)] = y.side;
      partner_[3 * static_cast<std::size_t>(y.side) + edge_slot(y.side, u, v)] = x.side;
    }
    return true;
  }

  // The position k of the edge a -> b in side s (f[k] = a, f[k + 1] = b).
  int edge_slot(Index s, Index a, Index b) const {
    const Triangle& f = sides_[static_cast<std::size_t>(s)].f;
    for (int k = 0; k < 3; ++k)
      if (f[k] == a && f[(k + 1) % 3] == b) return k;
    return -1;
  }

  // The closed surface of paired sides through side `seed` (a front triangle as given): the
  // boundary of one region on the inner side of the front. False when it holds a front
  // triangle reversed too (the region would be on both sides of the front).
  bool collect_shell(Index seed, std::vector<Index>& shell) {
    shell.assign(1, seed);
    shell_of_[static_cast<std::size_t>(seed)] = seed;
    for (std::size_t i = 0; i < shell.size(); ++i) {
      const Index s = shell[i];
      if (sides_[static_cast<std::size_t>(s)].kind == Side::kReversed) return false;
      for (int k = 0; k < 3; ++k) {
        const Index r = partner_[3 * static_cast<std::size_t>(s) + k];
        if (r == kInvalidIndex) return false;
        if (shell_of_[static_cast<std::size_t>(r)] != kInvalidIndex) continue;
        shell_of_[static_cast<std::size_t>(r)] = seed;
        shell.push_back(r);
      }
    }
    return true;
  }

  // True when every side of `shell` not on point x has x strictly on its inner side.
  bool sees_all(const std::vector<Index>& shell, const Point& x, Index v) const {
    for (Index s : shell) {
      const Triangle& f = sides_[static_cast<std::size_t>(s)].f;
      if (v != kInvalidIndex && has_corner(f, v)) continue;
      if (orient3d(at(f[0]), at(f[1]), at(f[2]), x) >= 0) return false;
    }
    return true;
  }

  // The point deepest inside the sides `shell` (a region's, or some of them), and its depth:
  // the point that maximises the smallest distance to the sides' planes (the linear programme:
  // largest t with n_i . x + t <= n_i . c_i, unit outward normals n_i through corners c_i),
  // negative when no point sees every side from inside (the region's kernel is empty). Its
  // optimum is a vertex where four constraints are tight: a subgradient ascent from the centroid
  // of the corners finds the neighbourhood, then every four of the kKernelCandidates tightest
  // constraints there are solved and the best point is kept. Nothing for a degenerate side.
  std::optional<std::pair<Point, double>> deepest_point(const std::vector<Index>& shell) const {
    std::vector<Point> normal;
    std::vector<double> offset;
    Point centre{0, 0, 0};
    for (Index s : shell) {
      const Triangle& f = sides_[static_cast<std::size_t>(s)].f;
      const Point n = cross(sub(at(f[1]), at(f[0])), sub(at(f[2]), at(f[0])));
      const double length = norm(n);
      if (!(length > 0)) return std::nullopt;
      normal.push_back(scale(n, 1.0 / length));  // outward
      offset.push_back(dot(normal.back(), at(f[0])));
      centre = add(centre, scale(add(at(f[0]), add(at(f[1]), at(f[2]))), 1.0 / 3.0));
    }
    centre = scale(centre, 1.0 / static_cast<double>(shell.size()));
    double extent = 0;
    for (Index s : shell)
      for (Index v : sides_[static_cast<std::size_t>(s)].f)
        extent = std::max(extent, distance(at(v), centre));
    const auto depth_at = [&](const Point& x) {  // smallest distance inside, negative outside
      double depth = std::numeric_limits<double>::infinity();
      for (std::size_t i = 0; i < normal.size(); ++i)
        depth = std::min(depth, offset[i] - dot(normal[i], x));
      return depth;
    };
    Point x = centre, best = centre;
    double best_depth = depth_at(centre);
    constexpr int kSteps = 200;
    for (int step = 0; step < kSteps; ++step) {
      std::size_t nearest = 0;
      double depth = std::numeric_limits<double>::infinity();
      for (std::size_t i = 0; i < normal.size(); ++i)
        if (const double d = offset[i] - dot(normal[i], x); d < depth) {
          depth = d;
          nearest = i;
        }
      if (depth > best_depth) {
        best_depth = depth;
        best = x;
      }
      x = sub(x, scale(normal[nearest], extent * 0.25 / (1.0 + step)));
    }
    // The vertices of the programme among the constraints tightest at the best point so far.
    std::vector<std::size_t> tight(normal.size());
    for (std::size_t i = 0; i < tight.size(); ++i) tight[i] = i;
    const auto slack = [&](std::size_t i) { return offset[i] - dot(normal[i], best); };
    std::sort(tight.begin(), tight.end(), [&](std::size_t i, std::size_t j) {
      return slack(i) < slack(j) || (slack(i) == slack(j) && i < j);
    });
    tight.resize(std::min(tight.size(), kKernelCandidates));
    const std::size_t m = tight.size();
    for (std::size_t a = 0; a < m; ++a)
      for (std::size_t b = a + 1; b < m; ++b)
        for (std::size_t c = b + 1; c < m; ++c)
          for (std::size_t d = c + 1; d < m; ++d) {
            Eigen::Matrix4d lhs;
            Eigen::Vector4d rhs;
            const std::size_t rows[4] = {tight[a], tight[b], tight[c], tight[d]};
            for (int r = 0; r < 4; ++r) {
              const std::size_t i = rows[r];
              lhs.row(r) << normal[i][0], normal[i][1], normal[i][2], 1.0;
              rhs[r] = offset[i];
            }
            const Eigen::FullPivLU<Eigen::Matrix4d> lu(lhs);
            if (lu.rank() < 4) continue;
            const Eigen::Vector4d v = lu.solve(rhs);
            if (!(v[3] > best_depth)) continue;
            const Point y{v[0], v[1], v[2]};
            if (const double depth = depth_at(y); depth > best_depth) {
              best_depth = depth;
              best = y;
            }
          }
    return std::pair<Point, double>{best, best_depth};
  }

  // Fills the region bounded by `shell` with the tets joining its sides to one point that sees
  // them all from inside: one of its corners if one does, else a new point in its kernel.
  bool fill_shell(const std::vector<Index>& shell) {
    std::vector<Index> corners;
    for (Index s : shell)
      for (Index v : sides_[static_cast<std::size_t>(s)].f)
        if (std::find(corners.begin(), corners.end(), v) == corners.end()) corners.push_back(v);
    Index apex = kInvalidIndex;
    for (Index v : corners)
      if (sees_all(shell, at(v), v)) {
        apex = v;
        break;
      }
    if (apex == kInvalidIndex) {
      const std::optional<std::pair<Point, double>> deepest = deepest_point(shell);
      if (!deepest) return false;
      if (!(deepest->second > 0) || !sees_all(shell, deepest->first, kInvalidIndex))
        return fill_otherwise(shell, corners, deepest->first);
      apex = c_.add_point(deepest->first);
      added_.push_back(apex);
    }
    for (Index s : shell) {
      const Triangle& f = sides_[static_cast<std::size_t>(s)].f;
      if (!has_corner(f, apex)) fresh_.push_back({apex, f[0], f[1], f[2]});
    }
    return true;
  }

  // Fills the region bounded by `shell` (with its corners `corners`) by fill_, if given, with
  // `inner` offered as a point inside too (the deepest point: it changes the region's Delaunay
  // tetrahedralisation, and the fill leaves it out where it is not inside). Only the new points
  // the fill's tets use are kept.
  bool fill_otherwise(const std::vector<Index>& shell, const std::vector<Index>& corners,
                      const Point& inner) {
    if (!fill_) return false;
    std::vector<Point> x;
    for (Index v : corners) x.push_back(at(v));
    x.push_back(inner);
    std::vector<Triangle> sides;
    for (Index s : shell) {
      Triangle f = sides_[static_cast<std::size_t>(s)].f;
      for (Index& v : f)
        v = static_cast<Index>(std::find(corners.begin(), corners.end(), v) - corners.begin());
      sides.push_back(f);
    }
    const std::optional<std::vector<Tet>> tets = fill_(x, sides);
    if (!tets) return false;
    std::vector<Index> global(x.size(), kInvalidIndex);
    std::copy(corners.begin(), corners.end(), global.begin());
    for (const Tet& t : *tets)
      for (Index v : t) {
        Index& g = global[static_cast<std::size_t>(v)];
        if (g != kInvalidIndex) continue;
        g = c_.add_point(x[static_cast<std::size_t>(v)]);
        added_.push_back(g);
      }
    for (const Tet& t : *tets)
      fresh_.push_back({global[static_cast<std::size_t>(t[0])],
                        global[static_cast<std::size_t>(t[1])],
                        global[static_cast<std::size_t>(t[2])],
                        global[static_cast<std::size_t>(t[3])]});
    return true;
  }

  // Takes back the points added for a cavity that was not refilled (the last added first).
  void drop_new_points() {
    for (; !added_.empty(); added_.pop_back()) c_.drop_last_point();
  }

  TetComplex& c_;
  std::span<const Triangle> front_;
  std::vector<Index> missing_;  // the triangles missing before the first cavity
  AabbTree missing_boxes_;      // their boxes, in the order of missing_
  const RegionFill& fill_;
  CancelCheck* stop_;
  absl::flat_hash_set<Index> tried_;  // in a group that could not be refilled
  absl::flat_hash_map<Triangle, Index> index_of_;  // front triangle by its sorted corners
  absl::flat_hash_map<std::pair<Index, Index>, std::vector<Index>> on_edge_;
  std::vector<Index> group_, cavity_, ball_, added_;
  absl::flat_hash_set<Index> in_group_, in_cavity_;
  FloodScratch flood_;
  std::vector<Side> sides_;
  std::vector<Index> partner_;   // 3 per side: the side paired across its edge k
  std::vector<Index> shell_of_;  // per side: the seed of its shell, or kInvalidIndex
  std::vector<Tet> fresh_;
  std::vector<Index> created_;
};
}  // namespace

std::vector<Index> recover_faces_by_flips(std::span<const Point> points, std::vector<Tet>& tets,
                                          std::span<const Triangle> faces,
                                          std::int64_t max_tests, CancelCheck* stop) {
  Mesh m;
  m.points.assign(points.begin(), points.end());
  m.tets = std::move(tets);
  absl::StatusOr<TetComplex> c = TetComplex::build(m);
  std::vector<Index> missing;
  if (!c.ok()) {  // not a tetrahedralisation: nothing is recovered
    tets = std::move(m.tets);
    for (std::size_t i = 0; i < faces.size(); ++i) missing.push_back(static_cast<Index>(i));
    return missing;
  }
  Recovery recovery(*c, faces, max_tests, stop);
  for (bool progress = true; progress && !recovery.out_of_work();) {
    progress = false;
    for (const Triangle& f : faces) progress = recovery.recover(f) || progress;
  }
  std::vector<Index> ball;
  for (std::size_t i = 0; i < faces.size(); ++i)
    if (!has_face(*c, faces[i], ball)) missing.push_back(static_cast<Index>(i));
  c->compact();
  tets = std::move(m.tets);
  return missing;
}

std::vector<Index> recover_faces_by_cavities(std::vector<Point>& points, std::vector<Tet>& tets,
                                             std::span<const Triangle> front,
                                             std::span<const Index> missing, CancelCheck* stop,
                                             const RegionFill& fill) {
  Mesh m;
  m.points = std::move(points);
  m.tets = std::move(tets);
  absl::StatusOr<TetComplex> c = TetComplex::build(m);
  std::vector<Index> still(missing.begin(), missing.end());
  if (!c.ok()) {
    points = std::move(m.points);
    tets = std::move(m.tets);
    return still;
  }
  CavityRecovery recovery(*c, front, missing, fill, stop);
  still.clear();
  for (Index i : missing) {
    if (stop != nullptr && stop->due()) {
      still.push_back(i);
      continue;
    }
    recovery.recover(i);
  }
  std::vector<Index> ball;
  for (Index i : missing)
    if (!has_face(*c, front[static_cast<std::size_t>(i)], ball)) still.push_back(i);
  if (!still.empty()) {
    // Where an outer region was left empty, a point's tets may no longer be joined through
    // faces (the region pinches there), and its ball, a walk through faces, misses some: the
    // triangles not found so are looked for among every tet's faces.
    absl::flat_hash_set<Triangle> faces;
    for (Index t = 0; t < c->slots(); ++t)
      if (c->alive(t))
        for (int k = 0; k < 4; ++k) faces.insert(tet_face_key(c->tet(t), k));
    std::erase_if(still, [&](Index i) {
      return faces.contains(sorted_triangle(front[static_cast<std::size_t>(i)]));
    });
  }
  std::sort(still.begin(), still.end());
  still.erase(std::unique(still.begin(), still.end()), still.end());
  c->compact();
  points = std::move(m.points);
  tets = std::move(m.tets);
  return still;
}

}  // namespace afmesh
