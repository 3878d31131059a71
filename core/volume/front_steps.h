// The steps of the volume front loop (paper §1, F5–F10), each a function on the MesherState.
// generate_volume_mesh.cc calls them in the order of the paper.
#pragma once

#include <algorithm>
#include <cstdint>

#include "core/environments/environments.h"
#include "core/volume/mesher_state.h"

namespace afmesh::volume {

// Crossing environments (paper §2): the filters of core/environments/environments.h on the
// mesher's points and front faces.
inline bool point_visible(const MesherState& s, Index env, Index q) {
  return afmesh::point_visible(s.point_env, env, q);
}
inline bool face_visible(const MesherState& s, Index env, Index g) {
  return item_visible(env, s.front.item(g).env);
}
inline Index face_environment(const MesherState& s, const Triangle& v) {
  return afmesh::item_environment(s.point_env, v);
}

// Relaxation of the acceptance rules for a face that has failed `attempts` times: later
// attempts accept worse elements and points closer to the front.
struct Strictness {
  double min_quality;     // smallest accepted tet quality (tet_shape_quality)
  double point_spacing;   // a new point keeps this fraction of d from front points
  double face_clearance;  // ... and this fraction of d from front faces
  double reach;           // front points within reach·d of the ideal point are candidates
  // Not in the paper: a cap (is_cap_face) also takes new points near the front's faces
  // (gather_candidates), set by the back-off only.
  bool cap_new_points = false;
  // Not in the paper: a front point outside the element may come no nearer than this fraction
  // of d to one of its new faces (element_crosses_front's `gap`; delete_face).
  double graze = 0.0;
};
Strictness strictness_for(int attempts);

// Shape quality of tet (a, b, c, d) in [0, 1]: 6·sqrt(2)·V / l_rms^3, with l_rms the root mean
// square edge length: 1 for the regular tet, 0 when flat, negative when inverted.
double tet_shape_quality(const Point& a, const Point& b, const Point& c, const Point& d);

// Eq. 15: the size wanted at face v, min(delta_bg(x), c_i · min(delta_A, delta_B, delta_C)), with
// x the centroid, or, where the size field varies, the point 0.41 × that size above it (where
// the element's new edges are).
double target_size_for_face(const MesherState& s, const Triangle& v);

// F5/F9: the size of the element face `v` should form for the wanted size `target`
// (target_size_for_face): element_size_for_target of core/front/front_sizes.h over the face's
// mean edge.
double element_size_for_target(const MesherState& s, const Triangle& v, double target);

// element_size_for_target(s, v, target_size_for_face(s, v)).
double element_size_for_face(const MesherState& s, const Triangle& v);

// Not in the paper: the shape (tet_shape_quality) of the best element on face v, the one with
// its best point (ideal_point) for an element as large as the face's mean edge. About 1 for a
// well-shaped face; under kSliverFaceQuality for a sliver (a cap with an angle over ~165
// degrees, a needle with one under ~5), on which every element is a sliver too.
double best_element_quality(const MesherState& s, const Triangle& v);
inline constexpr double kSliverFaceQuality = 0.15;
// True when face v of environment `env` and best_element_quality `best` is treated as a sliver
// (queue_size_for_face, gather_candidates): under kSliverFaceQuality, on a front without
// crossing environments. With environments (paper §2) the rules for slivers left the crossing
// plates of other shapes stuck (ThinVolume.CrossingPlatesOfOtherShapesMeshValid) and, on faces
// of rim points, let the large sails escape their box: thin regions keep the rules they
// had, but for the faces among the points of strips closing plates' rims
// (MesherState::rim_strip_point), needles that stop the front without them
// (ThinVolume.PlatesWithRimStripsMeshValid).
bool is_sliver_face(const MesherState& s, Index env, const Triangle& v, double best);

// True when front face v has a corner of a poor face of an input with slivers
// (MesherState::input_sliver_point).
bool touches_input_sliver(const MesherState& s, const Triangle& v);

// Not in the paper: face v has an angle over 120 degrees (a cap, its third corner near its
// longest edge), not a needle.
bool is_cap_face(const MesherState& s, const Triangle& v);

// F6: the queue key of face v: queue_key_for_element (core/front/front_sizes.h) of its target
// and element sizes; for a sliver face (is_sliver_face), that key scaled down by its best
// quality over kSliverFaceQuality, so that slivers are deleted first, the worst first (not in
// the paper: like the faces of crossing environments, §2, the troublesome faces go first,
// while the faces beside them are still on the front to be closed with them).
double queue_size_for_face(const MesherState& s, const Triangle& v, Index env);

// Not in the paper: the element of a coarse sliver face (is_sliver_face, its element clamped
// above the size wanted by element_size_for_target) where the front before it leaves less room
// than that size. The distance from the face's centroid along its normal to the first front face
// it sees, when under d, gives an element of kRoomShare times that distance (never under
// `target`), so that the best point lies within the room; else d itself. A sliver of a CAD
// tessellation tens of sizes long over a wall a size or two thick asked for an element whose
// best point lay beyond the wall: occt-misc's sh2.stl, a bore of strips 99.5 long in a wall 3
// thick at size 3.1 (elements clamped to 24-37), built chords of the wall's facets with lenses
// under them and failed at every size; fitted to their room, it meshes at every size (the
// sweep: occt-misc 9 -> 12 of 12). Applied to every coarse face it meshed sh2 with no size
// only, and a flat pocket far coarser than the size (Regression.Issue10PocketWithAThinKernel-
// Meshes at size 3), which the pocket fill closes from its kernel, was meshed into and got stuck.
inline constexpr double kRoomShare = 0.5;
double element_size_in_room(const MesherState& s, Index face, double target, double d);

// F7.1: the 'best point' for face v and element size d: above the centroid, along the face
// normal, at the height that makes the edges to the face's corners about d long.
Point ideal_point(const MesherState& s, const Triangle& v, double d);

// F7.2: the candidates for the face, best first: front points near the ideal point that form a
// positive element of acceptable shape, and the new point itself, followed by new points closer
// to the face. For a sliver face (is_sliver_face) the acceptable shape is relative to the best
// its elements can have, and the far corners of the front faces across its edges come first
// (neighbour_apex_candidates in candidates.cc). Fills s.candidates. A new point's clearance
// (new_point_is_clear) is left to the caller, to be checked only when the candidate is reached.
void gather_candidates(MesherState& s, Index face, const Point& ideal, double d,
                       const Strictness& rules);

// F7.2: true when a new point at x keeps its distance from the front: rules.point_spacing ×
// `spacing_size` from front points (else an existing point is to be used in lieu of it) and
// rules.face_clearance × `clearance_size` from front faces (Candidate's sizes: the element size
// for the best point; for a point closer to the face, the clearance shrinks with its height,
// the spacing does not).
// Only points and faces visible from environment `env` count (paper §2). Front points closer
// than `min_spacing` always count as too close, whatever the sizes.
bool new_point_is_clear(MesherState& s, const Point& x, double spacing_size,
                        double clearance_size, const Strictness& rules, Index env,
                        double min_spacing);

// F7.3: true when tet (v[0], v[1], v[2], p) would cross the front: it intersects a front face
// other than those it shares properly, or contains a front point. `p` is an index into
// s.points (a new point is appended before the check). Exact predicates only. When it crosses
// and `crossed` is given, *crossed is the front face it meets improperly, or kInvalidIndex when
// it crosses for another reason (a front point inside it or within `gap`, a meshed face).
// Not in the paper: with `gap` > 0 a visible front point that is no corner of the element also
// counts when it lies within `gap` of one of the element's new faces: the element would leave a
// gap that thin between that face and the point, which only a sliver fills (Strictness::graze;
// the surface front keeps the same clearance from its new sides). A corner of a poor input face
// (MesherState::is_input_sliver_point) does not count so: a CAD tessellation's slivers put such
// points within any gap of the faces near them, and the rule stopped runs that close without it
// (Regression.Issue10LeverMeshesAsGiven, Issue10HingeMeshesAsGiven).
bool element_crosses_front(MesherState& s, Index face, Index p, Index* crossed = nullptr,
                           double gap = 0.0);

// Not in the paper: the front's bins become adaptive (an octree, FrontBins::Adaptive) when
// element_crosses_front (F7.3) has looked at more than kCrowdedPointsPerSearch front points per
// face deletion over the last kBinsWindow deletions (MesherState::bins_watch, BinsWatch). The bins' cells are
// about one boundary edge; where the sizes span far more than that, large elements meet
// thousands of cells and the points in them: occt-misc's propeller.stl re-triangulated (sizes
// from 0.3 to 11.5) looked at 1,210 points per deletion and its front stopped over its budget.
// The bench's shapes and occt-misc's sh1, sh2, shape and TR12J_OCC look at 4-29; the corpus's
// re-triangulated cgal_dino and cgal_hand at up to 305 and 172, where the octree is slower
// (their fronts 10.5 -> 13.6 s and 3.6 -> 4.3 s): hence 512. Points, not faces: a sliver
// front's long faces meet every box, in the octree too (sh2.stl: 1,250 faces and points per
// deletion, 16 of them points). The answers are the same, exact either way; only the faces
// visited change, and with them which crossing face is met first. Call once per face deletion
// (it counts the deletion). The surface front does likewise (its S6 check).
inline constexpr std::int64_t kBinsWindow = 4096;
inline constexpr std::int64_t kCrowdedPointsPerSearch = 512;
void adapt_bins_when_crowded(MesherState& s);

// F8–F10: adds tet (v, p), deletes the face and every front face the tet closes, and puts the
// tet's other faces on the front with their element sizes.
void add_element(MesherState& s, Index face, Index p);

// Back-off when a face cannot be closed: removes the tets around the face's corners (within
// `rings` rings) and returns their faces to the front to be meshed again. Returns the number of
// tets removed.
std::int64_t open_cavity(MesherState& s, Index face, int rings);

// F11, the end game: collects into `pocket` the front faces connected to `face` through shared
// edges (the closed pocket of unmeshed space it bounds), sorted. False when the pocket has more
// than `max_faces` faces (it is not a small pocket).
bool collect_pocket(MesherState& s, Index face, std::size_t max_faces, std::vector<Index>& pocket);

// F11, the end game: fills the small pocket bounded by `face` from one kernel point that sees
// all of its faces (a new point near the pocket's centre, else one of its corners), each element
// checked by F7.3 before it is added. Returns the number of elements added (0 when the pocket is
// too large or no kernel point was found).
std::int64_t fill_pocket(MesherState& s, Index face, std::size_t max_faces);

// Not in the paper: the back-off for a face whose pocket is not star-shaped (fill_pocket found
// no kernel point). Of the pocket's faces, `face` and as many others as possible are closed from
// one new point: the deepest point of the part (the highest above the lowest of its face planes,
// a linear program); while that point does not close a face of the part (behind its plane, or
// the element crosses the front, F7.3), the face it is lowest above leaves the part and the
// point is found again. The part left is star-shaped about its point, and the pocket shrinks by
// it. Returns the number of elements added (0 when no part with `face` has such a point, or on
// a front with crossing environments, whose thin regions keep the back-off they had).
std::int64_t fill_part_of_pocket(MesherState& s, Index face, std::size_t max_faces);

// Not in the paper: the last back-off for a face whose pocket is not star-shaped, when
// fill_part_of_pocket and re-opening its surroundings have failed (F11 has no answer then). In a
// pocket that bends, the faces far from `face` decide where the deepest point of the whole lies,
// and fill_part_of_pocket's shrinking can drop the faces near `face` that block its element
// before the others, leaving `face` alone with no point; re-opening rebuilds the same pocket
// (Regression.Issue10BentPocketClosesTheFaceItWasStuckAt). Here the part grows from `face`
// instead, so it does not depend on an order of shrinking: while the element of `face` and the
// part's deepest point (over the box of the part's corners) crosses a front face (F7.3), that
// face joins the part, or, when it is in the part already, the pocket's faces across its edges
// do; then the point is found again. Once the element crosses nothing, the point closes `face`
// and every other face of the part above whose plane it lies and whose element crosses nothing.
// Returns the number of elements added: 0 when the part cannot grow (the element contains a
// front point, or meets a part face whose neighbours are all in the part), grows past
// `max_faces`, or has no point above all its faces; and, as fill_part_of_pocket, on a front with
// crossing environments.
std::int64_t fill_grown_part_of_pocket(MesherState& s, Index face, std::size_t max_faces);

}  // namespace afmesh::volume
