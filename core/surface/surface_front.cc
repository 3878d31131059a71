// The surface front, S1–S11 (paper §3); see surface_front.h.
#include "core/surface/surface_front.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <optional>
#include <span>
#include <string_view>

#include "absl/container/flat_hash_map.h"
#include "absl/strings/str_format.h"
#include "core/front/advancing_front.h"
#include "core/front/front_bins.h"
#include "core/front/front_sizes.h"
#include "core/front/repair_counts.h"
#include "core/geometry/closest_points.h"
#include "core/geometry/predicates.h"
#include "core/geometry/vec.h"
#include "core/mesh/simplex_incidence.h"
#include "core/quality/measures.h"
#include "core/sizing/attached_sizes.h"

namespace afmesh {

Index SurfaceMeshState::add_point(const Point& x, double size, FaceId host_face,
                                  Index anchor_vertex) {
  points.push_back(x);
  point_size.push_back(size);
  host.push_back(host_face);
  anchor.push_back(anchor_vertex);
  return static_cast<Index>(points.size() - 1);
}

void SurfaceMeshState::drop_last_point() {
  points.pop_back();
  point_size.pop_back();
  host.pop_back();
  anchor.pop_back();
}

void SurfaceMeshState::add_triangle(const Triangle& t, PatchId patch) {
  triangles.push_back(t);
  triangle_tags.push_back(features.patches[index_of(patch)].tag);
  triangle_patch.push_back(index_of(patch));
}

void SurfaceMeshState::compact_patch(Index first_point, std::size_t first_triangle) {
  std::size_t kept = first_triangle;
  for (std::size_t t = first_triangle; t < triangles.size(); ++t) {
    if (triangles[t][0] == kInvalidIndex) continue;
    triangles[kept] = triangles[t];
    triangle_tags[kept] = triangle_tags[t];
    triangle_patch[kept] = triangle_patch[t];
    ++kept;
  }
  triangles.resize(kept);
  triangle_tags.resize(kept);
  triangle_patch.resize(kept);
  const Index n = static_cast<Index>(points.size());
  std::vector<Index> new_index(static_cast<std::size_t>(n - first_point), kInvalidIndex);
  for (std::size_t t = first_triangle; t < kept; ++t)
    for (const Index q : triangles[t])
      if (q >= first_point) new_index[q - first_point] = 0;  // used
  Index next = first_point;
  for (Index q = first_point; q < n; ++q) {
    if (new_index[q - first_point] == kInvalidIndex) continue;
    points[next] = points[q];
    point_size[next] = point_size[q];
    host[next] = host[q];
    anchor[next] = anchor[q];
    new_index[q - first_point] = next++;
  }
  points.resize(next);
  point_size.resize(next);
  host.resize(next);
  anchor.resize(next);
  for (std::size_t t = first_triangle; t < kept; ++t)
    for (Index& q : triangles[t])
      if (q >= first_point) q = new_index[q - first_point];
}

void SurfaceMeshState::take_back_patch(Index first_point, std::size_t first_triangle) {
  for (std::size_t t = first_triangle; t < triangles.size(); ++t) triangles[t][0] = kInvalidIndex;
  compact_patch(first_point, first_triangle);
}

namespace {

bool in_patch(const SurfaceFeatures& features, PatchId patch, Index face) {
  return features.face_patch[face] == patch;
}

// Whether x, moved onto the patch at `on`, was held at the patch's edge (not in the paper): the
// nearest point lies on an edge where the patch ends (a line to another patch, or the input's
// boundary), and x lies beyond it by more than `reach` along the surface. x stood outside the
// patch, and a point made there sits on the line, where it makes faces of no area with the
// line's own points (inv_coil at a quarter of its mean edge, where a patch tapers to a tip
// between two lines).
bool held_at_the_patch_edge(const DiscreteSurface& surface, const SurfaceFeatures& features,
                            PatchId patch, const Point& x, const Located& on, double reach) {
  const Point r = sub(x, on.closest);
  const Point& n = surface.normal(on.face);
  if (squared_norm(sub(r, scale(n, dot(r, n)))) <= reach * reach) return false;
  const Index f = index_of(on.face);
  const Triangle& t = surface.triangle(on.face);
  const std::vector<Point>& p = surface.local_points();
  const double tolerance = 1e-9 * surface.size();
  for (int k = 0; k < 3; ++k) {
    const Index g = surface.neighbours().across[f][k];
    if (g != kInvalidIndex && in_patch(features, patch, g)) continue;
    const Point on_edge = closest_point_on_segment(on.closest, p[t[k]], p[t[(k + 1) % 3]]);
    if (squared_distance(on_edge, on.closest) <= tolerance * tolerance) return true;
  }
  return false;
}

// How far past the patch's edge, in elements, a best point may stand and still be made on it:
// only rounding. A line's sides are chords of its input edges, and where the input's rim bulges
// past a chord (a bore's polygon, sampled by fewer sides), a point moved onto the rim lies on the
// far side of the chord, over the next patch; a quarter of an element let such points be made
// (occt-misc's propeller.stl: a face closed flat over the bore's bottom, 8 crossing pairs).
constexpr double kHeldReach = 1e-6;

bool uses_any(const Triangle& t, std::span<const Index> points) {
  for (const Index q : t)
    if (std::find(points.begin(), points.end(), q) != points.end()) return true;
  return false;
}

}  // namespace

// Each step looks at the faces of the patch round the face's corners, each once: a face round two
// corners is met again at the second, and one round the face the walk came from was measured at
// the step before, where it was no nearer than the face the walk moved to; a face whose ball is
// farther than the nearest so far is not measured (DiscreteSurface::cannot_be_nearer). None of
// them can be strictly nearer, so skipping them changes no step (the faces are still offered in
// the same order, ties keeping the first).
Located locate_in_patch(const DiscreteSurface& surface, const SurfaceFeatures& features,
                        PatchId patch, const Point& x, FaceId hint, int max_steps) {
  Located at;
  Index face = index_of(hint);
  at.squared_distance = surface.squared_distance_to_face(x, hint, at.closest);
  ++at.evaluations;
  Triangle previous{kInvalidIndex, kInvalidIndex, kInvalidIndex};  // the corners of the last face
  const double margin = surface.ball_margin(x);
  for (int step = 0; step < max_steps; ++step) {
    Index best = kInvalidIndex;
    double best_distance = at.squared_distance;
    Point best_closest{};
    // The faces of the patch around the face's corners: its edge neighbours and those that share
    // only a corner (where the nearest point is a corner, the nearer face may be one of them).
    const Triangle& corners = surface.triangles()[face];
    for (int k = 0; k < 3; ++k) {
      for (const Index g : surface.faces_at(corners[k])) {
        if (g == face || !in_patch(features, patch, g)) continue;
        const Triangle& t = surface.triangles()[g];
        if (uses_any(t, std::span<const Index>(corners.data(), k)) || uses_any(t, previous) ||
            surface.cannot_be_nearer(x, margin, FaceId{g}, best_distance))
          continue;
        Point closest;
        const double d = surface.squared_distance_to_face(x, FaceId{g}, closest);
        ++at.evaluations;
        if (d < best_distance) {  // strictly nearer: ties keep the first (lowest corner's) face
          best = g;
          best_distance = d;
          best_closest = closest;
        }
      }
    }
    if (best == kInvalidIndex) break;
    previous = corners;
    face = best;
    at.squared_distance = best_distance;
    at.closest = best_closest;
    ++at.walk_steps;
  }
  at.face = FaceId{face};
  return at;
}

FaceId patch_hint(const SurfaceMeshState& s, PatchId patch, Index p) {
  const FaceId host = s.host[p];
  if (host != kNoFace && in_patch(s.features, patch, index_of(host))) return host;
  if (const Index v = s.anchor[p]; v != kInvalidIndex) {
    for (const Index g : s.surface.faces_at(v))
      if (in_patch(s.features, patch, g)) return FaceId{g};
  }
  return s.features.patches[index_of(patch)].first_face;
}

namespace {

constexpr double kSqrt3Over2 = 0.8660254037844386;
constexpr double kFacingCosine = 0.0;  // 90°: points and sides behind the side's plane
// A new face must lie within this angle's cosine of the host's tangent plane (60°; not in the
// paper): a point that projects onto another sheet of the surface (the next strand of a knotted
// tube, the far wall of a thin slot) makes a face standing across the gap, which the 2-D checks
// in the side's plane cannot see.
constexpr double kMinFaceCosine = 0.5;
// A hole of three sides whose smallest angle is under this (degrees) is closed whichever way
// round the plane of S6 sees it (PatchFront::closing_point; not in the paper).
constexpr double kSliverHoleDeg = 10.0;
// Two triangles sharing an edge inside a patch whose normals differ by more than 120° fold over
// each other (PatchFront::folds_over_a_neighbour; not in the paper).
constexpr double kFoldCosine = -0.5;
// A face to an existing front point may not make a side longer than the longer of the side it
// deletes and this many times the side's target size (not in the paper). A side's element is at
// least kMinElementOverEdge of its length (front_sizes.h), and its candidates lie within
// rules.reach of that: a side longer than its target reaches farther than the target allows,
// and a face to a far point leaves a still longer side, which reaches farther again. Where the
// size drops (a narrow patch of cgal_dino, 0.0101 inside a surface of 0.067), a fan round one
// point zipped the fine front to a coarse one with sides 0.024, 0.029, 0.033, 0.041, 0.055
// long, and the zipper ran on over 0.4 (40 targets), the patch stuck among long slivers.
constexpr double kMaxNewSideOverTarget = 3.0;

// Relaxation of the acceptance rules for a side that has failed `attempts` times (not in the
// paper; as the volume front's strictness_for): later attempts accept worse faces and new points
// closer to the front.
struct SideRules {
  double min_angle_deg;   // smallest accepted angle of the new face
  double point_spacing;   // a new point keeps this fraction of d from front points
  double side_clearance;  // ... and this fraction of d from front sides
  double reach;           // front points within reach·d of the best point are candidates
};
constexpr SideRules kRules[] = {
    {30.0, 0.55, 0.35, 1.1}, {20.0, 0.45, 0.28, 1.4}, {12.0, 0.35, 0.2, 1.6},
    {6.0, 0.25, 0.12, 2.0},  {2.0, 0.15, 0.06, 2.5},  {0.0, 0.08, 0.03, 3.0},
};
constexpr int kRuleClasses = static_cast<int>(sizeof(kRules) / sizeof(kRules[0]));

// The plane of paper Figure 6: the side's midpoint and the host normal, with t along the side
// and u = n × t to its left (towards the unmeshed part of the patch).
struct SidePlane {
  Point origin, t, u, n;
  std::array<double, 2> at(const Point& x) const {
    const Point r = sub(x, origin);
    return {dot(r, t), dot(r, u)};
  }
};

struct Candidate {
  Index point;  // kInvalidIndex: the new point
  double rank;
};

class PatchFront {
 public:
  PatchFront(SurfaceMeshState& s, PatchId patch, const Box& domain, double cell,
             std::int64_t max_cells)
      : s_(s), patch_(patch), front_(s.points, domain, cell, max_cells) {}

  // One of the patch's initial sides (kept by every back-off).
  void add_initial_side(const Side& v) {
    add_side(v);
    initial_.insert({v[0], v[1]});
  }
  // The seed triangle of a patch without lines (lay_seed), before its sides.
  void add_seed(const Triangle& t) { add_triangle(t); }
  void defer(Index f) { front_.defer(f, queue_key(front_.item(f).v, target_[f])); }
  AdvancingFront<2>& front() { return front_; }
  // The area the patch's triangles cover now (those a back-off removed taken off).
  double built_area() const { return built_area_; }
  // Not in the paper: the bins become adaptive (an octree, FrontBins::Adaptive) when the points
  // the crossing check (S6) visits per query average over kCrowdedBins in a window of
  // kBinsWindow queries: the patch's sizes span far more than its cells, which were chosen from
  // its lines (on the corpus and OCCT's files at their mean edges the average stays under 18;
  // OCCT's head.stl, a scan whose folds ask for 1/3,600 of the size, reached 2,900).
  void adapt_bins_when_crowded() {
    if (bins_watch_.crowded(kBinsWindow, kCrowdedBins)) front_.use_adaptive_bins();
  }

  // S2–S10 for side f; false when no face could be built on it now.
  bool delete_side(Index f);
  // The third point of a hole of three sides that side v bounds, when nothing of the front
  // lies inside it, else kInvalidIndex (not in the paper). Such a hole is closed by its own
  // triangle, however thin: any other face on v would overlap the triangles around it, and
  // where the hole is a sliver, the plane of S6 cannot tell (its corners' projections can turn
  // the hole inside out on a curved surface, which then looks like open space).
  Index closing_point(const Side& v, const SidePlane& plane);
  // The live side leaving `at` that goes on the loop of a hole arriving at `at` from `from`
  // (kInvalidIndex when none leaves it).
  Index next_side_of_loop(Index at, Index from) const;
  // S11, the end game: closes the small hole that side f bounds by ear clipping; false when
  // the hole is not a simple loop of at most kMaxHoleSides sides or cannot be cut into ears.
  // Where the walk from f comes back to a corner it passed (two holes touching there, the walk
  // having turned into the other), that other hole is closed instead; f's own, a loop then,
  // on the next try.
  bool fill_hole(Index f);
  // Ear clipping of the hole bounded by the front sides `loop` (loop[i] leaves corners[i]).
  bool fill_loop(const std::vector<Index>& loop, const std::vector<Index>& corners);
  // The corners of the loop of front sides from `start` along its side g and on (the way on
  // at each corner as fill_hole's walk takes it, next_side_of_loop) back to `start`, start
  // first; empty when the walk meets a corner twice, finds no way on or passes kMaxHoleSides
  // corners before it is back.
  std::vector<Index> loop_from(Index start, Index g) const;
  // Whether point q lies on a loop of front sides that bounds a hole: from q back to q within
  // kMaxHoleSides sides, turning counter-clockwise about the patch's normals at its corners.
  bool on_a_hole(Index q) const;
  // The points of the other holes that touch the hole bounded by `loop` at one of its corners:
  // loops of front sides from a corner back to it, turning counter-clockwise in `plane` as a
  // hole's do (an island's turn the other way).
  std::vector<Index> points_of_touching_holes(const std::vector<Index>& loop,
                                              const std::vector<Index>& corners,
                                              const SidePlane& plane) const;
  // The back-off for side f, which failed in every class and bounds no small hole (not in the
  // paper; as the volume front's cavity re-meshing, open_cavity in core/volume/front_steps.h):
  // removes the triangles of the patch near the side, within a radius growing with each retry
  // in the same region, and puts the cavity's boundary on the front; f is queued again as new
  // if it is still on the front. False when there was nothing to remove or the region has been
  // re-opened kMaxBackOffsAtPlace times.
  bool back_off(Index f);
  // FAILED_PRECONDITION for side f: why the patch stops, where, its sizes, and the back-offs
  // tried.
  absl::Status stuck(Index f, std::string_view why, std::int64_t triangles_before,
                     std::int64_t back_offs);

 private:
  // Eq. 15 at the side's midpoint: min(delta(x), c_i · min(delta_A, delta_B)).
  double target_size(const Side& v) const {
    const Point mid = midpoint(v);
    return new_point_size(s_.field_size(mid), s_.growth, s_.point_size, v);
  }
  double element_size(const Side& v, double target) const {
    return element_size_for_target(target, norm(sub(s_.points[v[1]], s_.points[v[0]])));
  }
  double queue_key(const Side& v, double target) const {
    return queue_key_for_element(target, element_size(v, target));
  }
  // Every side goes on the front through here. Its target size (a size field query, the front's
  // costliest lookup after the walks) is measured once and kept in target_ for the side's
  // deletion, deferrals and back-offs: the side's points and their sizes do not change while
  // it is on the front, so neither does its target.
  void add_side(const Side& v) {
    const double target = target_size(v);
    const Index f = front_.add(v, queue_key(v, target));
    if (static_cast<std::size_t>(f) >= target_.size()) target_.resize(f + 1);
    target_[f] = target;
  }
  Point midpoint(const Side& v) const {
    return scale(add(s_.points[v[0]], s_.points[v[1]]), 0.5);
  }
  bool plane_of(const Side& v, FaceId& host, SidePlane& plane) const;
  // The plane of face (v, p) itself, through the side's midpoint. S6 is checked in it too (not
  // in the paper): where the patch creases (a scan's fold, sharper than the ridge angle but
  // along a ridge that ends inside the patch) the face can rise far out of the host's plane,
  // and a front side it covers there can pass beside it in the host's plane. None when the face
  // has no area in floating point (p on the side's line): such a face is never built, and its
  // plane's axes would be NaN, which the exact predicates cannot take (fuzz_surface_mesher found
  // one in the last rule class, whose smallest angle allowed is 0).
  std::optional<SidePlane> face_plane(const Side& v, Index p) const {
    const Point along = sub(s_.points[v[1]], s_.points[v[0]]);
    const Point n = cross(along, sub(s_.points[p], s_.points[v[0]]));
    const double n_length = norm(n), along_length = norm(along);
    if (!(n_length > 0) || !(along_length > 0)) return std::nullopt;
    const Point unit_n = scale(n, 1.0 / n_length);
    const Point t = scale(along, 1.0 / along_length);
    const Point u = cross(unit_n, t);
    if (!std::isfinite(squared_norm(unit_n)) || !std::isfinite(squared_norm(u)))
      return std::nullopt;
    return SidePlane{midpoint(v), t, u, unit_n};
  }
  // Whether face (v, x) lies within kMinFaceCosine of the plane (its normal near n).
  bool lies_along(const Side& v, const Point& x, const SidePlane& plane) const {
    const Point normal = cross(sub(s_.points[v[1]], s_.points[v[0]]), sub(x, s_.points[v[0]]));
    return dot(normal, plane.n) >= kMinFaceCosine * norm(normal);
  }
  // Whether face (v, p) has a new side longer than `longest` (kMaxNewSideOverTarget).
  bool lengthens_the_front(const Side& v, Index p, double longest) const {
    return squared_norm(sub(s_.points[p], s_.points[v[0]])) > longest * longest ||
           squared_norm(sub(s_.points[p], s_.points[v[1]])) > longest * longest;
  }
  // Whether face (v, x) has a shape the rules take: its smallest angle not under
  // rules.min_angle_deg, and lying along the plane.
  bool takes_shape(const Side& v, const Point& x, const SidePlane& plane,
                   const SideRules& rules) const {
    return !(triangle_min_angle_deg(s_.points[v[0]], s_.points[v[1]], x) < rules.min_angle_deg) &&
           lies_along(v, x, plane);
  }
  // The unit normal of triangle t of s_.points (zero for a degenerate one).
  Point triangle_normal(const Triangle& t) const {
    return unit_normal(s_.points[t[0]], s_.points[t[1]], s_.points[t[2]]);
  }
  // Whether point q's side of the patch faces the plane's way (its normal within 90° of the
  // plane's): the 2-D checks of S6 see only such points and sides. Where the patch curves
  // round by more (a small cylinder meshed with few sides), the points behind would project
  // onto the plane over the points in front (not in the paper; Figure 6's problem carried on).
  // A line point that the patch lies on both sides of (a crease that ends inside the patch)
  // faces the plane when a face of the patch around it does: its host may be on either side.
  bool faces_plane(Index q, const SidePlane& plane) const {
    return planes_faced(q, std::span<const SidePlane>(&plane, 1)) != 0;
  }
  // faces_plane for each of `planes` (at most 32) at once, bit k for planes[k]: the normals of
  // q's faces are looked up once for all of them.
  std::uint32_t planes_faced(Index q, std::span<const SidePlane> planes) const {
    const std::uint32_t all = (std::uint32_t{1} << planes.size()) - 1;
    std::uint32_t faced = 0;
    const Point& n = s_.surface.normal(patch_hint(s_, patch_, q));
    for (std::size_t k = 0; k < planes.size(); ++k)
      if (dot(n, planes[k].n) > kFacingCosine) faced |= std::uint32_t{1} << k;
    if (faced == all || s_.anchor[q] == kInvalidIndex) return faced;
    for (const Index g : s_.surface.faces_at(s_.anchor[q])) {
      if (!in_patch(s_.features, patch_, g)) continue;
      for (std::size_t k = 0; k < planes.size(); ++k)
        if (dot(s_.surface.normal(FaceId{g}), planes[k].n) > kFacingCosine)
          faced |= std::uint32_t{1} << k;
    }
    return faced;
  }
  // The plane of the surface at front point a: through a, normal to the mean of the unit
  // normals of the patch's triangles at a and of a's host face. Where the surface turns fast
  // round a (a cone's apex, a scan's spike) this is the axis the fan of triangles turns about,
  // which the side's plane can be far from.
  SidePlane vertex_plane(Index a, const Point& along) const;
  // Whether new face (v, p) fits the gaps the front leaves at the side's two ends: at v[0],
  // ray v[0]→p lies within the unmeshed angle from v[0]→v[1] round (counter-clockwise) to the
  // front side arriving at v[0]; at v[1] likewise, from the side leaving v[1] round to
  // v[1]→v[0]. Checked in the vertex planes with exact orientation tests (not in the paper: the
  // angle check of the classical advancing front; the crossing checks of S6 work in the side's
  // plane, which can fold a fan over itself at an apex of the surface).
  bool fits_the_gaps(const Side& v, Index p) const;
  bool fits_the_gap_at(Index apex, Index from, Index p, bool at_start) const;
  void gather(const Side& v, const SidePlane& plane, const Point& best, double d,
              const SideRules& rules);
  // Not in the paper: the far ends of the initial (line) sides at the side's two corners, as
  // candidates after those gathered (delete_side adds them in the last rule class, to a side
  // shorter than its element). A side across a strip narrower than the size, between two lines
  // sampled at the size, reaches no farther than a few of its own lengths, and its only faces
  // are to those ends: without them it stops the patch (gmsh_lever at diag / 40). Built sides'
  // ends are not added: at the dino's eyes that joined sides 10^-8 long to far points.
  void add_front_neighbours(const Side& v, const SidePlane& plane, const Point& best, double d);
  bool new_point_is_clear(const Point& x, double d, const SideRules& rules, Index f) const;
  // S6 for new face (v, p) in each of `planes` (the side's plane and the face's own): whether
  // it crosses the front in any of them. One pass over the front near the face serves both.
  bool face_crosses_front(Index f, const Side& v, Index p,
                          const std::array<SidePlane, 2>& planes, double clearance) const;
  void add_face(Index f, const Side& v, Index p);
  // Every triangle of the front goes through here: into s_ and into the incidence.
  void add_triangle(const Triangle& t);
  // Whether a triangle of the front has directed edge (a, b) (has it on its left), and, when
  // c is given, is (a, b, c).
  bool has_edge(Index a, Index b, Index c = kInvalidIndex);
  // Whether a triangle built before has a new side of face (v, p) the way the face would have
  // it, so that the two would lie over each other, or a new side is a side of a discrete line
  // the face would be on the wrong side of (the line's other patch is there), or a chord that
  // a patch meshed before has between the same two line points: wherever the plane of S6 puts
  // their points, which near a sharp corner can fold a face over a ridge (not in the paper;
  // exact, from the incidence and the lines).
  bool lies_over_a_triangle(const Side& v, Index p) {
    return has_edge(v[1], p) || has_edge(p, v[0]) || off_its_patch(v[1], p) ||
           off_its_patch(p, v[0]) || s_.chord_of_another_patch(v[1], p) ||
           s_.chord_of_another_patch(p, v[0]);
  }
  // Whether triangle t would fold over a triangle of the patch across one of its edges that is
  // not a line's side: their normals more than 120° apart (kFoldCosine) (not in the paper: the
  // input turns by less than the ridge angle there, and a face laid back onto its neighbour — the
  // two sides of a crease, a pinch of the front — lies over it, which the checks in one
  // plane cannot see; exact on the topology, the angle measured on the two triangles).
  bool folds_over_a_neighbour(const Triangle& t);
  // Whether edge (a, b) of a triangle of the patch is a line's side with the patch on its right.
  bool off_its_patch(Index a, Index b) const {
    return s_.line_sides.contains({std::min(a, b), std::max(a, b)}) && !initial_.contains({a, b});
  }
  // Whether a triangle of `cavity` (sorted) shares a directed edge with a triangle outside it:
  // the two lie over each other (S6 let the front cross itself there).
  bool overlaps_outside(const std::vector<Index>& cavity);
  // Removes the triangles `cavity` of the patch and puts the boundary of the hole they leave
  // on the front.
  void open_cavity(const std::vector<Index>& cavity);
  // The patch's triangles with a corner within `radius` of x, reached from the points `seeds`
  // through the corners within it; sorted.
  void collect_cavity(const Side& seeds, const Point& x, double radius,
                      std::vector<Index>& cavity);

  SurfaceMeshState& s_;
  PatchId patch_;
  static constexpr std::int64_t kBinsWindow = 4096;
  static constexpr std::int64_t kCrowdedBins = 64;
  mutable BinsWatch bins_watch_;  // S6's point queries and the points they visit
  AdvancingFront<2> front_;
  double built_area_ = 0.0;
  std::vector<double> target_;  // the target size (eq. 15) of each front item, by item index
  // The triangles this front built (indices into s_.triangles), by point: the back-off finds
  // the triangles near a side through them.
  SimplexIncidence<3> incidence_;
  absl::flat_hash_set<std::pair<Index, Index>> initial_;  // the initial sides, as (a, b)
  RepairCounts repairs_;
  std::vector<Side> edges_;
  std::vector<Candidate> candidates_;
  std::vector<Index> cavity_, cavity_points_;
  mutable std::vector<Index> around_;
  mutable std::vector<Index> near_;
};

bool PatchFront::plane_of(const Side& v, FaceId& host, SidePlane& plane) const {
  const Point mid = midpoint(v);
  const Located at =
      locate_in_patch(s_.surface, s_.features, patch_, mid, patch_hint(s_, patch_, v[0]));
  host = at.face;
  const Point& n = s_.surface.normal(host);                          // S3
  const Point along = sub(s_.points[v[1]], s_.points[v[0]]);
  const Point tangent = sub(along, scale(n, dot(along, n)));
  const double length = norm(tangent);
  if (!(length > 0) || !(squared_norm(n) > 0)) return false;
  plane.origin = mid;
  plane.t = scale(tangent, 1.0 / length);
  plane.u = cross(n, plane.t);
  plane.n = n;
  return true;
}

SidePlane PatchFront::vertex_plane(Index a, const Point& along) const {
  Point n = s_.surface.normal(patch_hint(s_, patch_, a));
  around_.clear();
  incidence_.elements_of(s_.triangles, a, around_);
  for (const Index t : around_) n = add(n, triangle_normal(s_.triangles[t]));
  SidePlane plane{s_.points[a], {0, 0, 0}, {0, 0, 0}, {0, 0, 0}};
  const double length = norm(n);
  if (!(length > 0)) return plane;
  plane.n = scale(n, 1.0 / length);
  const Point tangent = sub(along, scale(plane.n, dot(along, plane.n)));
  if (!(norm(tangent) > 0)) return plane;
  plane.t = scale(tangent, 1.0 / norm(tangent));
  plane.u = cross(plane.n, plane.t);
  return plane;
}

bool PatchFront::fits_the_gap_at(Index apex, Index from, Index p, bool at_start) const {
  // The front side that bounds the gap at `apex` on the far side from `from`: arriving at the
  // apex when it is the side's start, leaving it when it is the side's end; where the front
  // touches itself at the apex, the one met first turning from `from` into the unmeshed side.
  const SidePlane plane = vertex_plane(apex, sub(s_.points[from], s_.points[apex]));
  if (!(squared_norm(plane.t) > 0)) return true;  // no plane to judge in
  const std::array<double, 2> o{0.0, 0.0}, f = plane.at(s_.points[from]);
  const auto turn = [&](Index q) {  // angle from `from` to q about the apex, into the gap
    const std::array<double, 2> x = plane.at(s_.points[q]);
    double angle = std::atan2(x[1], x[0]);  // plane.t points at `from`
    if (!at_start) angle = -angle;
    return angle <= 0 ? angle + 2 * std::numbers::pi : angle;
  };
  const auto far_end = [&](Index g) {  // the side's other point, if it bounds on that side
    const Side& w = front_.item(g).v;
    const Index q = at_start ? (w[1] == apex ? w[0] : kInvalidIndex)
                             : (w[0] == apex ? w[1] : kInvalidIndex);
    return q == from ? kInvalidIndex : q;
  };
  // Where one side can bound the gap (the front passes the apex once), it does, whatever its
  // angle (finite: the points are): the angles only choose among several.
  Index bound = kInvalidIndex;
  int sides = 0;
  front_.for_each_item_at(apex, [&](Index g) {
    if (const Index q = far_end(g); q != kInvalidIndex && sides++ == 0) bound = q;
  });
  if (sides > 1) {
    double smallest = std::numeric_limits<double>::infinity();
    bound = kInvalidIndex;
    front_.for_each_item_at(apex, [&](Index g) {
      const Index q = far_end(g);
      if (q == kInvalidIndex) return;
      if (const double angle = turn(q); angle < smallest) smallest = angle, bound = q;
    });
  }
  if (bound == kInvalidIndex || bound == p) return true;  // p closes the gap
  // Within the wedge from `from` to `bound` (counter-clockwise at the start, clockwise at the
  // end), strictly.
  std::array<double, 2> first = f, last = plane.at(s_.points[bound]);
  if (!at_start) std::swap(first, last);
  const std::array<double, 2> x = plane.at(s_.points[p]);
  const int after_first = orient2d(o.data(), first.data(), x.data());
  const int before_last = orient2d(o.data(), x.data(), last.data());
  if (orient2d(o.data(), first.data(), last.data()) > 0) return after_first > 0 && before_last > 0;
  return after_first > 0 || before_last > 0;  // a gap wider than a half turn
}

bool PatchFront::fits_the_gaps(const Side& v, Index p) const {
  return fits_the_gap_at(v[0], v[1], p, true) && fits_the_gap_at(v[1], v[0], p, false);
}

void PatchFront::gather(const Side& v, const SidePlane& plane, const Point& best, double d,
                        const SideRules& rules) {
  candidates_.clear();
  const double reach = rules.reach * d;
  Box box{best, best};
  for (int a = 0; a < 3; ++a) box.lo[a] -= reach, box.hi[a] += reach;
  const std::array<double, 2> a2 = plane.at(s_.points[v[0]]), b2 = plane.at(s_.points[v[1]]);
  front_.bins().for_each_point_near(box, [&](Index q) {
    if (q == v[0] || q == v[1]) return;
    const double r = norm(sub(s_.points[q], best));
    if (r > reach || !faces_plane(q, plane)) return;
    const std::array<double, 2> q2 = plane.at(s_.points[q]);
    if (orient2d(a2.data(), b2.data(), q2.data()) <= 0) return;  // not left of the side
    candidates_.push_back({q, r / d});
  });
  // S5: a front point nearer to the best point than the spacing a new point must keep is used
  // in lieu of it; farther ones come after it. Each face's shape (takes_shape) is judged when
  // its candidate is tried: most candidates come after a new point that is taken.
  candidates_.push_back({kInvalidIndex, rules.point_spacing});
  std::stable_sort(candidates_.begin(), candidates_.end(),
                   [](const Candidate& x, const Candidate& y) {
                     if (x.rank != y.rank) return x.rank < y.rank;
                     return x.point < y.point;
                   });
}

void PatchFront::add_front_neighbours(const Side& v, const SidePlane& plane, const Point& best,
                                      double d) {
  const std::array<double, 2> a2 = plane.at(s_.points[v[0]]), b2 = plane.at(s_.points[v[1]]);
  auto consider = [&](Index q) {
    if (q == v[0] || q == v[1] || !faces_plane(q, plane)) return;
    for (const Candidate& c : candidates_)
      if (c.point == q) return;  // within reach: gathered already
    const std::array<double, 2> q2 = plane.at(s_.points[q]);
    if (orient2d(a2.data(), b2.data(), q2.data()) <= 0) return;  // not left of the side
    candidates_.push_back({q, norm(sub(s_.points[q], best)) / d});
  };
  front_.for_each_item_at(v[0], [&](Index g) {
    const Side& w = front_.item(g).v;
    if (w[1] == v[0] && initial_.contains({w[0], w[1]})) consider(w[0]);
  });
  front_.for_each_item_at(v[1], [&](Index g) {
    const Side& w = front_.item(g).v;
    if (w[0] == v[1] && initial_.contains({w[0], w[1]})) consider(w[1]);
  });
}

bool PatchFront::new_point_is_clear(const Point& x, double d, const SideRules& rules,
                                    Index f) const {
  const double spacing = rules.point_spacing * d, clearance = rules.side_clearance * d;
  const double r = std::max(spacing, clearance);
  const Box box{{x[0] - r, x[1] - r, x[2] - r}, {x[0] + r, x[1] + r, x[2] + r}};
  bool clear = true;
  front_.bins().for_each_point_near(box, [&](Index q) {
    if (clear && squared_norm(sub(s_.points[q], x)) < spacing * spacing) clear = false;
  });
  if (!clear) return false;
  return !front_.bins().find_item_near(box, [&](Index g) {
    if (g == f) return false;
    const Side& w = front_.item(g).v;
    const Point c = closest_point_on_segment(x, s_.points[w[0]], s_.points[w[1]]);
    return squared_norm(sub(c, x)) < clearance * clearance;
  });
}

// Exact 2-D segment tests on the projected points (the projection rounds, the tests on its
// results do not: every decision is consistent).
bool segments_cross(const std::array<double, 2>& p, const std::array<double, 2>& q,
                    const std::array<double, 2>& r, const std::array<double, 2>& s) {
  const int o1 = orient2d(p.data(), q.data(), r.data());
  const int o2 = orient2d(p.data(), q.data(), s.data());
  const int o3 = orient2d(r.data(), s.data(), p.data());
  const int o4 = orient2d(r.data(), s.data(), q.data());
  if (o1 * o2 < 0 && o3 * o4 < 0) return true;  // proper crossing
  auto on = [](const std::array<double, 2>& a, const std::array<double, 2>& b,
               const std::array<double, 2>& c) {  // c on segment ab, given collinear
    return std::min(a[0], b[0]) <= c[0] && c[0] <= std::max(a[0], b[0]) &&
           std::min(a[1], b[1]) <= c[1] && c[1] <= std::max(a[1], b[1]);
  };
  return (o1 == 0 && on(p, q, r)) || (o2 == 0 && on(p, q, s)) || (o3 == 0 && on(r, s, p)) ||
         (o4 == 0 && on(r, s, q));
}

bool PatchFront::face_crosses_front(Index f, const Side& v, Index p,
                                    const std::array<SidePlane, 2>& planes,
                                    double clearance) const {
  using Point2 = std::array<double, 2>;
  std::array<Point2, 2> a, b, c;  // the face's corners in each plane
  for (std::size_t k = 0; k < planes.size(); ++k) {
    a[k] = planes[k].at(s_.points[v[0]]);
    b[k] = planes[k].at(s_.points[v[1]]);
    c[k] = planes[k].at(s_.points[p]);
    if (orient2d(a[k].data(), b[k].data(), c[k].data()) <= 0) return true;
  }
  // A new side that is already on the front the same way round has the patch's meshed part
  // on the new face's side: the face would lie over a triangle built before. The crossing test
  // below cannot see it (a front side sharing an end with a new side is not tested).
  if (front_.find({v[0], p}) || front_.find({p, v[1]})) return true;
  Box box{s_.points[v[0]], s_.points[v[0]]};
  enclose(box, s_.points[v[1]]);
  enclose(box, s_.points[p]);
  // A point strictly inside the new face, or on its two new sides, covers front space; one
  // nearer than `clearance` to a new side would leave a sliver gap (not in the paper: a front
  // point a rounding's width outside a new side, a line's middle point beside a face across
  // both its sides, passes the exact test).
  box = grown(box, clearance);
  const double clearance2 = clearance * clearance;
  bool covered = false;
  ++bins_watch_.queries;
  front_.bins().for_each_point_near(box, [&](Index q) {
    ++bins_watch_.points;
    if (covered || q == v[0] || q == v[1] || q == p) return;
    const Point& xq = s_.points[q];
    if (squared_norm(sub(closest_point_on_segment(xq, s_.points[v[0]], s_.points[p]), xq)) <
            clearance2 ||
        squared_norm(sub(closest_point_on_segment(xq, s_.points[p], s_.points[v[1]]), xq)) <
            clearance2) {
      covered = true;
      return;
    }
    const std::uint32_t faced = planes_faced(q, planes);
    for (std::size_t k = 0; k < planes.size() && !covered; ++k) {
      if (!(faced >> k & 1)) continue;
      const Point2 x = planes[k].at(xq);
      covered = orient2d(a[k].data(), b[k].data(), x.data()) >= 0 &&
                orient2d(b[k].data(), c[k].data(), x.data()) >= 0 &&
                orient2d(c[k].data(), a[k].data(), x.data()) >= 0;
    }
  });
  if (covered) return true;
  // S6: the new sides (a, p) and (p, b) against every front side near them.
  return front_.bins().find_item_near(box, [&](Index g) {
    if (g == f) return false;
    const Side& w = front_.item(g).v;
    std::uint32_t faced = planes_faced(w[0], planes);
    if (faced != (1u << planes.size()) - 1) faced |= planes_faced(w[1], planes);
    const auto shares = [&](Index e0, Index e1) {
      return w[0] == e0 || w[0] == e1 || w[1] == e0 || w[1] == e1;
    };
    for (std::size_t k = 0; k < planes.size(); ++k) {
      if (!(faced >> k & 1)) continue;
      const Point2 x = planes[k].at(s_.points[w[0]]), y = planes[k].at(s_.points[w[1]]);
      if (!shares(v[0], p) && segments_cross(a[k], c[k], x, y)) return true;
      if (!shares(p, v[1]) && segments_cross(c[k], b[k], x, y)) return true;
    }
    return false;
  });
}

void PatchFront::add_triangle(const Triangle& t) {
  built_area_ += triangle_area(s_.points[t[0]], s_.points[t[1]], s_.points[t[2]]);
  s_.add_triangle(t, patch_);
  incidence_.add(s_.triangles, static_cast<Index>(s_.triangles.size() - 1));
}

void PatchFront::add_face(Index f, const Side& v, Index p) {
  add_triangle({v[0], v[1], p});                                              // S7
  front_.remove(f);                                                           // S10
  for (const Side& side : {Side{v[0], p}, Side{p, v[1]}}) {
    if (auto g = front_.find({side[1], side[0]})) {
      front_.remove(*g);
    } else {
      add_side(side);                                                         // S9
    }
  }
}

// Not in the paper (as the volume front's pocket fill, F11): where the last sides of a region
// cannot take a new point, the hole they bound is cut into ears: the best-shaped ear (largest
// smallest angle) first, each checked in the hole's mean plane with exact tests. Up to 256 sides
// (O(n^3) tests at most, ~0.2 s): a ledge narrower than the size, its lines split finer until
// their sides no longer cross (crossing_sides), leaves a strip of ~60 sides that no new point fits
// (gmsh_lever at its mean edge; 32 left it stuck); at a quarter of its mean edge, its lines split
// at the ledge's own size (the smaller of their two sides', curvature_sizes.h), over 64.
constexpr std::size_t kMaxHoleSides = 256;
// The patch front's bins (mesh_patch): at most this many cells per triangle the patch may build,
// and this many more.
constexpr std::int64_t kCellsPerTriangle = 16;
constexpr std::int64_t kMinCells = 4096;
// A corner of the hole this near an ear's diagonal, as a fraction of the diagonal's length, lies
// on it (a rounding's width; not in the paper).
constexpr double kOnDiagonal = 1e-9;
// Whether x lies on segment (a, c) within kOnDiagonal of its length.
bool on_diagonal(const Point& x, const Point& a, const Point& c) {
  return norm(sub(closest_point_on_segment(x, a, c), x)) <= kOnDiagonal * norm(sub(c, a));
}

Index PatchFront::next_side_of_loop(Index at, Index from) const {
  Index leaving = kInvalidIndex, count = 0;
  front_.for_each_item_at(at, [&](Index g) {
    if (front_.item(g).v[0] == at) leaving = g, ++count;
  });
  if (count <= 1) return leaving;
  // Where the front touches itself at `at`, the loop of the hole goes on along the side that
  // leaves the smallest angle, turning counter-clockwise about the patch's normal there, from
  // it to the way back to `from`: the other sides at `at` belong to other loops.
  const Point& n = s_.surface.normal(patch_hint(s_, patch_, at));
  const Point back = sub(s_.points[from], s_.points[at]);
  double smallest = std::numeric_limits<double>::infinity();
  leaving = kInvalidIndex;
  front_.for_each_item_at(at, [&](Index g) {
    if (front_.item(g).v[0] != at) return;
    const Point out = sub(s_.points[front_.item(g).v[1]], s_.points[at]);
    double angle = std::atan2(dot(cross(out, back), n), dot(out, back));
    if (angle <= 0) angle += 2 * M_PI;
    if (angle < smallest) smallest = angle, leaving = g;
  });
  return leaving;
}

bool PatchFront::fill_hole(Index f) {
  // The loop: from each side's end, the one live side leaving it.
  std::vector<Index> loop = {f};
  std::vector<Index> corners = {front_.item(f).v[0]};
  Index at = front_.item(f).v[1];
  while (at != corners[0]) {
    // A loop through a point twice is two holes touching there, which ears cannot cut as one:
    // the walk turned into the other hole at `at` (the way on is chosen by the angle about the
    // patch's normal there, which at a point where two sheets of the patch meet, as on a wing's
    // thin edge, can be either's), and has come round it; that hole is closed alone (not in the
    // paper). Libcgal-demo's boeing: two holes of four sides touching at a point of the wing's
    // edge stopped patch 1's front 8 sides short of closing.
    if (const auto again = std::find(corners.begin(), corners.end(), at);
        again != corners.end()) {
      const auto first = static_cast<std::size_t>(again - corners.begin());
      return fill_loop({loop.begin() + static_cast<std::ptrdiff_t>(first), loop.end()},
                       {corners.begin() + static_cast<std::ptrdiff_t>(first), corners.end()});
    }
    const Index leaving = next_side_of_loop(at, corners.back());
    if (leaving == kInvalidIndex || loop.size() >= kMaxHoleSides) return false;
    loop.push_back(leaving);
    corners.push_back(at);
    at = front_.item(leaving).v[1];
  }
  return fill_loop(loop, corners);
}

bool PatchFront::fill_loop(const std::vector<Index>& loop, const std::vector<Index>& corners) {
  if (corners.size() < 3) return false;
  // The hole's plane: the mean of its corners' normals on the patch.
  Point n{0, 0, 0}, centre{0, 0, 0};
  for (const Index q : corners) {
    n = add(n, s_.surface.normal(patch_hint(s_, patch_, q)));
    centre = add(centre, s_.points[q]);
  }
  if (!(norm(n) > 0)) return false;
  n = scale(n, 1.0 / norm(n));
  centre = scale(centre, 1.0 / static_cast<double>(corners.size()));
  Point t = sub(s_.points[corners[1]], s_.points[corners[0]]);
  t = sub(t, scale(n, dot(t, n)));
  if (!(norm(t) > 0)) return false;
  const SidePlane plane{centre, scale(t, 1.0 / norm(t)), cross(n, scale(t, 1.0 / norm(t))), n};
  std::vector<std::array<double, 2>> xy;
  for (const Index q : corners) xy.push_back(plane.at(s_.points[q]));
  // No other front point may lie in the hole (an island of front inside it).
  Box box = empty_box();
  for (const Index q : corners) enclose(box, s_.points[q]);
  bool island = false;
  const std::vector<Index> touching = points_of_touching_holes(loop, corners, plane);
  front_.bins().for_each_point_near(box, [&](Index q) {
    if (island || std::find(corners.begin(), corners.end(), q) != corners.end() ||
        std::find(touching.begin(), touching.end(), q) != touching.end())
      return;
    const std::array<double, 2> x = plane.at(s_.points[q]);
    int winding = 0;  // crossings of a ray along +x from q with the loop
    for (std::size_t i = 0; i < xy.size(); ++i) {
      const auto& a = xy[i];
      const auto& b = xy[(i + 1) % xy.size()];
      if ((a[1] > x[1]) != (b[1] > x[1])) {
        const int o = orient2d(a.data(), b.data(), x.data());
        if ((b[1] > a[1]) == (o > 0)) ++winding;
      }
    }
    // Another hole is no island, though its points may fall inside this one in the plane (not
    // in the paper): on a patch that bends where two of its lines run a hair apart, as along
    // the strips of boeing's wing edges, the holes on either side of a strip overlap in the
    // mean plane of either. An island inside a hole is bounded by a loop turning the other way
    // (its meshed part on the loop's left), so a point on a hole's loop is not one.
    island = winding % 2 == 1 && !on_a_hole(q);
  });
  if (island) return false;
  // Ear clipping.
  std::vector<std::size_t> ring(corners.size());
  for (std::size_t i = 0; i < ring.size(); ++i) ring[i] = i;
  std::vector<Triangle> ears;
  while (ring.size() > 3) {
    double best_angle = -1;
    std::size_t best = 0;
    for (std::size_t i = 0; i < ring.size(); ++i) {
      const std::size_t a = ring[(i + ring.size() - 1) % ring.size()], b = ring[i],
                        c = ring[(i + 1) % ring.size()];
      if (orient2d(xy[a].data(), xy[b].data(), xy[c].data()) <= 0) continue;
      if (s_.chord_of_another_patch(corners[a], corners[c])) continue;
      bool empty = true;
      for (const std::size_t j : ring) {
        if (j == a || j == b || j == c) continue;
        if (orient2d(xy[a].data(), xy[b].data(), xy[j].data()) >= 0 &&
            orient2d(xy[b].data(), xy[c].data(), xy[j].data()) >= 0 &&
            orient2d(xy[c].data(), xy[a].data(), xy[j].data()) >= 0)
          empty = false;
      }
      if (!empty) continue;
      // Nor on its diagonal in space, the ear's own corner b included, where the rounding of
      // the plane's coordinates can put a point a hair outside: line points split along one
      // straight input edge lie on the chord between two of them. An ear with b on it has no
      // area and faces any way (cgal_bones at 1.4 times its mean edge: an ear on three line
      // points, 2.3e-18 in area, turned over, left a vertex with two fans); one with another
      // corner on it covers that point with an edge along the line and leaves a hole of no area
      // (gmsh_lever with its lines split at their turning vertices, an experiment).
      for (const std::size_t j : ring)
        if (j != a && j != c &&
            on_diagonal(s_.points[corners[j]], s_.points[corners[a]], s_.points[corners[c]]))
          empty = false;
      if (!empty) continue;
      double angle = triangle_min_angle_deg(s_.points[corners[a]], s_.points[corners[b]],
                                            s_.points[corners[c]]);
      // With four corners left, the ear decides the last triangle too: both are judged, so
      // that three points along a straight line are not left as the last one (cgal_homer at
      // half its mean edge: a last triangle of 1e-13 degrees).
      if (ring.size() == 4) {
        const std::size_t d = ring[(i + 2) % ring.size()];
        if (orient2d(xy[c].data(), xy[d].data(), xy[a].data()) <= 0) continue;
        angle = std::min(angle, triangle_min_angle_deg(s_.points[corners[c]],
                                                       s_.points[corners[d]],
                                                       s_.points[corners[a]]));
      }
      if (angle > best_angle) best_angle = angle, best = i;
    }
    if (best_angle < 0) return false;
    const std::size_t a = ring[(best + ring.size() - 1) % ring.size()], b = ring[best],
                      c = ring[(best + 1) % ring.size()];
    ears.push_back({corners[a], corners[b], corners[c]});
    ring.erase(ring.begin() + static_cast<std::ptrdiff_t>(best));
  }
  if (orient2d(xy[ring[0]].data(), xy[ring[1]].data(), xy[ring[2]].data()) <= 0) return false;
  // The last ear, too, must have area in space (a hole of three sides along a line).
  if (on_diagonal(s_.points[corners[ring[1]]], s_.points[corners[ring[0]]],
                  s_.points[corners[ring[2]]]))
    return false;
  ears.push_back({corners[ring[0]], corners[ring[1]], corners[ring[2]]});
  for (const Index g : loop) front_.remove(g);
  for (const Triangle& ear : ears) add_triangle(ear);
  return true;
}

std::vector<Index> PatchFront::points_of_touching_holes(const std::vector<Index>& loop,
                                                        const std::vector<Index>& corners,
                                                        const SidePlane& plane) const {
  std::vector<Index> points;
  for (const Index c : corners) {
    std::vector<Index> leaving;
    front_.for_each_item_at(c, [&](Index g) {
      if (front_.item(g).v[0] == c && std::find(loop.begin(), loop.end(), g) == loop.end())
        leaving.push_back(g);
    });
    for (const Index g : leaving) {
      const std::vector<Index> other = loop_from(c, g);
      if (other.size() < 3 || other.size() >= kMaxHoleSides) continue;
      double twice_area = 0.0;  // the shoelace sum in the plane: > 0 counter-clockwise
      for (std::size_t i = 0; i < other.size(); ++i) {
        const std::array<double, 2> a = plane.at(s_.points[other[i]]);
        const std::array<double, 2> b = plane.at(s_.points[other[(i + 1) % other.size()]]);
        twice_area += a[0] * b[1] - a[1] * b[0];
      }
      if (twice_area > 0) points.insert(points.end(), other.begin() + 1, other.end());
    }
  }
  return points;
}

std::vector<Index> PatchFront::loop_from(Index start, Index g) const {
  std::vector<Index> loop = {start};
  Index at = front_.item(g).v[1];
  while (at != start) {
    if (loop.size() >= kMaxHoleSides || std::find(loop.begin(), loop.end(), at) != loop.end())
      return {};
    const Index next = next_side_of_loop(at, loop.back());
    if (next == kInvalidIndex) return {};
    loop.push_back(at);
    at = front_.item(next).v[1];
  }
  return loop;
}

bool PatchFront::on_a_hole(Index q) const {
  std::vector<Index> leaving;
  front_.for_each_item_at(q, [&](Index g) {
    if (front_.item(g).v[0] == q) leaving.push_back(g);
  });
  for (const Index g : leaving) {
    const std::vector<Index> loop = loop_from(q, g);
    if (loop.size() < 3) continue;
    // The loop's vector area against the patch's normals at its corners.
    Point area{0, 0, 0}, normal{0, 0, 0};
    const Point& origin = s_.points[loop[0]];
    for (std::size_t i = 0; i < loop.size(); ++i) {
      area = add(area, cross(sub(s_.points[loop[i]], origin),
                             sub(s_.points[loop[(i + 1) % loop.size()]], origin)));
      normal = add(normal, s_.surface.normal(patch_hint(s_, patch_, loop[i])));
    }
    if (dot(area, normal) > 0) return true;
  }
  return false;
}

Index PatchFront::closing_point(const Side& v, const SidePlane& plane) {
  Index closing = kInvalidIndex;
  front_.for_each_item_at(v[1], [&](Index g) {
    const Side& w = front_.item(g).v;
    if (closing == kInvalidIndex && w[0] == v[1] && w[1] != v[0] && front_.find({w[1], v[0]}))
      closing = w[1];
  });
  if (closing == kInvalidIndex) return kInvalidIndex;
  // The three sides may instead bound an island: the seed triangle, whose sides face out, or
  // another patch inside this one, whose lines give this patch sides that face out. The loop
  // then turns clockwise in the plane. A clockwise loop is taken for a hole only when it is a
  // sliver the plane cannot judge, not the reverse of a triangle there, and either the whole
  // front or made of sides the front built (a line's sides say on which side the patch is).
  const std::array<double, 2> a = plane.at(s_.points[v[0]]), b = plane.at(s_.points[v[1]]),
                              c = plane.at(s_.points[closing]);
  const int turn = orient2d(a.data(), b.data(), c.data()) > 0 ? 1 : -1;
  if (turn < 0) {
    const bool built = !initial_.contains({v[0], v[1]}) && !initial_.contains({v[1], closing}) &&
                       !initial_.contains({closing, v[0]});
    if (triangle_min_angle_deg(s_.points[v[0]], s_.points[v[1]], s_.points[closing]) >=
            kSliverHoleDeg ||
        has_edge(v[1], v[0], closing) || !(built || front_.size() == 3))
      return kInvalidIndex;
  }
  // An island of front inside the three sides (a hole of the patch smaller than the loop
  // around it) keeps the loop open.
  Box box{s_.points[v[0]], s_.points[v[0]]};
  enclose(box, s_.points[v[1]]);
  enclose(box, s_.points[closing]);
  bool island = false;
  front_.bins().for_each_point_near(box, [&](Index q) {
    if (island || q == v[0] || q == v[1] || q == closing) return;
    const std::array<double, 2> x = plane.at(s_.points[q]);
    island = turn * orient2d(a.data(), b.data(), x.data()) > 0 &&
             turn * orient2d(b.data(), c.data(), x.data()) > 0 &&
             turn * orient2d(c.data(), a.data(), x.data()) > 0;
  });
  return island ? kInvalidIndex : closing;
}

bool PatchFront::delete_side(Index f) {
  const Side v = front_.item(f).v;
  const SideRules& rules = kRules[std::min<int>(front_.item(f).attempts, kRuleClasses - 1)];
  FaceId host;
  SidePlane plane;
  if (!plane_of(v, host, plane)) return false;
  if (const Index y = closing_point(v, plane);
      y != kInvalidIndex && !folds_over_a_neighbour({v[0], v[1], y})) {
    add_face(f, v, y);
    return true;
  }
  const double target = target_[f];
  const double d = element_size(v, target);
  const double length = norm(sub(s_.points[v[1]], s_.points[v[0]]));
  // S4: the best point, at the height that makes both new sides d long, moved onto the patch.
  const double height = std::sqrt(std::max(d * d - 0.25 * length * length, 0.0));
  const Point above = add(plane.origin, scale(plane.u, std::max(height, 0.5 * kSqrt3Over2 * d)));
  const Located on = locate_in_patch(s_.surface, s_.features, patch_, above, host);  // S8
  const Point best = on.closest;
  gather(v, plane, best, d, rules);                                          // S5
  if (d < target && front_.item(f).attempts >= kRuleClasses - 1)  // not in the paper
    add_front_neighbours(v, plane, best, d);
  for (const Candidate& c : candidates_) {
    Index p = c.point;
    if (p == kInvalidIndex) {
      if (held_at_the_patch_edge(s_.surface, s_.features, patch_, above, on, kHeldReach * d) ||
          !new_point_is_clear(best, d, rules, f))
        continue;
      p = s_.add_point(best, new_point_size(s_.field_size(best), s_.growth, s_.point_size, v),
                       on.face, kInvalidIndex);
      if (!takes_shape(v, best, plane, rules)) {
        s_.drop_last_point();
        continue;
      }
    } else if (!takes_shape(v, s_.points[p], plane, rules) ||
               lengthens_the_front(v, p, std::max(length, kMaxNewSideOverTarget * target))) {
      continue;
    }
    const std::optional<SidePlane> own = face_plane(v, p);
    if (own && !face_crosses_front(f, v, p, {plane, *own}, rules.side_clearance * d) &&  // S6
        !lies_over_a_triangle(v, p) && fits_the_gaps(v, p) &&
        !folds_over_a_neighbour({v[0], v[1], p})) {
      add_face(f, v, p);
      return true;
    }
    if (c.point == kInvalidIndex) s_.drop_last_point();
  }
  return false;
}

// The back-off's reach (not in the paper): the cavity of the k-th back-off in a region holds
// the triangles with a corner within (1 + k)·d of the side's midpoint, d the larger of the
// side's length and its target size; a region is re-opened at most kMaxBackOffsAtPlace times
// (as the volume front's kMaxCavityRings; a radius passed over because its cavity overlaps the
// triangles beyond counts as one), after which the side stops the patch.
constexpr int kMaxBackOffsAtPlace = 6;

void PatchFront::collect_cavity(const Side& seeds, const Point& x, double radius,
                                std::vector<Index>& cavity) {
  cavity.clear();
  cavity_points_.clear();
  absl::flat_hash_set<Index> in_cavity, seen;  // membership only: the order is the vectors'
  const double r2 = radius * radius;
  // From the side's corners, through the triangles at each point reached, to their corners
  // within the radius: a search of the region, never of the whole patch; and along the mesh,
  // so that another sheet of the surface near in space (the next strand of a knotted tube)
  // is left alone.
  cavity_points_ = {seeds[0], seeds[1]};
  seen.insert(cavity_points_.begin(), cavity_points_.end());
  for (std::size_t i = 0; i < cavity_points_.size(); ++i) {
    around_.clear();
    incidence_.elements_of(s_.triangles, cavity_points_[i], around_);
    for (const Index t : around_) {
      if (!in_cavity.insert(t).second) continue;
      cavity.push_back(t);
      for (const Index q : s_.triangles[t])
        if (squared_norm(sub(s_.points[q], x)) <= r2 && seen.insert(q).second)
          cavity_points_.push_back(q);
    }
  }
  std::sort(cavity.begin(), cavity.end());
}

bool PatchFront::has_edge(Index a, Index b, Index c) {
  around_.clear();
  incidence_.elements_of(s_.triangles, a, around_);
  for (const Index t : around_) {
    const Triangle& k = s_.triangles[t];
    for (int e = 0; e < 3; ++e)
      if (k[e] == a && k[(e + 1) % 3] == b && (c == kInvalidIndex || k[(e + 2) % 3] == c))
        return true;
  }
  return false;
}

bool PatchFront::folds_over_a_neighbour(const Triangle& t) {
  const Point n = triangle_normal(t);
  for (int e = 0; e < 3; ++e) {
    const Index a = t[e], b = t[(e + 1) % 3];
    if (s_.line_sides.contains({std::min(a, b), std::max(a, b)})) continue;
    around_.clear();
    incidence_.elements_of(s_.triangles, b, around_);
    for (const Index u : around_) {
      const Triangle& k = s_.triangles[u];
      for (int g = 0; g < 3; ++g)
        if (k[g] == b && k[(g + 1) % 3] == a && dot(n, triangle_normal(k)) < kFoldCosine)
          return true;
    }
  }
  return false;
}

bool PatchFront::overlaps_outside(const std::vector<Index>& cavity) {
  for (const Index t : cavity) {
    const Triangle& k = s_.triangles[t];
    for (int e = 0; e < 3; ++e) {
      const Index a = k[e], b = k[(e + 1) % 3];
      around_.clear();
      incidence_.elements_of(s_.triangles, a, around_);
      for (const Index u : around_) {
        if (std::binary_search(cavity.begin(), cavity.end(), u)) continue;
        const Triangle& w = s_.triangles[u];
        for (int f = 0; f < 3; ++f)
          if (w[f] == a && w[(f + 1) % 3] == b) return true;
      }
    }
  }
  return false;
}

void PatchFront::open_cavity(const std::vector<Index>& cavity) {
  edges_.clear();
  for (const Index t : cavity) {
    const Triangle k = s_.triangles[t];
    built_area_ -= triangle_area(s_.points[k[0]], s_.points[k[1]], s_.points[k[2]]);
    incidence_.remove(s_.triangles, t);
    s_.triangles[t][0] = kInvalidIndex;
    for (int e = 0; e < 3; ++e) {
      edges_.push_back({k[e], k[(e + 1) % 3]});
      edges_.push_back({k[(e + 1) % 3], k[e]});
    }
  }
  std::sort(edges_.begin(), edges_.end());
  edges_.erase(std::unique(edges_.begin(), edges_.end()), edges_.end());
  // Side (a, b) belongs on the front when no triangle is on its left (the unmeshed side) and
  // one is on its right, or it is one of the patch's initial sides (a line's, or the seed's).
  // Decided from the remaining triangles rather than by flipping the sides the front holds, so
  // that the cavity's boundary is right even where the front had laid triangles over each
  // other before it got stuck (a fault of S6 this does not mend, but must not spread).
  for (const Side& side : edges_) {
    const bool wanted = !has_edge(side[0], side[1]) &&
                        (has_edge(side[1], side[0]) || initial_.contains({side[0], side[1]}));
    if (wanted) {
      if (!front_.find(side)) add_side(side);
    } else {
      // All copies: where triangles were laid twice, the front can hold a side twice.
      while (const std::optional<Index> g = front_.find(side)) front_.remove(*g);
    }
  }
}

bool PatchFront::back_off(Index f) {
  const Side v = front_.item(f).v;
  const std::uint32_t stamp = front_.item(f).stamp;
  const double d = std::max(target_[f], norm(sub(s_.points[v[1]], s_.points[v[0]])));
  if (!(d > 0)) return false;
  const Point x = midpoint(v);
  int& count = repairs_.at(x, d);
  // A cavity whose triangles overlap triangles outside it cannot be re-meshed (the front
  // would be rebuilt over them and run away): a larger one is tried.
  do {
    if (count >= kMaxBackOffsAtPlace) return false;
    ++count;
    collect_cavity(v, x, (1.0 + count) * d, cavity_);
    if (cavity_.empty()) return false;
  } while (overlaps_outside(cavity_));
  open_cavity(cavity_);
  const FrontItem<2>& item = front_.item(f);
  if (item.alive && item.stamp == stamp) front_.requeue(f, queue_key(v, target_[f]));
  return true;
}

absl::Status PatchFront::stuck(Index f, std::string_view why, std::int64_t triangles_before,
                               std::int64_t back_offs) {
  const Side v = front_.item(f).v;
  const Point x = s_.surface.to_global(s_.points[v[0]]);
  s_.stopped_at = SurfaceMeshState::StoppedAt{
      s_.points[v[0]],
      3.0 * std::max(target_[f], norm(sub(s_.points[v[1]], s_.points[v[0]])))};
  return absl::FailedPreconditionError(absl::StrFormat(
      "the surface front of patch %d (input tag %d) got stuck (%s) at side (%d, %d) near (%g, "
      "%g, %g), %g long, size wanted %g, after %d back-offs in the patch; %d triangles built in "
      "the patch (some later removed by back-offs), %d sides left",
      index_of(patch_), s_.features.patches[index_of(patch_)].tag, why, v[0], v[1], x[0], x[1],
      x[2], norm(sub(s_.points[v[1]], s_.points[v[0]])), target_[f], back_offs,
      static_cast<std::int64_t>(s_.triangles.size()) - triangles_before, front_.size()));
}

// A patch without lines (a closed smooth surface: a sphere, a torus) has no front to start
// from: a seed triangle of the wanted size is laid on its first face, and its sides, turned
// outward, are the front (not in the paper, which meshes patches bounded by lines).
Triangle lay_seed(SurfaceMeshState& s, PatchId patch, std::vector<Side>& sides) {
  const FaceId face = s.features.patches[index_of(patch)].first_face;
  const Triangle& t = s.surface.triangle(face);
  const std::vector<Point>& p = s.surface.local_points();
  const Point& c = s.surface.centroid(face);
  const double h = s.field_size(c);
  const Point& n = s.surface.normal(face);
  Point e = sub(p[t[1]], p[t[0]]);
  e = scale(e, 1.0 / norm(e));
  const Point f = cross(n, e);
  Index ids[3];
  for (int k = 0; k < 3; ++k) {
    const double angle = 2.0 * std::numbers::pi * k / 3.0;
    const Point x = add(c, scale(add(scale(e, std::cos(angle)), scale(f, std::sin(angle))),
                                 h / std::sqrt(3.0)));
    const Located on = locate_in_patch(s.surface, s.features, patch, x, face);
    ids[k] = s.add_point(on.closest, h, on.face, kInvalidIndex);
  }
  sides = {{ids[1], ids[0]}, {ids[2], ids[1]}, {ids[0], ids[2]}};
  return {ids[0], ids[1], ids[2]};
}

}  // namespace

std::vector<std::pair<std::size_t, std::size_t>> crossing_sides(const SurfaceMeshState& s,
                                                                PatchId patch,
                                                                std::span<const Side> sides) {
  std::vector<std::pair<std::size_t, std::size_t>> crossing;
  if (sides.size() < 2) return crossing;
  double total = 0.0;
  for (const Side& v : sides) total += norm(sub(s.points[v[1]], s.points[v[0]]));
  const double cell = total / static_cast<double>(sides.size());
  if (!(cell > 0.0)) return crossing;
  const auto side_box = [&](const Side& v) {
    Box box{s.points[v[0]], s.points[v[0]]};
    enclose(box, s.points[v[1]]);
    return box;
  };
  Box domain = empty_box();
  for (const Side& v : sides) enclose(domain, side_box(v));
  // Cells of the sides' mean length, at most a few per side: O(n) memory and, for sides of
  // similar lengths, O(1) sides per query.
  FrontBins bins(domain, cell, 16 * static_cast<std::int64_t>(sides.size()) + 4096);
  for (std::size_t i = 0; i < sides.size(); ++i)
    bins.insert_item(static_cast<Index>(i), side_box(sides[i]));
  std::vector<Index> near;
  for (std::size_t i = 0; i < sides.size(); ++i) {
    const Side& v = sides[i];
    const Point& a = s.points[v[0]];
    const Point& b = s.points[v[1]];
    const double length = norm(sub(b, a));
    const Point& n = s.surface.normal(patch_hint(s, patch, v[0]));
    Point u = sub(b, a);
    u = sub(u, scale(n, dot(u, n)));
    if (!(norm(u) > 0.0)) continue;
    u = scale(u, 1.0 / norm(u));
    const Point w = cross(n, u);
    const auto in_plane = [&](const Point& x) {
      const Point r = sub(x, a);
      return std::array<double, 2>{dot(r, u), dot(r, w)};
    };
    const std::array<double, 2> p = in_plane(a), q = in_plane(b);
    // A side whose points lie within `length` of v's plane and that crosses v in that plane
    // passes within `length` of v: its box meets v's box grown by `length`.
    const Box reach = grown(side_box(v), length);
    near.clear();
    bins.items_near(reach, near);  // each side once
    for (const Index found : near) {
      const auto j = static_cast<std::size_t>(found);
      if (j <= i) continue;
      const Side& x = sides[j];
      if (x[0] == v[0] || x[0] == v[1] || x[1] == v[0] || x[1] == v[1]) continue;
      const Point& c0 = s.points[x[0]];
      const Point& c1 = s.points[x[1]];
      if (std::abs(dot(sub(c0, a), n)) > length || std::abs(dot(sub(c1, a), n)) > length)
        continue;
      if (segments_cross(p, q, in_plane(c0), in_plane(c1))) crossing.push_back({i, j});
    }
  }
  return crossing;
}

// The patch's triangles from `first` on are a closed cover of the region its initial sides
// bound: every directed edge used once, and its reverse too unless it is an initial side, which
// every one is (not in the paper: a check of the result, so that a fault of the front is a
// FAILED_PRECONDITION naming where, never a surface with a hole or a fold). O(N log N).
absl::Status check_patch_closed(const SurfaceMeshState& s, PatchId patch,
                                const std::vector<Side>& sides, std::size_t first) {
  std::vector<Side> edges;
  edges.reserve(3 * (s.triangles.size() - first));
  for (std::size_t t = first; t < s.triangles.size(); ++t)
    for (int e = 0; e < 3; ++e) edges.push_back({s.triangles[t][e], s.triangles[t][(e + 1) % 3]});
  std::sort(edges.begin(), edges.end());
  std::vector<Side> initial = sides;
  std::sort(initial.begin(), initial.end());
  const auto fault = [&](const Side& e, std::string_view what) {
    const Point x = s.surface.to_global(s.points[e[0]]);
    return absl::FailedPreconditionError(absl::StrFormat(
        "the surface front of patch %d (input tag %d) did not close it: edge (%d, %d) near (%g, "
        "%g, %g) %s",
        index_of(patch), s.features.patches[index_of(patch)].tag, e[0], e[1], x[0], x[1], x[2],
        what));
  };
  for (std::size_t i = 0; i < edges.size(); ++i) {
    const Side& e = edges[i];
    if (i + 1 < edges.size() && edges[i + 1] == e)
      return fault(e, "is used the same way by two triangles (they overlap)");
    if (!std::binary_search(edges.begin(), edges.end(), Side{e[1], e[0]}) &&
        !std::binary_search(initial.begin(), initial.end(), e))
      return fault(e, "has a triangle on one side only (a hole)");
  }
  for (const Side& v : initial)
    if (!std::binary_search(edges.begin(), edges.end(), v))
      return fault(v, "is a side of the patch's lines with no triangle on it");
  return absl::OkStatus();
}

// Records the edges of the patch's triangles (from `first` on) that join two line points off
// the lines, for the patches meshed after it (SurfaceMeshState::chords_between_line_points).
void keep_chords_between_line_points(SurfaceMeshState& s, std::size_t first) {
  for (std::size_t t = first; t < s.triangles.size(); ++t) {
    for (int k = 0; k < 3; ++k) {
      const Index a = s.triangles[t][k], b = s.triangles[t][(k + 1) % 3];
      const std::pair<Index, Index> edge{std::min(a, b), std::max(a, b)};
      if (edge.second < s.line_points && !s.line_sides.contains(edge))
        s.chords_between_line_points.insert(edge);
    }
  }
}

absl::Status mesh_patch(SurfaceMeshState& s, PatchId patch, const std::vector<Side>& sides,
                        const Box& domain, const PatchFrontParams& params, Progress& progress) {
  const std::int64_t triangles_before = static_cast<std::int64_t>(s.triangles.size());
  const Index points_before = static_cast<Index>(s.points.size());
  // A patch without lines starts from a seed, which is the patch's own triangle: the checks
  // and the back-offs see it as every other.
  std::vector<Side> seed_sides;
  const std::optional<Triangle> seed =
      sides.empty() ? std::optional<Triangle>(lay_seed(s, patch, seed_sides)) : std::nullopt;
  const std::vector<Side>& initial = seed ? seed_sides : sides;
  double cell = std::numeric_limits<double>::infinity();
  for (const Side& v : initial)
    cell = std::min(cell, std::max(s.point_size[v[0]], norm(sub(s.points[v[1]], s.points[v[0]]))));
  // The bins' cells are the smallest initial side, but no more cells than a few per triangle
  // the patch may build (not in the paper): a patch whose lines hold one short side had a grid
  // of up to 4M cells over its box to clear and fault in (gmsh_lever: 127 grids, 1.2M cells, for
  // 22k triangles; FrontBins was 6% of its time). Its points and sides still spread over no
  // fewer cells than the front has points; crowded bins turn adaptive (adapt_bins_when_crowded).
  const std::int64_t max_cells =
      std::min(FrontBins::kDefaultMaxCells,
               kCellsPerTriangle * std::min(params.max_triangles, FrontBins::kDefaultMaxCells) +
                   kMinCells);
  PatchFront pf(s, patch, domain, cell, max_cells);
  if (seed) pf.add_seed(*seed);
  for (const Side& v : initial) pf.add_initial_side(v);
  std::int64_t steps = 0, back_offs = 0;
  while (std::optional<Index> f = pf.front().pop()) {                         // S1, S11
    const std::int64_t built = static_cast<std::int64_t>(s.triangles.size()) - triangles_before;
    if (++steps > params.steps_per_item * (built + static_cast<std::int64_t>(initial.size())) +
                      params.step_slack)
      return pf.stuck(*f, "too many steps", triangles_before, back_offs);
    if (built > params.max_triangles)
      return pf.stuck(*f, "far more triangles than the size asks", triangles_before, back_offs);
    if (pf.built_area() > params.max_area)
      return pf.stuck(*f, "its triangles cover more than the patch: the front has run over its own triangles",
                      triangles_before, back_offs);
    if (steps % 256 == 0 && progress.cancelled())
      return absl::CancelledError("surface meshing cancelled");
    if (steps % 1024 == 0) pf.adapt_bins_when_crowded();
    if (pf.delete_side(*f)) continue;
    const auto& item = pf.front().item(*f);
    if (item.attempts + 1 < kRuleClasses) {
      pf.defer(*f);
      continue;
    }
    if (pf.fill_hole(*f)) continue;
    if (back_offs < params.max_back_offs && pf.back_off(*f)) {
      ++back_offs;
      continue;
    }
    return pf.stuck(*f,
                    back_offs < params.max_back_offs ? "no face, and the back-offs there failed"
                                                     : "no face, and no back-off left",
                    triangles_before, back_offs);
  }
  s.compact_patch(points_before, static_cast<std::size_t>(triangles_before));
  if (absl::Status closed =
          check_patch_closed(s, patch, initial, static_cast<std::size_t>(triangles_before));
      !closed.ok())
    return closed;
  keep_chords_between_line_points(s, static_cast<std::size_t>(triangles_before));
  return absl::OkStatus();
}

}  // namespace afmesh
