#include "core/quality/optimise.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <utility>
#include <vector>

#include "core/geometry/vec.h"
#include "core/quality/optimise_steps.h"
#include "core/quality/tet_complex.h"

namespace afmesh {

double tet_min_sine(const Point& a, const Point& b, const Point& c, const Point& d) {
  // The value is scale-free: edges are scaled by 1 / |b - a| so that the squares below neither
  // overflow nor underflow for any sensible coordinates.
  const double ab = norm(sub(b, a));
  if (!(ab > 0)) return 0.0;
  const double s = 1.0 / ab;
  const Point u = scale(sub(b, a), s), v = scale(sub(c, a), s), w = scale(sub(d, a), s);
  // N[i]: squared twice-area of the face opposite corner i. The sine of the dihedral angle at
  // edge (i, j), between the faces opposite k and l, is det · |e_ij| / sqrt(N[k] N[l]).
  const Point vu = sub(v, u), wu = sub(w, u);
  const double area2[4] = {squared_norm(cross(vu, wu)), squared_norm(cross(v, w)),
                           squared_norm(cross(u, w)), squared_norm(cross(u, v))};
  if (!(area2[0] > 0 && area2[1] > 0 && area2[2] > 0 && area2[3] > 0)) return 0.0;
  const double det = dot(cross(u, v), w);
  const double r2[6] = {1.0 / (area2[2] * area2[3]),  // |u|^2 = 1
                        squared_norm(v) / (area2[1] * area2[3]),
                        squared_norm(w) / (area2[1] * area2[2]),
                        squared_norm(vu) / (area2[0] * area2[3]),
                        squared_norm(wu) / (area2[0] * area2[2]),
                        squared_norm(sub(w, v)) / (area2[0] * area2[1])};
  const auto [lo, hi] = std::minmax_element(r2, r2 + 6);
  return det >= 0 ? det * std::sqrt(*lo) : det * std::sqrt(*hi);
}

namespace {

constexpr int kCancelCheckInterval = 256;
constexpr int kEdges[6][2] = {{0, 1}, {0, 2}, {0, 3}, {1, 2}, {1, 3}, {2, 3}};

// A tet to work on, ordered worst first, then by slot. `failed_at` is the change count when
// every step last failed on it (-1: not tried yet); it is tried again only once something
// around it has changed since.
struct BadTet {
  double quality;
  Index tet;
  std::int64_t failed_at = -1;
  bool operator<(const BadTet& o) const {
    return quality < o.quality || (quality == o.quality && tet < o.tet);
  }
};

void consider(const TopologyChange& candidate, TopologyChange& best) {
  if (candidate.quality > best.quality) best = candidate;
}

class Optimiser {
 public:
  Optimiser(TetComplex& c, Index fixed_points, const OptimiseParams& params)
      : c_(c), fixed_(fixed_points), params_(params),
        threshold_(std::sin(params.target_min_dihedral_deg * std::numbers::pi / 180.0)),
        touched_(c.points().size(), -1) {}

  double quality(Index t) const { return tet_min_sine(c_.points(), c_.tet(t)); }
  bool bad(double quality) const { return quality < threshold_; }
  void allow_splits(bool allowed) { splits_allowed_ = allowed; }

  // Laplacian smoothing over every movable point, kept where the worst tet around it improves.
  absl::Status smoothing_sweep(Progress& progress);
  // The tets under the target, worst first.
  // The tets under the threshold, worst first; empty once `stop` finds the call cancelled.
  std::vector<BadTet> bad_tets(CancelCheck& stop) const;
  // One round over `work` (sorted); the tets to look at in the next round are appended to
  // `next`. Returns CANCELLED when asked to stop.
  absl::Status round(const std::vector<BadTet>& work, std::vector<BadTet>& next, bool& changed,
                     Progress& progress);

  OptimiseStats stats;

 private:
  // The best change of edge removal and 2-3 flip around tet t, made; its tets in created_.
  bool change_topology(Index t);
  // Smooths the movable corners of tet t; the tets around a moved point that are under the
  // target are appended to `next`.
  bool smooth_corners(Index t, std::vector<BadTet>& next);
  // The edge contraction of tet t (one movable end merged into the other) whose new worst tet
  // is best, in best_, kept_ and gone_; and its making, which smooths the point kept (the tets
  // around it in created_).
  bool propose_contraction(Index t);
  bool make_contraction();
  // The split of an interior edge of tet t whose new worst tet is best, in best_split_; and its
  // making (the new tets in created_).
  bool propose_split(Index t);
  bool make_split();
  // Of the best contraction and the best split (in the rounds that split), the one whose new
  // worst tet is better, made.
  bool contract_or_split(Index t);
  // Records a change to `tets` (their points are touched) and queues those under the target.
  void changed(const std::vector<Index>& tets, std::vector<BadTet>& next);
  // True when a tet at one of t's points changed after `since`.
  bool touched_since(Index t, std::int64_t since) const {
    for (Index p : c_.tet(t))
      if (touched_[p] > since) return true;
    return false;
  }

  TetComplex& c_;
  Index fixed_;
  const OptimiseParams& params_;
  bool splits_allowed_ = true;  // this round may split edges (OptimiseParams::split_passes)
  double threshold_;
  std::vector<std::int64_t> touched_;  // per point: the change count of the last change at it
  std::int64_t changes_ = 0;
  EdgeRing ring_;
  TopologyChange candidate_, best_;
  EdgeSplit split_, best_split_;
  std::vector<Index> ball_;
  Index kept_ = kInvalidIndex, gone_ = kInvalidIndex;  // the contraction in best_
  SmoothingScratch smoothing_;
  std::vector<Index> created_;
};

absl::Status Optimiser::smoothing_sweep(Progress& progress) {
  for (Index v = fixed_; v < static_cast<Index>(c_.points().size()); ++v) {
    if ((v & 511) == 0 && progress.cancelled())
      return absl::CancelledError("mesh optimisation cancelled");
    stats.points_moved += smooth_point(c_, v, fixed_, /*climb_too=*/false, smoothing_);
  }
  return absl::OkStatus();
}

std::vector<BadTet> Optimiser::bad_tets(CancelCheck& stop) const {
  std::vector<BadTet> bad;
  for (Index t = 0; t < c_.slots(); ++t) {
    if (stop.due()) return {};
    if (!c_.alive(t)) continue;
    const double q = quality(t);
    if (q < threshold_) bad.push_back({q, t});
  }
  std::sort(bad.begin(), bad.end());
  return bad;
}

void Optimiser::changed(const std::vector<Index>& tets, std::vector<BadTet>& next) {
  ++changes_;
  touched_.resize(c_.points().size(), -1);  // an edge split adds a point
  for (Index t : tets) {
    for (Index p : c_.tet(t)) touched_[p] = changes_;
    if (const double q = quality(t); bad(q)) next.push_back({q, t});
  }
}

bool Optimiser::change_topology(Index t) {
  best_.quality = -std::numeric_limits<double>::infinity();
  const Tet k = c_.tet(t);
  if (params_.edge_removal)
    for (const auto& e : kEdges)
      if (propose_edge_removal(c_, t, k[e[0]], k[e[1]], params_.max_edge_ring, ring_, candidate_))
        consider(candidate_, best_);
  if (params_.face_removal)
    for (int corner = 0; corner < 4; ++corner)
      if (propose_face_removal(c_, t, corner, candidate_)) consider(candidate_, best_);
  if (best_.fresh.empty() || best_.quality == -std::numeric_limits<double>::infinity())
    return false;
  created_.clear();
  if (!c_.replace(best_.old, best_.fresh, created_)) return false;
  if (best_.fresh.size() == 3 && best_.old.size() == 2) {
    ++stats.flips_23;
  } else {
    ++stats.edge_removals;
    stats.flips_32 += best_.old.size() == 3;
  }
  return true;
}

bool Optimiser::smooth_corners(Index t, std::vector<BadTet>& next) {
  bool moved = false;
  const Tet k = c_.tet(t);
  for (Index v : k) {
    if (!smooth_point(c_, v, fixed_, /*climb_too=*/true, smoothing_)) continue;
    moved = true;
    ++stats.points_moved;
    changed(smoothing_.ball, next);
  }
  return moved;
}

bool Optimiser::propose_contraction(Index t) {
  const Tet k = c_.tet(t);
  best_.quality = -std::numeric_limits<double>::infinity();
  kept_ = gone_ = kInvalidIndex;
  for (const auto& e : kEdges)
    for (int way = 0; way < 2; ++way) {
      const Index a = k[e[way]], b = k[e[1 - way]];
      if (propose_edge_contraction(c_, t, a, b, fixed_, ball_, candidate_) &&
          candidate_.quality > best_.quality) {
        best_ = candidate_;
        kept_ = a;
        gone_ = b;
      }
    }
  return gone_ != kInvalidIndex;
}

bool Optimiser::make_contraction() {
  created_.clear();
  if (!c_.replace(best_.old, best_.fresh, created_, /*boundary_may_change=*/false, gone_))
    return false;
  ++stats.edge_contractions;
  // The tets around the point kept, its new tets among them, as smoothing leaves them.
  if (smooth_point(c_, kept_, fixed_, /*climb_too=*/true, smoothing_)) ++stats.points_moved;
  c_.ball(kept_, created_);
  return true;
}

bool Optimiser::propose_split(Index t) {
  const Tet k = c_.tet(t);
  best_split_.quality = -std::numeric_limits<double>::infinity();
  for (const auto& e : kEdges)
    if (propose_edge_split(c_, t, k[e[0]], k[e[1]], params_.max_edge_ring, split_) &&
        split_.quality > best_split_.quality)
      best_split_ = split_;
  return best_split_.quality > -std::numeric_limits<double>::infinity();
}

bool Optimiser::make_split() {
  created_.clear();
  if (!make_edge_split(c_, best_split_, fixed_, smoothing_, created_)) return false;
  ++stats.edge_splits;
  return true;
}

bool Optimiser::contract_or_split(Index t) {
  const bool contraction = params_.edge_contraction && propose_contraction(t);
  const bool split = params_.edge_split && splits_allowed_ && propose_split(t);
  if (contraction && (!split || best_.quality >= best_split_.quality)) return make_contraction();
  return split && make_split();
}

absl::Status Optimiser::round(const std::vector<BadTet>& work, std::vector<BadTet>& next,
                              bool& any_change, Progress& progress) {
  std::int64_t visited = 0;
  for (const BadTet& w : work) {
    if (++visited % kCancelCheckInterval == 0 && progress.cancelled())
      return absl::CancelledError("mesh optimisation cancelled");
    if (!c_.alive(w.tet) || !bad(quality(w.tet))) continue;
    if (w.failed_at >= 0 && !touched_since(w.tet, w.failed_at)) {
      next.push_back(w);  // nothing new around it: not worth another try yet
      continue;
    }
    const std::int64_t before = changes_;
    if (change_topology(w.tet)) {
      changed(created_, next);
    } else if (params_.smoothing && smooth_corners(w.tet, next) && !bad(quality(w.tet))) {
      // smoothed enough
    } else if (c_.alive(w.tet) && bad(quality(w.tet)) && contract_or_split(w.tet)) {
      changed(created_, next);
    } else if (c_.alive(w.tet) && bad(quality(w.tet))) {
      next.push_back({quality(w.tet), w.tet, changes_});
    }
    any_change = any_change || changes_ > before;
  }
  return absl::OkStatus();
}

// The work of the next round from the entries made in this one. Slots are reused, so each live
// tet under the target is kept once, with its current quality and the earliest failure mark among
// its entries (-1 when it is new, so that it is tried).
std::vector<BadTet> next_work(const TetComplex& c, const Optimiser& opt,
                              const std::vector<BadTet>& entries) {
  std::vector<BadTet> work;
  for (const BadTet& b : entries)
    if (c.alive(b.tet) && opt.bad(opt.quality(b.tet)))
      work.push_back({opt.quality(b.tet), b.tet, b.failed_at});
  std::sort(work.begin(), work.end(), [](const BadTet& x, const BadTet& y) {
    return x.tet < y.tet || (x.tet == y.tet && x.failed_at < y.failed_at);
  });
  std::size_t kept = 0;
  for (std::size_t i = 0; i < work.size(); ++i)
    if (kept == 0 || work[kept - 1].tet != work[i].tet) work[kept++] = work[i];
  work.resize(kept);
  std::sort(work.begin(), work.end());
  return work;
}

}  // namespace

absl::StatusOr<OptimiseStats> optimise_tets(Mesh& mesh, Index fixed_points,
                                            const OptimiseParams& params, Progress& progress) {
  absl::StatusOr<TetComplex> complex = TetComplex::build(mesh, progress);
  if (!complex.ok()) return complex.status();
  Optimiser opt(*complex, fixed_points, params);
  absl::Status status;
  for (int sweep = 0; sweep < params.smoothing_sweeps && status.ok(); ++sweep)
    status = opt.smoothing_sweep(progress);
  CancelCheck stop(progress);
  std::vector<BadTet> work = status.ok() ? opt.bad_tets(stop) : std::vector<BadTet>{}, next;
  if (status.ok() && stop.stopped()) status = absl::CancelledError("mesh optimisation cancelled");
  opt.stats.bad_tets = static_cast<std::int64_t>(work.size());
  for (int pass = 0; pass < params.passes + params.more_passes && status.ok() && !work.empty();
       ++pass) {
    if (pass >= params.passes &&
        static_cast<std::int64_t>(work.size()) > params.more_passes_max_tets)
      break;
    bool changed = false;
    next.clear();
    opt.allow_splits(pass < params.split_passes);
    status = opt.round(work, next, changed, progress);
    if (!changed) break;
    work = next_work(*complex, opt, next);
  }
  complex->compact();
  if (!status.ok()) return status;
  return opt.stats;
}

}  // namespace afmesh
