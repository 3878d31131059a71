// F5, F7.1 and F7.2 of the volume front: element size, best point and close points.
#include <algorithm>
#include <cmath>
#include <numbers>

#include "core/geometry/closest_points.h"
#include "core/geometry/predicates.h"
#include "core/geometry/vec.h"
#include "core/front/front_sizes.h"
#include "core/sizing/attached_sizes.h"
#include "core/volume/front_steps.h"

namespace afmesh::volume {
namespace {

// The height of the midpoints of a regular tet's three new edges above its base, per edge
// length: sqrt(2/3) / 2.
constexpr double kNewEdgeHeight = 0.408;

// wedge_apex_candidates: two front faces on one edge whose normals are within this angle of
// opposite bound a thin wedge.
constexpr double kWedgeAngleDeg = 20.0;
// ... and, where that rule is not on, this angle: a pocket between them holds almost nothing
// (wedge_apex_angle).
constexpr double kFlatWedgeAngleDeg = 2.0;

double mean_edge(const Point& a, const Point& b, const Point& c) {
  return (norm(sub(b, a)) + norm(sub(c, b)) + norm(sub(a, c))) / 3.0;
}

Box cube_around(const Point& x, double r) {
  return Box{{x[0] - r, x[1] - r, x[2] - r}, {x[0] + r, x[1] + r, x[2] + r}};
}

bool has_candidate(const MesherState& s, Index q) {
  for (const Candidate& c : s.candidates)
    if (c.point == q) return true;
  return false;
}

// Calls fn(g, q) for each front face g across an edge of `face` (the face on that edge the other
// way round) whose far corner q is visible from `face`, forms a positive element on it and is
// not a candidate yet.
template <typename Fn>
void for_each_neighbour_apex(const MesherState& s, Index face, Fn&& fn) {
  const Triangle v = s.front.item(face).v;
  const Index env = s.front.item(face).env;
  const Point& a = s.points[v[0]];
  const Point& b = s.points[v[1]];
  const Point& c = s.points[v[2]];
  for (int e = 0; e < 3; ++e) {
    const Index from = v[e], to = v[(e + 1) % 3];
    s.front.for_each_item_at(from, [&](Index g) {
      if (g == face) return;
      const Triangle& w = s.front.item(g).v;
      int k = 0;  // w holds the edge the other way round: w[k] = to, w[k + 1] = from
      while (k < 3 && w[k] != to) ++k;
      if (k == 3 || w[(k + 1) % 3] != from) return;
      const Index q = w[(k + 2) % 3];
      if (q == v[0] || q == v[1] || q == v[2] || !point_visible(s, env, q)) return;
      if (orient3d(a, b, c, s.points[q]) <= 0 || has_candidate(s, q)) return;
      fn(g, q);
    });
  }
}

// A triangle with an angle over kCapAngleDeg: a cap (its third corner near its longest edge),
// not a needle (one short edge).
constexpr double kCapAngleDeg = 120.0;
bool is_cap(const Point& a, const Point& b, const Point& c) {
  const double cos_cap = std::cos(kCapAngleDeg * std::numbers::pi / 180.0);
  const auto cos_at = [](const Point& o, const Point& x, const Point& y) {
    const Point u = sub(x, o), w = sub(y, o);
    return dot(u, w) / (norm(u) * norm(w));
  };
  return std::min({cos_at(a, b, c), cos_at(b, c, a), cos_at(c, a, b)}) < cos_cap;
}

// Not in the paper: the far corner of each front face across an edge of the sliver cap `face`
// (for_each_neighbour_apex) ranked before every other candidate, the better shaped (relative to
// `best`, best_element_quality) first. The element on a sliver face is a sliver whatever its
// fourth point; built on a neighbour's corner it closes that neighbour too, and the front keeps
// the faces the boundary gave, split at the sliver's corner, instead of gaining slivers of its
// own. It is the ear across a cap's long edge where a CAD tessellation splits a ridge on one
// side only, and along a fan of coplanar caps, the one point the first of them took, shared by
// the rest through the faces it left.
//
// Caps only (is_cap): a sliver needle takes the wedge rule's corners (wedge_apex_candidates) and
// points near its best point, as other faces do. Across a needle's long edge lies the next needle
// of a fan, and the element on its far corner is flat: on a fan round a pole, the ear taken from
// needle to needle folds the fan into ever wider flat faces reaching across it. Latitude-
// longitude spheres with 72 or more points round (poles of needles under 5 degrees: sliver
// fronts) stopped or met tets of 0.00 degrees after reruns; closed cylinders with fanned caps
// too. With needles left out, eight of them mesh at their mean edge on the first run (e.g. 100
// round and 49 rings, 200,815 tets in 3 s, stopped before after 8 reruns); raw CAD fronts mesh
// with fewer reruns (the lever, pinion, handle and OCCT's shape on the first run).
void neighbour_apex_candidates(MesherState& s, Index face, double best) {
  const Triangle v = s.front.item(face).v;
  const Point& a = s.points[v[0]];
  const Point& b = s.points[v[1]];
  const Point& c = s.points[v[2]];
  for_each_neighbour_apex(s, face, [&](Index, Index q) {
    const Point& x = s.points[q];
    s.candidates.push_back({q, x, -1.0 - tet_shape_quality(a, b, c, x) / best});
  });
}

// Not in the paper: on a sliver front (MesherState::sliver_front()), and on a front with crossing
// environments at a face that has failed once (wedge_apex_angle), the far corner of each
// front face across an edge of `face` that looks back at it within `wedge_deg`, kWedgeAngleDeg
// (for_each_neighbour_apex; the two faces' normals within that angle of opposite) is ranked
// before every other candidate: the element closes the thin wedge between the two faces at once.
// At netgen_hinge's last stop, 195 of the 610 edges of the front faces within 15 of where it
// stopped were such wedges, two faces on one edge facing each other across a gap under 20
// degrees: the front had left them where a face took a point of its own instead of its
// neighbour's corner, and in a wedge that thin no point fits later. The sweep's corpus runs went
// from 29 to 35 of 60 valid with it, none lost, in less time (bench/sweep/README.md); the
// element it makes is as flat as the wedge (TR12J_OCC's min dihedral 0.20 -> 0.00003 degrees).
void wedge_apex_candidates(MesherState& s, Index face, double wedge_deg) {
  const Triangle v = s.front.item(face).v;
  const Point nf =
      cross(sub(s.points[v[1]], s.points[v[0]]), sub(s.points[v[2]], s.points[v[0]]));
  const double cos_wedge = std::cos(wedge_deg * std::numbers::pi / 180.0);
  for_each_neighbour_apex(s, face, [&](Index g, Index q) {
    const Triangle& w = s.front.item(g).v;
    const Point ng =
        cross(sub(s.points[w[1]], s.points[w[0]]), sub(s.points[w[2]], s.points[w[0]]));
    if (dot(nf, ng) > -cos_wedge * norm(nf) * norm(ng)) return;
    s.candidates.push_back({q, s.points[q], -1.0});
  });
}

// The angle within which `face` ranks its neighbours' far corners across thin wedges first
// (wedge_apex_candidates), or 0 where it does not: on a sliver front (MesherState::sliver_front())
// every face, and on a front with crossing environments (paper §2; not in the paper) a face that
// has failed once, at kWedgeAngleDeg; on any other front a face that has failed once, at
// kFlatWedgeAngleDeg (below). The
// issue's large sails (make-thin-examples' sails_t*_grid4_box3, ~14k sail triangles in a box
// of some 20 chords) stopped on their cambered sides, where elements whose four corners are
// input points had left flat lids over the input: a pocket of four faces and 5e-8 volume between
// a quad's two diagonals, one pair the input's looking up, the other the lid's looking down.
// Each lid face sees the input face on its edge within a few degrees, and the input face's far
// corner closes the pocket. With the rule, the sweep's thin group went from 120 to 124 of 124
// valid (bench/sweep/README.md): sails_t0.01_grid4_box3 meshes at once in 9 s, sails_t0.001
// after one rerun in 15 s (they stopped after 8 reruns, 78-116 s). The other 120 thin runs
// changed too, most by a few tets: min dihedral better in 43, worse in 41 (the 6-cell X with
// camber 0.02, 1 mm: 20.01 -> 14.05 degrees; a dome with auto: 8.25 -> 17.05). From a face's
// first try the rule also meshed the large sails, after more reruns (33-52 s); at 5 or 2 degrees
// instead of 20 too, after more reruns (16-54 s).
//
// On any front, a face that has failed once takes the far corner across a wedge of under
// kFlatWedgeAngleDeg first: a flat pocket, which nothing but that element closes. A latitude-
// longitude sphere's bands are quads of four points coplanar but for rounding, split in two;
// where an element's face took the quad's other diagonal (its fourth point a hair inside), the
// two input triangles and the two faces over them enclose almost nothing, and no point but the
// quad's own corners fits in there. Such spheres stopped at their mean edge, with and without
// reruns (libcgal-demo's sphere966.stl, 44 around and 21 rings: 1,272 front faces left at the
// first stop, 1,165 of them on input points; Regression.Issue10LatitudeLongitudeSpheresMeshAt-
// TheirMeanEdge). The element is as flat as the pocket. At kWedgeAngleDeg instead, 6 of the
// sweep's 240 runs of the first 60 solids lost over 0.5 degrees of min dihedral; at 2 degrees 4
// (and 1 gained), all 240 valid either way.
double wedge_apex_angle(const MesherState& s, Index face) {
  const bool failed = s.front.item(face).attempts > 0;
  if (s.sliver_front() || (!s.point_env.empty() && failed)) return kWedgeAngleDeg;
  return failed ? kFlatWedgeAngleDeg : 0.0;
}

// gather_candidates' new points: at these shares of the best point's height above the face,
// with these ranks; a cap's same points nearer the front (cap_clearance_size) from this rank on,
// after every other candidate.
constexpr double kNewPointHeights[] = {1.0, 0.6, 0.35};
constexpr double kNewPointRanks[] = {0.6, 2.0, 2.1};
constexpr double kCapPointRank = 3.0;

// Not in the paper: where the back-off asks for it (Strictness::cap_new_points), a cap (is_cap)
// also takes the new points gather_candidates makes with their clearance from front faces a
// share of the cap's own height (its corner's distance from its longest edge, returned here)
// instead of the element size's, ranked after every other candidate. A cap can lie in a pocket
// thinner than any such clearance, where only a new point fits: on a faceted cylinder whose side
// quads are exactly planar (a binary STL writes one float x and y per angle on every ring),
// elements across the side leave flat faces on chords of the wall from one point of a ring to
// the next but one, and between a chord and the two quads it spans lies a lens 0.002 of the
// radius thick whose quads' diagonals twist round it (a Schönhardt prism: no element on its own
// points fills it). The front made a cap in there on three points of a ring, and every point
// above it lay within 0.0015 of the walls, 0.007 being the clearance at the last try
// (Regression.Issue10CylinderOfExactlyPlanarQuadsMeshesWithNoSize; it stopped with no size, also
// after 16 reruns). The crossing check (F7.3) still decides whether the element fits; its spacing
// from front points is as for the other new points.
double cap_clearance_size(const Point& a, const Point& b, const Point& c) {
  const double longest = std::sqrt(
      std::max({squared_norm(sub(b, a)), squared_norm(sub(c, b)), squared_norm(sub(a, c))}));
  return norm(cross(sub(b, a), sub(c, a))) / longest;
}

// The smallest shape (tet_shape_quality) gather_candidates accepts: the rules' share of
// `reference` (1, or a sliver's best element, best_element_quality), or, not in the paper, of
// `ideal_quality`, the element on the best point of face v for element size d, where that element
// is under the other threshold and d is larger than the size asked (the face is: d is kept within
// kMinElementOverEdge of its mean edge). Such a face has its best point low above it (the height
// is kept at half the size, ideal_point): a needle of a cap's fan, 1 long and 0.1 wide where the
// size is 0.2, has its element clamped to 0.55 of its mean edge and its best point 0.19 above
// it, an element of shape under 0.3, the first rules' threshold, for a needle that is not a
// sliver (is_sliver_face). None of its new points was then a candidate; the first points that
// fitted, under the third rules, were the wall's, half a radius away, and the fans' elements
// reached round the cylinder from its axis to the wall, leaving thin layers between their faces
// and the wall's facets where the front stopped (Regression.Issue10CylindersWithFannedCapsMesh-
// UnderTheirMeanEdge).
double min_quality_for_face(const MesherState& s, const Triangle& v, double d,
                            const Strictness& rules, double reference, double ideal_quality) {
  const double min_quality = rules.min_quality * reference;
  if (ideal_quality >= min_quality || !(d > target_size_for_face(s, v))) return min_quality;
  return rules.min_quality * std::max(ideal_quality, 0.0);
}

}  // namespace

bool new_point_is_clear(MesherState& s, const Point& x, double spacing_size,
                        double clearance_size, const Strictness& rules, Index env,
                        double min_spacing) {
  const double spacing = std::max(rules.point_spacing * spacing_size, min_spacing);
  const double clearance = rules.face_clearance * clearance_size;
  const double reach = std::max(spacing, clearance);
  bool crowded = false;
  s.front.bins().for_each_point_near(cube_around(x, reach), [&](Index q) {
    crowded = crowded ||
              (point_visible(s, env, q) && squared_norm(sub(s.points[q], x)) < spacing * spacing);
  });
  if (crowded) return false;
  const bool near_a_face = s.front.bins().find_item_near(cube_around(x, clearance), [&](Index g) {
    if (!face_visible(s, env, g)) return false;
    const Triangle& w = s.front.item(g).v;
    return squared_distance(
               x, closest_point_on_triangle(x, s.points[w[0]], s.points[w[1]], s.points[w[2]])) <
           clearance * clearance;
  });
  return !near_a_face;
}

Strictness strictness_for(int attempts) {
  // The first tries look for points close to the ideal point only (most faces take one of
  // them, and a small search is cheap); faces that failed look further.
  static constexpr Strictness kRules[] = {
      {0.30, 0.55, 0.35, 1.1}, {0.20, 0.45, 0.28, 1.4}, {0.10, 0.35, 0.20, 1.4},
      {0.04, 0.25, 0.12, 1.4}, {0.01, 0.15, 0.06, 1.4}, {0.0, 0.08, 0.03, 1.4},
  };
  constexpr int n = sizeof(kRules) / sizeof(kRules[0]);
  // Strictness::graze, in the first four rules only: the last two take what fits. Tried on the
  // fanned cylinders of exporter_tessellations_test.cc's family (108 runs in float STL and 108
  // in double OBJ, valid before: 90 and 69): these shares 91 and 89; 0.1 down to 0.02, 88 and
  // 86; 0.05 down to 0.01 through the fifth rules, 86 and 82; 0.03 down to 0.01, 89 and 70.
  // With input sliver points left out (element_crosses_front) these shares give 89 and 85.
  static constexpr double kGraze[] = {0.05, 0.04, 0.03, 0.02, 0.0, 0.0};
  Strictness r = kRules[std::clamp(attempts, 0, n - 1)];
  r.graze = kGraze[std::clamp(attempts, 0, n - 1)];
  return r;
}

double tet_shape_quality(const Point& a, const Point& b, const Point& c, const Point& d) {
  const Point ab = sub(b, a), ac = sub(c, a), ad = sub(d, a);
  const double six_v = dot(cross(ab, ac), ad);
  const double sum_sq = squared_norm(ab) + squared_norm(ac) + squared_norm(ad) +
                        squared_norm(sub(c, b)) + squared_norm(sub(d, b)) +
                        squared_norm(sub(d, c));
  const double l_rms = std::sqrt(sum_sq / 6.0);
  if (!(l_rms > 0)) return 0.0;
  return std::sqrt(2.0) * six_v / (l_rms * l_rms * l_rms);
}

double target_size_for_face(const MesherState& s, const Triangle& v) {
  const Point& a = s.points[v[0]];
  const Point& b = s.points[v[1]];
  const Point& c = s.points[v[2]];
  const Point centroid = scale(add(a, add(b, c)), 1.0 / 3.0);
  const double attached = grown_corner_size(s.growth, s.point_size, v);
  const double at_face = std::min(s.size_field.size_at(centroid), attached);  // eq. 15
  if (!s.size_field_varies) return at_face;
  // Not in the paper: where the field varies, it is read where the element's new edges are,
  // halfway up to the best point (0.41 d above the face for a regular element), not on the
  // face. Read on the face, a graded field gave edges 5-11% under its law, the element reaching
  // into larger sizes than its face's.
  const Point n = cross(sub(b, a), sub(c, a));
  const double length = norm(n);
  if (!(length > 0)) return at_face;
  const Point mid = add(centroid, scale(n, kNewEdgeHeight * at_face / length));
  return std::min(s.size_field.size_at(mid), attached);
}

double element_size_for_target(const MesherState& s, const Triangle& v, double target) {
  return afmesh::element_size_for_target(target,
                                         mean_edge(s.points[v[0]], s.points[v[1]], s.points[v[2]]));
}

double element_size_in_room(const MesherState& s, Index face, double target, double d) {
  const Triangle v = s.front.item(face).v;
  const Index env = s.front.item(face).env;
  const Point& a = s.points[v[0]];
  const Point& b = s.points[v[1]];
  const Point& c = s.points[v[2]];
  const Point centroid = scale(add(a, add(b, c)), 1.0 / 3.0);
  const Point n = cross(sub(b, a), sub(c, a));
  const double length = norm(n);
  if (!(length > 0)) return d;
  const Point u = scale(n, 1.0 / length);
  const Point end = add(centroid, scale(u, d));
  Box box{centroid, centroid};
  enclose(box, end);
  double room = d;  // to the first front face the normal meets, up to d
  s.front.bins().find_item_near(box, [&](Index g) {
    if (g == face || !face_visible(s, env, g)) return false;
    const Triangle& w = s.front.item(g).v;
    room = std::min(room, ray_triangle_parameter(centroid, u, s.points[w[0]], s.points[w[1]],
                                                 s.points[w[2]]));
    return false;
  });
  return room < d ? std::max(target, kRoomShare * room) : d;
}

double element_size_for_face(const MesherState& s, const Triangle& v) {
  return element_size_for_target(s, v, target_size_for_face(s, v));
}

bool is_sliver_face(const MesherState& s, Index env, const Triangle& v, double best) {
  if (!(best < kSliverFaceQuality)) return false;
  if (s.point_env.empty()) return true;
  return env == kNoEnvironment && !s.rim_strip_point.empty() &&
         std::all_of(v.begin(), v.end(), [&](Index p) {
           return p < static_cast<Index>(s.rim_strip_point.size()) && s.rim_strip_point[p];
         });
}

bool is_cap_face(const MesherState& s, const Triangle& v) {
  return is_cap(s.points[v[0]], s.points[v[1]], s.points[v[2]]);
}

bool touches_input_sliver(const MesherState& s, const Triangle& v) {
  return std::any_of(v.begin(), v.end(), [&](Index p) { return s.is_input_sliver_point(p); });
}

double best_element_quality(const MesherState& s, const Triangle& v) {
  const Point& a = s.points[v[0]];
  const Point& b = s.points[v[1]];
  const Point& c = s.points[v[2]];
  return tet_shape_quality(a, b, c, ideal_point(s, v, mean_edge(a, b, c)));
}

double queue_size_for_face(const MesherState& s, const Triangle& v, Index env) {
  const double target = target_size_for_face(s, v);
  const double key = queue_key_for_element(target, element_size_for_target(s, v, target));
  const double best = best_element_quality(s, v);
  return is_sliver_face(s, env, v, best) ? key * std::max(best, 0.0) / kSliverFaceQuality : key;
}

Point ideal_point(const MesherState& s, const Triangle& v, double d) {
  const Point& a = s.points[v[0]];
  const Point& b = s.points[v[1]];
  const Point& c = s.points[v[2]];
  const Point centroid = scale(add(a, add(b, c)), 1.0 / 3.0);
  const Point n = cross(sub(b, a), sub(c, a));
  const double r2 = (squared_norm(sub(a, centroid)) + squared_norm(sub(b, centroid)) +
                     squared_norm(sub(c, centroid))) / 3.0;
  const double height = std::sqrt(std::max(d * d - r2, 0.25 * d * d));
  return add(centroid, scale(n, height / norm(n)));
}

void gather_candidates(MesherState& s, Index face, const Point& ideal, double d,
                       const Strictness& rules) {
  const Triangle v = s.front.item(face).v;
  const Index env = s.front.item(face).env;
  const Point& a = s.points[v[0]];
  const Point& b = s.points[v[1]];
  const Point& c = s.points[v[2]];
  s.candidates.clear();
  // Not in the paper: on a sliver face no element reaches the shapes asked of the others; it
  // is asked the same share of the best it can have.
  const double best = best_element_quality(s, v);
  const bool sliver = is_sliver_face(s, env, v, best);
  const double min_quality =
      min_quality_for_face(s, v, d, rules, sliver ? best : 1.0, tet_shape_quality(a, b, c, ideal));
  if (sliver && is_cap(a, b, c))
    neighbour_apex_candidates(s, face, best);
  else if (const double wedge_deg = wedge_apex_angle(s, face); wedge_deg > 0)
    wedge_apex_candidates(s, face, wedge_deg);

  // Existing front points near the ideal point that form a positive, well-shaped element.
  const double reach = rules.reach * d;
  s.front.bins().for_each_point_near(cube_around(ideal, reach), [&](Index q) {
    if (q == v[0] || q == v[1] || q == v[2] || !point_visible(s, env, q)) return;
    const Point& x = s.points[q];
    const double dist = norm(sub(x, ideal));
    if (dist > reach || orient3d(a, b, c, x) <= 0 || (sliver && has_candidate(s, q))) return;
    const double quality = tet_shape_quality(a, b, c, x);
    if (quality < min_quality) return;
    s.candidates.push_back({q, x, dist / d + 0.5 * (1.0 - quality)});
  });

  // The new point, and new points closer to the face, where the front leaves room for them:
  // under a front face too near for the best point. On a sliver front (MesherState::
  // sliver_front()) a closer point keeps the best point's spacing from front points (not in the
  // paper): allowed the spacing of its own smaller element, a face whose best point is crowded
  // made a smaller element among the same points, whose faces' best points were crowded in
  // turn, and the elements shrank without end (Regression.Issue10CubeWithSliversAlongItsEdges-
  // Meshes). Elsewhere the closer points keep their own spacing: there the rule changed the
  // shipped meshes for the worse (min dihedral: L-block 20.009 -> 20.003 degrees, dome with
  // tags 20.011 -> 19.747).
  const Point centroid = scale(add(a, add(b, c)), 1.0 / 3.0);
  const bool cap_points = rules.cap_new_points && is_cap(a, b, c);
  const double cap_clearance = cap_points ? cap_clearance_size(a, b, c) : 0.0;
  for (int i = 0; i < 3; ++i) {
    const Point x = add(centroid, scale(sub(ideal, centroid), kNewPointHeights[i]));
    if (tet_shape_quality(a, b, c, x) < min_quality) continue;
    // Its clearance from the front is checked only if the loop gets to it (most faces take
    // the first candidate).
    const double spacing_size = s.sliver_front() ? d : d * kNewPointHeights[i];
    s.candidates.push_back(
        {kInvalidIndex, x, kNewPointRanks[i], d * kNewPointHeights[i], spacing_size});
    if (cap_points)  // the same point again, nearer the front's faces (cap_clearance_size)
      s.candidates.push_back({kInvalidIndex, x, kCapPointRank + i, cap_clearance, spacing_size});
  }
  std::sort(s.candidates.begin(), s.candidates.end(),
            [](const Candidate& l, const Candidate& r) {
              if (l.rank != r.rank) return l.rank < r.rank;
              return l.point < r.point;
            });
}

}  // namespace afmesh::volume
