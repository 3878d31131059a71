// Repairs of the input's sliver triangles (sliver_repairs.h; not in the paper).
#include "core/surface/sliver_repairs.h"

#include <algorithm>
#include <cmath>
#include <limits>
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
  explicit SurfaceEdits(Mesh& surface)
      : surface_(surface),
        incidence_(SimplexIncidence<3>::of(surface.triangles)),
        alive_(surface.triangles.size(), true) {}

  bool alive(Index f) const { return alive_[f]; }

  // Edge (a, b) collapsed: the two faces on it are dropped and one end takes the other's place
  // in its other faces, b if that turns none of them by 90° or more, else a on the same
  // condition. Only when exactly two faces share the edge and a and b have no common neighbour
  // but their two opposite corners (the link condition). False, and nothing changed, otherwise.
  bool collapse(Index a, Index b) {
    const std::vector<Triangle>& tris = surface_.triangles;
    fan_a_.clear();
    fan_b_.clear();
    incidence_.elements_of(tris, a, fan_a_);
    incidence_.elements_of(tris, b, fan_b_);
    on_edge_.clear();
    for (const Index g : fan_a_)
      if (has_corner(tris[g], b)) on_edge_.push_back(g);
    if (on_edge_.size() != 2) return false;
    corners_of_fan(tris, fan_a_, a, around_a_);
    corners_of_fan(tris, fan_b_, b, around_b_);
    int common = 0;
    for (const Index q : around_a_)
      common += q != b && std::binary_search(around_b_.begin(), around_b_.end(), q);
    if (common != 2) return false;
    if (turns_none(fan_b_, b, a)) {
      move_corner(fan_b_, b, a);
    } else if (turns_none(fan_a_, a, b)) {
      move_corner(fan_a_, a, b);
    } else {
      return false;
    }
    return true;
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
      const Point before = cross(sub(p[was[1]], p[was[0]]), sub(p[was[2]], p[was[0]]));
      const Point after = cross(sub(p[moved[1]], p[moved[0]]), sub(p[moved[2]], p[moved[0]]));
      if (!(dot(before, after) > 0.0)) return false;
    }
    return true;
  }

  // The faces on the edge dropped; `gone` becomes `keep` in the other faces of `fan`.
  void move_corner(const std::vector<Index>& fan, Index gone, Index keep) {
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

  Mesh& surface_;
  SimplexIncidence<3> incidence_;
  std::vector<bool> alive_;
  std::vector<Index> fan_a_, fan_b_, around_a_, around_b_, on_edge_;
};

}  // namespace

FoldedCollapses collapse_folded_slivers(Mesh& clean, std::span<const FaceId> folded) {
  SurfaceEdits edits(clean);
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
    if (!edits.collapse(t[k], t[(k + 1) % 3])) continue;
    ++done.count;
    done.longest_edge = std::max(done.longest_edge, shortest);
  }
  if (done.count > 0) edits.finish();
  return done;
}

}  // namespace afmesh
