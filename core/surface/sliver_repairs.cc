// Repairs of the input's sliver triangles (sliver_repairs.h; not in the paper).
#include "core/surface/sliver_repairs.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <optional>
#include <vector>

#include "core/geometry/vec.h"
#include "core/mesh/simplex_incidence.h"

namespace afmesh {
namespace {

// Edits of a surface's faces in place, with their point incidence kept up to date: edge
// collapses that keep the surface manifold and turn no face over; finish() drops the faces
// collapsed and the points left on no face.
class SurfaceEdits {
 public:
  // `before`, when given and empty, takes a copy of the surface as it is before the first change.
  explicit SurfaceEdits(Mesh& surface, std::optional<Mesh>* before = nullptr)
      : surface_(surface),
        before_(before),
        incidence_(SimplexIncidence<3>::of(surface.triangles)),
        alive_(surface.triangles.size(), true) {}

  bool alive(Index f) const { return alive_[f]; }

  // Edge (a, b) collapsed: the two faces on it are dropped and one end takes the other's place
  // in its other faces, b if that turns none of them by 90° or more, else a on the same
  // condition. Only when exactly two faces share the edge and a and b have no common neighbour
  // but their two opposite corners (the link condition). Returns the end kept; kInvalidIndex,
  // and nothing changed, otherwise.
  Index collapse(Index a, Index b) {
    const std::vector<Triangle>& tris = surface_.triangles;
    fan_a_.clear();
    fan_b_.clear();
    incidence_.elements_of(tris, a, fan_a_);
    incidence_.elements_of(tris, b, fan_b_);
    on_edge_.clear();
    for (const Index g : fan_a_)
      if (has_corner(tris[g], b)) on_edge_.push_back(g);
    if (on_edge_.size() != 2) return kInvalidIndex;
    corners_of_fan(tris, fan_a_, a, around_a_);
    corners_of_fan(tris, fan_b_, b, around_b_);
    int common = 0;
    for (const Index q : around_a_)
      common += q != b && std::binary_search(around_b_.begin(), around_b_.end(), q);
    if (common != 2) return kInvalidIndex;
    if (turns_none(fan_b_, b, a)) {
      move_corner(fan_b_, b, a);
      return a;
    }
    if (turns_none(fan_a_, a, b)) {
      move_corner(fan_a_, a, b);
      return b;
    }
    return kInvalidIndex;
  }

  // Face f becomes t (its tag kept).
  void replace(Index f, const Triangle& t) {
    keep_before();
    incidence_.remove(surface_.triangles, f);
    surface_.triangles[f] = t;
    incidence_.add(surface_.triangles, f);
  }

  // Appends the live faces with corner p to `out`.
  void faces_of(Index p, std::vector<Index>& out) const {
    incidence_.elements_of(surface_.triangles, p, out);
  }

  // The face across edge (a, b) of face f, which traverses it a→b: the only other face on the
  // edge, traversing it b→a; kInvalidIndex when there is none, or more, or it goes a→b too.
  Index face_across(Index f, Index a, Index b) {
    const std::vector<Triangle>& tris = surface_.triangles;
    fan_a_.clear();
    incidence_.elements_of(tris, a, fan_a_);
    Index across = kInvalidIndex;
    for (const Index g : fan_a_) {
      if (g == f || !has_corner(tris[g], b)) continue;
      if (across != kInvalidIndex) return kInvalidIndex;
      across = g;
    }
    if (across == kInvalidIndex) return kInvalidIndex;
    const Triangle& u = tris[across];
    for (int k = 0; k < 3; ++k)
      if (u[k] == b) return u[(k + 1) % 3] == a ? across : kInvalidIndex;
    return kInvalidIndex;
  }

  // Whether v and w are corners of one face.
  bool has_edge(Index v, Index w) {
    fan_a_.clear();
    incidence_.elements_of(surface_.triangles, v, fan_a_);
    return std::any_of(fan_a_.begin(), fan_a_.end(),
                       [&](Index g) { return has_corner(surface_.triangles[g], w); });
  }

  // Drops the faces collapsed (with their tags) and the points on no face, renumbering the rest
  // in the order the faces use them.
  void finish() {
    const std::vector<Point>& p = surface_.points;
    Mesh out;
    std::vector<Index> new_index(p.size(), kInvalidIndex);
    for (std::size_t t = 0; t < surface_.triangles.size(); ++t) {
      if (!alive_[t]) continue;
      Triangle w;
      for (int c = 0; c < 3; ++c) {
        const Index v = surface_.triangles[t][c];
        if (new_index[v] == kInvalidIndex) {
          new_index[v] = static_cast<Index>(out.points.size());
          out.points.push_back(p[v]);
        }
        w[c] = new_index[v];
      }
      out.triangles.push_back(w);
      out.triangle_tags.push_back(surface_.triangle_tags[t]);
    }
    surface_ = std::move(out);
  }

 private:
  // Whether every face of `fan` but those on the edge keeps its area and turns by less than
  // 90° when `gone` becomes `keep`.
  bool turns_none(const std::vector<Index>& fan, Index gone, Index keep) const {
    const std::vector<Point>& p = surface_.points;
    for (const Index g : fan) {
      if (g == on_edge_[0] || g == on_edge_[1]) continue;
      const Triangle& was = surface_.triangles[g];
      Triangle moved = was;
      for (Index& w : moved)
        if (w == gone) w = keep;
      if (!(dot(vector_area(p, was), vector_area(p, moved)) > 0.0)) return false;
    }
    return true;
  }

  // The faces on the edge dropped; `gone` becomes `keep` in the other faces of `fan`.
  void move_corner(const std::vector<Index>& fan, Index gone, Index keep) {
    keep_before();
    std::vector<Triangle>& tris = surface_.triangles;
    for (const Index g : on_edge_) {
      incidence_.remove(tris, g);
      alive_[g] = false;
    }
    for (const Index g : fan) {
      if (!alive_[g]) continue;
      incidence_.remove(tris, g);
      for (Index& w : tris[g])
        if (w == gone) w = keep;
      incidence_.add(tris, g);
    }
  }

  void keep_before() {
    if (before_ != nullptr && !before_->has_value()) *before_ = surface_;
  }

  Mesh& surface_;
  std::optional<Mesh>* before_;
  SimplexIncidence<3> incidence_;
  std::vector<bool> alive_;
  std::vector<Index> fan_a_, fan_b_, around_a_, around_b_, on_edge_;
};

}  // namespace

FoldedCollapses collapse_folded_slivers(Mesh& clean, std::span<const FaceId> folded,
                                        std::optional<Mesh>* before) {
  SurfaceEdits edits(clean, before);
  FoldedCollapses done;
  for (const FaceId face : folded) {
    const Index f = index_of(face);
    if (!edits.alive(f)) continue;
    const Triangle t = clean.triangles[f];
    const std::vector<Point>& p = clean.points;
    int k = 0;
    double shortest = std::numeric_limits<double>::infinity(), longest = 0.0;
    for (int e = 0; e < 3; ++e) {
      const double l = norm(sub(p[t[(e + 1) % 3]], p[t[e]]));
      if (l < shortest) shortest = l, k = e;
      longest = std::max(longest, l);
    }
    if (!(shortest < kFoldedSliverEdgeRatio * longest)) continue;
    if (edits.collapse(t[k], t[(k + 1) % 3]) == kInvalidIndex) continue;
    ++done.count;
    done.longest_edge = std::max(done.longest_edge, shortest);
  }
  if (done.count > 0) edits.finish();
  return done;
}

namespace {

// Whether two faces' unit normals (from unnormalised ones) make an angle whose cosine is above
// `cos_angle`; false when either has no area.
bool turn_below(const Point& n1, const Point& n2, double cos_angle) {
  const double lengths = norm(n1) * norm(n2);
  return lengths > 0.0 && dot(n1, n2) > cos_angle * lengths;
}

}  // namespace

StepRepairs repair_sliver_steps(Mesh& clean, const SizeField& sizes, double ridge_angle_deg,
                                double max_height, std::optional<Mesh>* before) {
  SurfaceEdits edits(clean, before);
  const std::vector<Point>& p = clean.points;
  const std::vector<Triangle>& tris = clean.triangles;
  const auto tag = [&](Index f) {
    return clean.triangle_tags.empty() ? 0 : clean.triangle_tags[f];
  };
  const double cos_ridge = std::cos(ridge_angle_deg * std::numbers::pi / 180.0);
  // Face f as a step: its longest edge (a, b), the face g across it, and how far the surface
  // moves when it goes; nullopt when f is no step.
  struct Step {
    int longest_at, shortest_at;
    Index across;
    bool needle;
    double height;
  };
  std::vector<Index> fan;
  const auto step_of = [&](Index f) -> std::optional<Step> {
    const Triangle& t = tris[f];
    Step st{};
    double longest = 0.0, shortest = std::numeric_limits<double>::infinity();
    for (int e = 0; e < 3; ++e) {
      const double l = distance(p[t[e]], p[t[(e + 1) % 3]]);
      if (l > longest) longest = l, st.longest_at = e;
      if (l < shortest) shortest = l, st.shortest_at = e;
    }
    const Point n_f = vector_area(p, t);
    st.height = norm(n_f) / longest;
    if (!(st.height < kStepHeightOfEdge * longest)) return std::nullopt;
    const Index a = t[st.longest_at], b = t[(st.longest_at + 1) % 3],
                v = t[(st.longest_at + 2) % 3];
    st.across = edits.face_across(f, a, b);
    if (st.across == kInvalidIndex || tag(st.across) != tag(f)) return std::nullopt;
    const Point n_g = vector_area(p, tris[st.across]);
    if (turn_below(n_f, n_g, cos_ridge)) return std::nullopt;
    // The surface beyond the step continues the one across ab: a face at v turns less than the
    // ridge angle against g (a seam; a chamfer's or a rib's faces meet at a ridge instead).
    fan.clear();
    edits.faces_of(v, fan);
    if (std::none_of(fan.begin(), fan.end(), [&](Index h) {
          return h != f && !(has_corner(tris[h], a) && has_corner(tris[h], b)) &&
                 turn_below(vector_area(p, tris[h]), n_g, cos_ridge);
        }))
      return std::nullopt;
    st.needle = shortest < kStepHeightOfEdge * longest;
    if (st.needle) st.height = std::max(st.height, shortest);
    return st;
  };
  // The steps, and which of them go: a strip of steps (joined through their corners) goes
  // whole when its highest is lower than kStepHeightOfSize of the smallest size asked along it,
  // or not at all; only a distance bound (max_height) keeps its steps over the bound and lets
  // the rest go. A seam's strip is a chain of lunes, each as wide as the two polygons' chords
  // are apart, meeting at points; removed in part by the size alone, the lever's kept its wide
  // lunes as patches with corners of 10 degrees at their ends, where the sizes ran down to
  // 1/1000 of the size asked (50k triangles for 28k; at 5.44, a front stuck there).
  const std::size_t m = tris.size();
  std::vector<char> goes(m), is_step(m), seen(m);
  std::vector<double> height(m);
  std::vector<Index> strip, stack, around, work, changed;
  const auto mark_strips_that_go = [&] {
    std::fill(goes.begin(), goes.end(), 0);
    std::fill(is_step.begin(), is_step.end(), 0);
    std::fill(seen.begin(), seen.end(), 0);
    bool any = false;
    for (std::size_t f = 0; f < m; ++f)
      if (edits.alive(static_cast<Index>(f)))
        if (const std::optional<Step> st = step_of(static_cast<Index>(f))) {
          is_step[f] = 1;
          height[f] = st->height;
        }
    for (std::size_t first = 0; first < m; ++first) {
      if (!is_step[first] || seen[first]) continue;
      strip.clear();
      stack.assign(1, static_cast<Index>(first));
      seen[first] = 1;
      double highest = 0.0, smallest_size = std::numeric_limits<double>::infinity();
      while (!stack.empty()) {
        const Index f = stack.back();
        stack.pop_back();
        strip.push_back(f);
        const Triangle& t = tris[f];
        highest = std::max(highest, height[f]);
        smallest_size = std::min(smallest_size, sizes.size_at(lerp(p[t[0]], p[t[1]], 0.5)));
        for (int e = 0; e < 3; ++e) {
          around.clear();
          edits.faces_of(t[e], around);
          for (const Index g : around)
            if (is_step[g] && !seen[g]) {
              seen[g] = 1;
              stack.push_back(g);
            }
        }
      }
      if (!(highest < kStepHeightOfSize * smallest_size)) continue;
      // With the user's distance bound, the steps higher than it stay and the rest go (see
      // max_height in the header); without it, the whole strip goes.
      for (const Index f : strip)
        if (height[f] <= max_height) goes[f] = 1, any = true;
    }
    return any;
  };
  // The faces that go are repaired in ascending order, then each face a repair changed; then
  // the strips are found again while that repairs any (a repair can make a step of a face that
  // was none: a sliver of the strip beside one flipped, whose own flip is refused until then).
  // A repair takes a step away, so there are fewer than M; the bound guards against a cycle.
  const auto max_repairs = static_cast<std::int64_t>(m);
  StepRepairs done;
  bool collapsed = false;
  for (std::int64_t before = -1; done.count > before && done.count < max_repairs;) {
    before = done.count;
    if (!mark_strips_that_go()) break;
    for (std::size_t f = m; f-- > 0;)
      if (goes[f]) work.push_back(static_cast<Index>(f));
    while (!work.empty() && done.count < max_repairs) {
      const Index f = work.back();
      work.pop_back();
      if (!edits.alive(f) || !goes[f]) continue;
      const std::optional<Step> st = step_of(f);
      if (!st) continue;
      const Triangle t = tris[f];
      changed.clear();
      if (st->needle) {
        const Index kept = edits.collapse(t[st->shortest_at], t[(st->shortest_at + 1) % 3]);
        if (kept == kInvalidIndex) continue;
        collapsed = true;
        edits.faces_of(kept, changed);
      } else {
        const Index a = t[st->longest_at], b = t[(st->longest_at + 1) % 3],
                    v = t[(st->longest_at + 2) % 3];
        const Index g = st->across;
        const Triangle& u = tris[g];
        const Index w = u[0] != a && u[0] != b ? u[0] : u[1] != a && u[1] != b ? u[1] : u[2];
        if (w == v || edits.has_edge(v, w)) continue;
        const Point n_g = vector_area(p, u);
        const Triangle first{v, a, w}, second{v, w, b};
        if (!turn_below(vector_area(p, first), n_g, cos_ridge) ||
            !turn_below(vector_area(p, second), n_g, cos_ridge))
          continue;
        edits.replace(f, first);
        edits.replace(g, second);
        changed = {g, f};
      }
      done.highest = std::max(done.highest, st->height);
      ++done.count;
      for (const Index c : changed) work.push_back(c);
    }
  }
  if (collapsed) edits.finish();
  return done;
}

}  // namespace afmesh
