#include "core/surface/patch_from_input.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string_view>
#include <tuple>
#include <utility>
#include <vector>

#include "absl/cleanup/cleanup.h"
#include "absl/container/flat_hash_map.h"
#include "absl/container/flat_hash_set.h"
#include "absl/strings/str_format.h"
#include "core/geometry/vec.h"
#include "core/mesh/simplex_incidence.h"
#include "core/quality/measures.h"
#include "core/sizing/attached_sizes.h"
#include "core/surface/flip_edges.h"

namespace afmesh {
namespace {

// Not in the paper: no split or merge turns a triangle by more than this from the one it replaces
// (the bound of the flips, collapses and smoothing that follow).
constexpr double kMaxNormalTurnDeg = 30.0;
// Not in the paper: an input vertex on a line that no triangulation of its hole within
// kMaxNormalTurnDeg removes (remove_input_line_vertices) is tried again, after every other of its
// line, with triangles within this of the fan's on their side: still no fold (that is over 90
// degrees), where a fault left the whole surface unmeshed. cgal_dino at diag / 20 and cgal_hand at
// 3 times its mean edge, both with no curvature bound, failed so (their patch 0's front had
// stopped first); they re-triangulate valid, 98.6% and 98.1% of their triangles at 30 degrees
// and more. The surfaces that met no such vertex are unchanged.
constexpr double kMaxLineVertexTurnDeg = 60.0;
// Not in the paper: edges longer than this times the size wanted at their middle are split (the
// bound of CGAL's isotropic_remeshing), so that the edges end between 2/3 and 4/3 of it.
constexpr double kSplitOver = 4.0 / 3.0;
// Each pass of split_long_edges halves the longest edges: 64 passes reach any ratio a double can
// hold. A patch whose longest edge is r times its size needs about log2(r) passes; the passes
// stop kExtraSplitPasses after that. Not in the paper: the flips after a pass can join a point to
// the one the pass made by another long edge, whose split lands beside it, pass after pass (on
// OCCT's TR12J_OCC.stl two pairs of points split so through all 64 passes, 1.6 of the 2.7 s of a
// patch re-triangulated from its input, their clusters collapsed afterwards).
constexpr int kMaxSplitPasses = 64;
constexpr int kExtraSplitPasses = 4;
// Not in the paper: while its long edges are split, a patch may hold this many times the
// triangles it may end with (the bound patch_from_input is given), since the splits of an input
// sliver's long edges make needles that the collapses then merge. gmsh_lever.stl's end face at
// size 5.44 with no curvature bound (its front stopped at a step of the face 0.1-1.8 wide)
// peaked at 15,614 triangles in the splits for 1,982 in the end, over its bound of 14,788, and
// the surface failed; at 6 of 31 sizes from 4 to 7 it did so (12,396 for 1,638 and 11,588 at 7).
constexpr double kSplitPeakOverResult = 4.0;
// Not in the paper: edges off the lines shorter than this times the size wanted at their middle
// lose a point inside the patch (the bound of CGAL's isotropic_remeshing), where the input is
// finer than the size; at most kMaxCollapsePasses passes.
constexpr double kCollapseUnder = 4.0 / 5.0;
constexpr int kMaxCollapsePasses = 16;

// Whether a triangle whose (unnormalised) normal was `before` may become one with `after`: it keeps
// an area and turns by at most `max_turn_deg`.
bool turns_little(const Point& before, const Point& after,
                  double max_turn_deg = kMaxNormalTurnDeg) {
  const double a = norm(after), b = norm(before);
  if (!(a > 0.0) || !(b > 0.0)) return false;
  return dot(before, after) >= std::cos(max_turn_deg * std::numbers::pi / 180.0) * a * b;
}

// The patch's triangles while they are built, over the points of s (their incidence kept).
class InputPatch {
 public:
  InputPatch(SurfaceMeshState& s, PatchId patch, std::int64_t max_triangles, Progress& progress)
      : s_(s),
        patch_(patch),
        max_triangles_(max_triangles),
        progress_(progress),
        cancel_(progress, 1024) {}

  absl::Status take_input_faces();
  absl::Status insert_line_points();
  absl::Status remove_input_line_vertices();
  absl::Status split_long_edges();
  absl::Status collapse_short_edges();
  // FAILED_PRECONDITION when the patch ends with more than max_triangles triangles.
  absl::Status check_count();
  void append_to_state() const;

 private:
  bool live(Index t) const { return tris_[t][0] != kInvalidIndex; }
  void add(const Triangle& t);
  void replace(Index t, const Triangle& with);
  void drop(Index t);
  // The live triangles with both a and b, into `out`.
  void triangles_with(Index a, Index b, std::vector<Index>& out) const;
  // Splits edge (a, b) at point m (every triangle on it into two); with `check`, only when no new
  // triangle turns from its old one by more than kMaxNormalTurnDeg, without, only when both
  // have an area. False, with nothing changed, when not done.
  bool split(Index a, Index b, Index m, bool check);
  // Removes point x, whose neighbours along its line are y1 and y2: its fan of triangles goes, and
  // the polygon left on each side of the line, closed by the side (y1, y2), is triangulated for the
  // largest smallest angle, each new triangle within max_turn_deg of one of the fan on its side
  // and no new edge one the patch has already (a vertex removal, which a collapse of x into y1 or
  // y2 is one case of). False, with nothing changed, when no such triangulation exists.
  bool remove_line_vertex(Index x, Index y1, Index y2, double max_turn_deg);
  // The size wanted at x between points a and b: the field's, bounded by their attached sizes grown
  // over the distance (eq. 15, size_grown_over), so that the triangles grade out from short line
  // sides as the front's do.
  double size_at(const Point& x, Index a, Index b) const {
    return std::min({s_.field_size(x),
                     size_grown_over(s_.point_size[a], s_.growth, distance(x, s_.points[a])),
                     size_grown_over(s_.point_size[b], s_.growth, distance(x, s_.points[b]))});
  }
  // size_at the middle of edge (a, b), measured once per edge: no point of the patch moves and
  // no attached size changes while it is built, and the passes of steps 3 and 4 ask again for the
  // edges they left (the size field's query, a nearest-face search where the curvature binds,
  // was a third of OCCT's TR12J_OCC.stl). A point dropped after a failed split was on no edge.
  double edge_size(Index a, Index b) {
    const auto [it, fresh] = edge_size_.try_emplace({std::min(a, b), std::max(a, b)}, 0.0);
    if (fresh) {
      const Point mid = scale(afmesh::add(s_.points[a], s_.points[b]), 0.5);
      it->second = size_at(mid, a, b);
    }
    return it->second;
  }
  // A line of the patch in its order: its points (LinePoints::ids) and, between them, its
  // inner input vertices (`input` set, `id` the input vertex), each point after the vertex that
  // starts the segment it lies on.
  struct OnLine {
    Index id;
    bool input;
  };
  std::vector<OnLine> line_in_order(LineId l) const;
  // Merges point x (a point of this patch, not on a line) into y along their edge when x and y
  // share only the two triangles of the edge's neighbours (the link condition), no moved
  // triangle turns by more than kMaxNormalTurnDeg or loses its area, and no edge it makes at y
  // is longer than kSplitOver times the size. False, with nothing changed, otherwise.
  bool collapse(Index x, Index y);
  // The point of s at input vertex v, made on first use.
  Index point_at(Index v, FaceId face);
  // FAILED_PRECONDITION: the patch could not be made, `what` near x (local frame).
  absl::Status fault(const Point& x, std::string_view what) const;

  SurfaceMeshState& s_;
  PatchId patch_;
  std::int64_t max_triangles_;
  Progress& progress_;
  CancelCheck cancel_;
  std::vector<Triangle> tris_;  // tris_[t][0] == kInvalidIndex: dropped
  std::int64_t live_count_ = 0;
  SimplexIncidence<3> incidence_;
  // While set (split_long_edges), the triangles added or replaced get their flag set: the flips
  // after a pass of splits look only at them (flip_edges' may_gain).
  std::vector<bool>* changed_ = nullptr;
  void mark_changed(Index t) {
    if (changed_ == nullptr) return;
    if (static_cast<std::size_t>(t) >= changed_->size()) changed_->resize(t + 1, false);
    (*changed_)[t] = true;
  }
  absl::flat_hash_map<Index, Index> point_of_vertex_;  // input vertex -> point of s
  absl::flat_hash_set<Index> line_vertices_;           // inner vertices of the patch's lines
  absl::flat_hash_set<Index> pending_;                 // points at them, still to be removed
  mutable std::vector<Index> scratch_, fan_x_;
  absl::flat_hash_map<std::pair<Index, Index>, double> edge_size_;  // edge_size, by (min, max)
};

void InputPatch::add(const Triangle& t) {
  tris_.push_back(t);
  incidence_.add(tris_, static_cast<Index>(tris_.size() - 1));
  ++live_count_;
  mark_changed(static_cast<Index>(tris_.size() - 1));
}

void InputPatch::replace(Index t, const Triangle& with) {
  incidence_.remove(tris_, t);
  tris_[t] = with;
  incidence_.add(tris_, t);
  mark_changed(t);
}

void InputPatch::drop(Index t) {
  incidence_.remove(tris_, t);
  tris_[t][0] = kInvalidIndex;
  --live_count_;
}

void InputPatch::triangles_with(Index a, Index b, std::vector<Index>& out) const {
  out.clear();
  scratch_.clear();
  incidence_.elements_of(tris_, a, scratch_);
  for (const Index t : scratch_)
    if (has_corner(tris_[t], b)) out.push_back(t);
  std::sort(out.begin(), out.end());
}

absl::Status InputPatch::fault(const Point& local, std::string_view what) const {
  const Point x = s_.surface.to_global(local);
  return absl::FailedPreconditionError(absl::StrFormat(
      "patch %d (input tag %d) could not be re-triangulated from its input triangles either: %s "
      "near (%g, %g, %g)",
      index_of(patch_), s_.features.patches[index_of(patch_)].tag, what, x[0], x[1], x[2]));
}

Index InputPatch::point_at(Index v, FaceId face) {
  auto [it, fresh] = point_of_vertex_.try_emplace(v, kInvalidIndex);
  if (fresh) {
    const Point& x = s_.surface.local_points()[v];
    const bool on_line = line_vertices_.contains(v);
    it->second = s_.add_point(x, s_.field_size(x), face, on_line ? v : kInvalidIndex);
    if (on_line) pending_.insert(it->second);
  }
  return it->second;
}

// The patch's input faces, found from its first face across the edges inside it, as triangles over
// points of s: the corners' own points (shared with the other patches), a new point at every other
// input vertex (on the input).
absl::Status InputPatch::take_input_faces() {
  const SurfaceFeatures& features = s_.features;
  const DiscreteSurface& surface = s_.surface;
  // Every line's ends are corners with their points (sides_along_lines).
  for (std::size_t l = 0; l < features.lines.size(); ++l) {
    const std::vector<Index>& ids = s_.points_along_lines[l].ids;
    point_of_vertex_.try_emplace(features.lines[l].vertices.front(), ids.front());
    point_of_vertex_.try_emplace(features.lines[l].vertices.back(), ids.back());
  }
  for (const LineId l : features.patches[index_of(patch_)].lines) {
    const std::vector<Index>& vertices = features.lines[index_of(l)].vertices;
    for (std::size_t i = 1; i + 1 < vertices.size(); ++i) line_vertices_.insert(vertices[i]);
  }
  std::vector<Index> faces{index_of(features.patches[index_of(patch_)].first_face)};
  absl::flat_hash_set<Index> seen{faces[0]};
  for (std::size_t i = 0; i < faces.size(); ++i) {
    if (cancel_.due()) return absl::CancelledError("surface meshing cancelled");
    for (const Index g : surface.neighbours().across[faces[i]])
      if (g != kInvalidIndex && features.face_patch[g] == patch_ && seen.insert(g).second)
        faces.push_back(g);
  }
  // A bound on the work and memory, as the front's: more input triangles than the patch may
  // hold while it is split (kSplitPeakOverResult times what it may end with; the collapses merge
  // an input finer than the size) are refused before anything is built.
  if (static_cast<double>(faces.size()) > kSplitPeakOverResult * max_triangles_)
    return fault(surface.centroid(FaceId{faces[0]}),
                 absl::StrFormat("its %d input triangles are more than %g times the %d its "
                                 "size asks for",
                                 faces.size(), kSplitPeakOverResult, max_triangles_));
  std::sort(faces.begin(), faces.end());
  for (const Index f : faces) {
    Triangle t;
    for (int k = 0; k < 3; ++k) t[k] = point_at(surface.triangles()[f][k], FaceId{f});
    add(t);
  }
  return absl::OkStatus();
}

bool InputPatch::split(Index a, Index b, Index m, bool check) {
  std::vector<Index> on_edge;
  triangles_with(a, b, on_edge);
  if (on_edge.empty()) return false;
  // Each triangle (x, y, w) with {x, y} = {a, b}, in its own turn.
  const auto corners = [&](Index t) {
    const Triangle& tri = tris_[t];
    int k = 0;
    while (!((tri[k] == a || tri[k] == b) && (tri[(k + 1) % 3] == a || tri[(k + 1) % 3] == b))) ++k;
    return std::array<Index, 3>{tri[k], tri[(k + 1) % 3], tri[(k + 2) % 3]};
  };
  // A line point may lie exactly on an input vertex of its line (split_line's point at the end of
  // its segment): the triangle of no area it makes goes with that vertex (step 2).
  const auto goes_later = [&](Index q) {
    return pending_.contains(q) && s_.points[q] == s_.points[m];
  };
  for (const Index t : on_edge) {
    const auto [x, y, w] = corners(t);
    const Point before = vector_area(s_.points, tris_[t]);
    const Point first = vector_area(s_.points, {x, m, w});
    const Point second = vector_area(s_.points, {m, y, w});
    if (check ? !turns_little(before, first) || !turns_little(before, second)
              : (!(squared_norm(first) > 0.0) && !goes_later(x)) ||
                    (!(squared_norm(second) > 0.0) && !goes_later(y)))
      return false;  // a fold, or (unchecked) a triangle of no area that would stay
  }
  for (const Index t : on_edge) {
    const auto [x, y, w] = corners(t);
    replace(t, {x, m, w});
    add({m, y, w});
  }
  return true;
}

std::vector<InputPatch::OnLine> InputPatch::line_in_order(LineId l) const {
  const std::vector<Index>& vertices = s_.features.lines[index_of(l)].vertices;
  const SurfaceMeshState::LinePoints& along = s_.points_along_lines[index_of(l)];
  const std::size_t last = along.ids.size() - 1;
  std::vector<OnLine> out{{along.ids[0], false}};
  std::size_t i = 1;
  for (std::size_t seg = 0; seg + 1 < vertices.size(); ++seg) {
    for (; i < last && along.segment[i] == static_cast<Index>(seg); ++i)
      out.push_back({along.ids[i], false});
    if (seg + 2 < vertices.size()) out.push_back({vertices[seg + 1], true});
  }
  out.push_back({along.ids[last], false});
  return out;
}

// Step 1: the points of each line of the patch, in the line's order, split the input edges they
// lie on (LineSplit::segment): from the last point or input vertex before to the next input
// vertex or corner. A point never leaves its edge, so no triangle turns.
absl::Status InputPatch::insert_line_points() {
  for (const LineId l : s_.features.patches[index_of(patch_)].lines) {
    const std::vector<OnLine> line = line_in_order(l);
    for (const OnLine& on : line)
      if (on.input && !point_of_vertex_.contains(on.id))
        return fault(s_.points[line[0].id], "a line of the patch runs off its input faces");
    // The point at each entry's next input vertex (the line's last corner at the end).
    std::vector<Index> ahead(line.size(), line.back().id);
    for (std::size_t j = line.size() - 1; j-- > 0;)
      ahead[j] = line[j + 1].input ? point_of_vertex_.at(line[j + 1].id) : ahead[j + 1];
    Index left = line[0].id;
    for (std::size_t j = 1; j + 1 < line.size(); ++j) {
      if (line[j].input) {
        left = point_of_vertex_.at(line[j].id);
        continue;
      }
      if (cancel_.due()) return absl::CancelledError("surface meshing cancelled");
      if (!split(left, ahead[j], line[j].id, /*check=*/false))
        return fault(s_.points[line[j].id],
                     "a line point lies on an input edge of no triangle of the patch");
      left = line[j].id;
    }
  }
  return absl::OkStatus();
}

bool InputPatch::remove_line_vertex(Index x, Index y1, Index y2, double max_turn_deg) {
  fan_x_.clear();
  incidence_.elements_of(tris_, x, fan_x_);
  // The link of x: a -> b for each triangle (x, a, b), with one way out of and into each point.
  absl::flat_hash_map<Index, Index> next;
  absl::flat_hash_set<Index> has_in;
  for (const Index t : fan_x_) {
    const Triangle& tri = tris_[t];
    const int k = tri[0] == x ? 0 : tri[1] == x ? 1 : 2;
    const Index a = tri[(k + 1) % 3], b = tri[(k + 2) % 3];
    if (!next.try_emplace(a, b).second || !has_in.insert(b).second) return false;
  }
  // The link cut at y1 and y2 into chains from one to the other (one for a line on the patch's rim,
  // two for a line inside it), each a polygon closed by the side (last, first).
  std::vector<std::vector<Index>> chains;
  std::size_t linked = 0;
  for (const Index start : {y1, y2}) {
    const auto out = next.find(start);
    if (out == next.end()) continue;
    std::vector<Index> chain{start};
    for (Index q = out->second;; q = next.at(q)) {
      chain.push_back(q);
      ++linked;
      if (q == y1 || q == y2) break;
      if (q == x || !next.contains(q) || chain.size() > next.size() + 1) return false;
    }
    if (chain.back() == start) return false;
    chains.push_back(std::move(chain));
  }
  if (chains.empty() || linked != next.size()) return false;
  // Each polygon triangulated for the largest smallest angle (dynamic programming over its
  // diagonals), every triangle within kMaxNormalTurnDeg of a triangle of x's fan, and no diagonal
  // an edge the patch has already.
  absl::flat_hash_map<Index, Point> normal_after;  // a -> the normal of triangle (x, a, b)
  for (const Index t : fan_x_) {
    const Triangle& tri = tris_[t];
    normal_after[tri[(std::find(tri.begin(), tri.end(), x) - tri.begin() + 1) % 3]] =
        vector_area(s_.points, tri);
  }
  std::vector<Triangle> made;
  std::vector<Point> old_normals;
  for (const std::vector<Index>& c : chains) {
    const std::size_t m = c.size() - 1;
    // The fan's triangles on this side of the line only: a triangle turned as the other side's
    // would fold across a crease the line follows.
    old_normals.clear();
    for (std::size_t k = 0; k < m; ++k) old_normals.push_back(normal_after.at(c[k]));
    if (m < 2) continue;
    const std::size_t n = m + 1;
    constexpr double kInvalid = -1.0;
    std::vector<double> best(n * n, kInvalid);
    std::vector<std::size_t> apex(n * n, 0);
    std::vector<Index> on_edge;
    // Whether chord (c_i, c_j) of the polygon may be an edge.
    const auto usable = [&](std::size_t i, std::size_t j) {
      if (j == i + 1 || (i == 0 && j == m)) return true;
      triangles_with(c[i], c[j], on_edge);
      return on_edge.empty();
    };
    for (std::size_t i = 0; i + 1 < n; ++i) best[i * n + i + 1] = 180.0;  // an edge: no triangle
    for (std::size_t span = 2; span <= m; ++span) {
      for (std::size_t i = 0; i + span < n; ++i) {
        const std::size_t j = i + span;
        if (!usable(i, j)) continue;
        for (std::size_t k = i + 1; k < j; ++k) {
          const double inner = std::min(best[i * n + k], best[k * n + j]);
          if (inner <= best[i * n + j]) continue;
          const Point nt = vector_area(s_.points, {c[i], c[k], c[j]});
          if (std::none_of(old_normals.begin(), old_normals.end(),
                           [&](const Point& o) { return turns_little(o, nt, max_turn_deg); }))
            continue;
          const double q = std::min(
              inner, triangle_min_angle_deg(s_.points[c[i]], s_.points[c[k]], s_.points[c[j]]));
          if (q > best[i * n + j]) best[i * n + j] = q, apex[i * n + j] = k;
        }
      }
    }
    if (!(best[m] > 0.0)) return false;  // best[0 * n + m]
    std::vector<std::pair<std::size_t, std::size_t>> todo{{0, m}};
    while (!todo.empty()) {
      const auto [i, j] = todo.back();
      todo.pop_back();
      if (j == i + 1) continue;
      const std::size_t k = apex[i * n + j];
      made.push_back({c[i], c[k], c[j]});
      todo.push_back({i, k});
      todo.push_back({k, j});
    }
  }
  const std::vector<Index> fan = fan_x_;
  for (const Index t : fan) drop(t);
  for (const Triangle& t : made) add(t);
  return true;
}

// Step 2: along each line of the patch, in its order, the points at input vertices are removed
// (remove_line_vertex), pass after pass while one goes, first within kMaxNormalTurnDeg, then
// within kMaxLineVertexTurnDeg; one that never can is a fault.
absl::Status InputPatch::remove_input_line_vertices() {
  for (const LineId l : s_.features.patches[index_of(patch_)].lines) {
    // The line's points and the points at its input vertices, in its order.
    std::vector<Index> chain;
    for (const OnLine& on : line_in_order(l))
      chain.push_back(on.input ? point_of_vertex_.at(on.id) : on.id);
    std::vector<std::size_t> prev(chain.size()), next(chain.size());
    for (std::size_t j = 0; j < chain.size(); ++j) prev[j] = j - 1, next[j] = j + 1;
    std::vector<bool> gone(chain.size(), false);
    for (const double max_turn : {kMaxNormalTurnDeg, kMaxLineVertexTurnDeg}) {
      for (bool merged = true; merged;) {
        merged = false;
        for (std::size_t j = 1; j + 1 < chain.size(); ++j) {
          if (gone[j] || !pending_.contains(chain[j])) continue;
          if (cancel_.due()) return absl::CancelledError("surface meshing cancelled");
          const Index x = chain[j];
          const Index y1 = chain[prev[j]], y2 = chain[next[j]];
          if (!remove_line_vertex(x, y1, y2, max_turn)) continue;
          pending_.erase(x);
          gone[j] = merged = true;
          next[prev[j]] = next[j];
          prev[next[j]] = prev[j];
        }
      }
    }
    for (std::size_t j = 1; j + 1 < chain.size(); ++j)
      if (!gone[j] && pending_.contains(chain[j]))
        return fault(s_.points[chain[j]],
                     "an input vertex on a line cannot be removed without folding a triangle");
  }
  if (!pending_.empty())
    return fault(s_.points[*pending_.begin()], "an input vertex on a line is left");
  return absl::OkStatus();
}

// Step 3: the edges off the lines longer than kSplitOver times the size at their middle, the
// longest relative to it first, split at their middle moved onto the patch (S8), pass after pass.
// An edge whose split would turn a triangle by more than kMaxNormalTurnDeg stays.
absl::Status InputPatch::split_long_edges() {
  absl::flat_hash_set<std::pair<Index, Index>> kept;
  std::vector<std::pair<Index, Index>> edges;
  std::vector<std::tuple<double, Index, Index>> long_edges;
  // flip_edges takes the live triangles only, all of this patch.
  std::erase_if(tris_, [](const Triangle& t) { return t[0] == kInvalidIndex; });
  std::vector<Index> same_patch;
  // The triangles whose edges the next flips look at: all of them before the first flips (the
  // input's faces), then those the flips left gaining and those the splits made (not in the
  // paper: a pass that splits a few edges of a large patch flipped over all of it, 23% of
  // cgal_dino's time when its patch 0 came from its input, 19.5% now; the same flips are made).
  std::vector<bool> may_gain(tris_.size(), true);
  changed_ = &may_gain;
  const absl::Cleanup stop_marking = [this] { changed_ = nullptr; };
  int passes = kMaxSplitPasses;
  for (int pass = 0; pass < passes; ++pass) {
    if (pass > 0) {
      same_patch.assign(tris_.size(), index_of(patch_));
      may_gain.resize(tris_.size(), false);
      if (absl::StatusOr<std::int64_t> flips = flip_edges(s_.points, tris_, same_patch,
                                                          s_.line_sides, {}, progress_, &may_gain);
          !flips.ok())
        return flips.status();
    }
    incidence_ = SimplexIncidence<3>::of(tris_);
    edges.clear();
    for (std::size_t t = 0; t < tris_.size(); ++t) {
      if (!live(static_cast<Index>(t))) continue;
      for (int k = 0; k < 3; ++k) {
        const Index a = tris_[t][k], b = tris_[t][(k + 1) % 3];
        const std::pair<Index, Index> e{std::min(a, b), std::max(a, b)};
        if (!s_.line_sides.contains(e) && !kept.contains(e)) edges.push_back(e);
      }
    }
    std::sort(edges.begin(), edges.end());
    edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
    long_edges.clear();
    for (const auto& [a, b] : edges) {
      if (cancel_.due()) return absl::CancelledError("surface meshing cancelled");
      const double ratio = norm(sub(s_.points[b], s_.points[a])) / edge_size(a, b);
      if (ratio > kSplitOver) long_edges.emplace_back(-ratio, a, b);
    }
    if (long_edges.empty()) return absl::OkStatus();
    std::sort(long_edges.begin(), long_edges.end());
    if (pass == 0) {
      const double longest = -std::get<0>(long_edges.front());
      passes = std::min(kMaxSplitPasses,
                        static_cast<int>(std::ceil(std::log2(longest))) + kExtraSplitPasses);
    }
    for (const auto& [minus_ratio, a, b] : long_edges) {
      if (cancel_.due()) return absl::CancelledError("surface meshing cancelled");
      const Point mid = scale(afmesh::add(s_.points[a], s_.points[b]), 0.5);
      const Located on =
          locate_in_patch(s_.surface, s_.features, patch_, mid, patch_hint(s_, patch_, a));
      const Index m = s_.add_point(on.closest, size_at(on.closest, a, b), on.face, kInvalidIndex);
      if (!split(a, b, m, /*check=*/true)) {
        s_.drop_last_point();
        kept.insert({a, b});
        continue;
      }
      if (static_cast<double>(live_count_) > kSplitPeakOverResult * max_triangles_)
        return fault(s_.points[m],
                     absl::StrFormat("it needs more than %d triangles while its long edges are "
                                     "split (%g times the %d it may end with)",
                                     static_cast<std::int64_t>(kSplitPeakOverResult *
                                                               max_triangles_),
                                     kSplitPeakOverResult, max_triangles_));
    }
  }
  return absl::OkStatus();
}

bool InputPatch::collapse(Index x, Index y) {
  fan_x_.clear();
  incidence_.elements_of(tris_, x, fan_x_);
  std::vector<Index> shared, moved;
  for (const Index t : fan_x_) (has_corner(tris_[t], y) ? shared : moved).push_back(t);
  if (shared.size() != 2) return false;
  // The link condition: x and y have as common neighbours only the two opposite corners.
  std::vector<Index> fan_y, around_x, around_y;
  incidence_.elements_of(tris_, y, fan_y);
  corners_of_fan(tris_, fan_x_, x, around_x);
  corners_of_fan(tris_, fan_y, y, around_y);
  std::vector<Index> common;
  std::set_intersection(around_x.begin(), around_x.end(), around_y.begin(), around_y.end(),
                        std::back_inserter(common));
  if (common.size() != 2) return false;
  for (const Index t : moved) {
    Triangle after = tris_[t];
    for (Index& q : after) q = q == x ? y : q;
    if (!turns_little(vector_area(s_.points, tris_[t]), vector_area(s_.points, after))) {
      return false;
    }
    for (const Index w : after) {
      if (w == y) continue;
      if (distance(s_.points[y], s_.points[w]) > kSplitOver * edge_size(y, w)) return false;
    }
  }
  for (const Index t : shared) drop(t);
  for (const Index t : moved) {
    Triangle after = tris_[t];
    for (Index& q : after) q = q == x ? y : q;
    replace(t, after);
  }
  return true;
}

// Step 4 (not in the paper): where the input is finer than the size, the edges off the lines
// shorter than kCollapseUnder times the size at their middle, the shortest relative to it first,
// lose a point of the patch (collapse), pass after pass, each pass followed by flips. Line points
// never move.
absl::Status InputPatch::collapse_short_edges() {
  const auto movable = [&](Index q) { return q >= s_.line_points; };
  std::vector<std::tuple<double, Index, Index>> short_edges;
  std::vector<Index> same_patch;
  std::vector<Index> on_edge;
  for (int pass = 0; pass < kMaxCollapsePasses; ++pass) {
    std::erase_if(tris_, [](const Triangle& t) { return t[0] == kInvalidIndex; });
    incidence_ = SimplexIncidence<3>::of(tris_);
    short_edges.clear();
    for (const Triangle& t : tris_) {
      for (int k = 0; k < 3; ++k) {
        const Index a = t[k], b = t[(k + 1) % 3];
        if (a > b || s_.line_sides.contains({a, b}) || (!movable(a) && !movable(b))) continue;
        if (cancel_.due()) return absl::CancelledError("surface meshing cancelled");
        const double ratio = distance(s_.points[a], s_.points[b]) / edge_size(a, b);
        if (ratio < kCollapseUnder) short_edges.emplace_back(ratio, a, b);
      }
    }
    if (short_edges.empty()) return absl::OkStatus();
    std::sort(short_edges.begin(), short_edges.end());
    std::int64_t made = 0;
    for (const auto& [ratio, a, b] : short_edges) {
      if (cancel_.due()) return absl::CancelledError("surface meshing cancelled");
      triangles_with(a, b, on_edge);  // gone when a point of it was merged away
      if (on_edge.empty()) continue;
      if ((movable(a) && collapse(a, b)) || (movable(b) && collapse(b, a))) ++made;
    }
    if (made == 0) return absl::OkStatus();
    std::erase_if(tris_, [](const Triangle& t) { return t[0] == kInvalidIndex; });
    same_patch.assign(tris_.size(), index_of(patch_));
    if (absl::StatusOr<std::int64_t> flips =
            flip_edges(s_.points, tris_, same_patch, s_.line_sides, {}, progress_);
        !flips.ok())
      return flips.status();
  }
  return absl::OkStatus();
}

absl::Status InputPatch::check_count() {
  if (live_count_ <= max_triangles_) return absl::OkStatus();
  for (const Triangle& t : tris_)
    if (t[0] != kInvalidIndex)
      return fault(s_.points[t[0]],
                   absl::StrFormat("it needs more than %d triangles", max_triangles_));
  return absl::OkStatus();
}

void InputPatch::append_to_state() const {
  for (std::size_t t = 0; t < tris_.size(); ++t)
    if (live(static_cast<Index>(t))) s_.add_triangle(tris_[t], patch_);
}

}  // namespace

absl::Status patch_from_input(SurfaceMeshState& s, PatchId patch, const std::vector<Side>& sides,
                              std::int64_t max_triangles, Progress& progress) {
  const std::size_t first = s.triangles.size();
  const Index points_before = static_cast<Index>(s.points.size());
  // s as before the call.
  const auto undo = [&](absl::Status st) {
    s.take_back_patch(points_before, first);
    return st;
  };
  InputPatch built(s, patch, max_triangles, progress);
  for (const auto& step : {&InputPatch::take_input_faces, &InputPatch::insert_line_points,
                           &InputPatch::remove_input_line_vertices, &InputPatch::split_long_edges,
                           &InputPatch::collapse_short_edges, &InputPatch::check_count})
    if (absl::Status st = (built.*step)(); !st.ok()) return undo(std::move(st));
  built.append_to_state();
  s.compact_patch(points_before, first);  // drops the points merged away
  if (absl::Status closed = check_patch_closed(s, patch, sides, first); !closed.ok())
    return undo(std::move(closed));
  keep_chords_between_line_points(s, first);
  return absl::OkStatus();
}

}  // namespace afmesh
