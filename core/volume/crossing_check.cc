// F7.3 of the volume front: does the new element cross the front?
#include <algorithm>
#include <cmath>
#include <cstdint>

#include "core/geometry/closest_points.h"
#include "core/geometry/intersect.h"
#include "core/geometry/predicates.h"
#include "core/geometry/vec.h"
#include "core/volume/front_steps.h"

namespace afmesh::volume {
namespace {

// Faces of the positive tet (a, b, c, d), oriented out of it: (a, c, b), then the element's sides
// (a, b, d), (b, c, d), (c, a, d) in the order of element_crosses_front's `sides`.
constexpr int kFaces[4][3] = {{0, 2, 1}, {0, 1, 3}, {1, 2, 3}, {0, 3, 2}};
// The corners of the element's sides (kFaces 1, 2, 3), as bits of tet corners.
constexpr unsigned kSideCorners[3] = {0b1011, 0b1110, 0b1101};
// The faces each corner of the tet lies on, as bits of kFaces.
constexpr std::uint8_t kFacesOfCorner[4] = {0b1011, 0b0111, 0b1101, 0b1110};

// Where points lie against the element's four face planes (exact, Orient3dPlane), each point
// evaluated once per element. A point's code has, for face f, bit f when the point is a corner of
// face f or strictly outside its plane, and bit f + 4 when it is a corner of face f or strictly
// inside.
class TetPlanes {
  static constexpr std::uint32_t kEpochs = 1u << 24;

 public:
  TetPlanes(MesherState& s, const Tet& tet) : s_(s), tet_(tet) {
    for (int f = 0; f < 4; ++f) {
      const int* c = kFaces[f];
      planes_[f] = Orient3dPlane(s.points[tet[c[0]]], s.points[tet[c[1]]], s.points[tet[c[2]]]);
    }
    if (s.side_codes.size() < s.points.size()) s.side_codes.resize(s.points.size(), 0);
    if (++s.side_epoch == kEpochs) {  // wrapped: forget every old code
      std::fill(s.side_codes.begin(), s.side_codes.end(), 0);
      s.side_epoch = 1;
    }
  }

  std::uint8_t code(Index q) {
    std::uint32_t& cached = s_.side_codes[q];
    if (cached >> 8 == s_.side_epoch) return static_cast<std::uint8_t>(cached);
    std::uint8_t corner = 0;
    for (int k = 0; k < 4; ++k)
      if (q == tet_[k]) corner = kFacesOfCorner[k];
    std::uint8_t bits = corner | std::uint8_t(corner << 4);
    const Point& x = s_.points[q];
    for (int f = 0; f < 4; ++f) {
      if (corner & (1u << f)) continue;
      const int side = planes_[f].side(x);
      if (side > 0) bits |= std::uint8_t(1u << f);
      if (side < 0) bits |= std::uint8_t(16u << f);
    }
    cached = s_.side_epoch << 8 | bits;
    return bits;
  }

  // orient3d(tet) > 0: the element is positive.
  bool positive() const { return planes_[0].side(s_.points[tet_[3]]) < 0; }

 private:
  MesherState& s_;
  const Tet& tet_;
  Orient3dPlane planes_[4];
};

// With crossing environments (paper §2): true when a side of the element (oriented out of it)
// lies on three points that already bound a live tet while the front holds no face on them
// looking at the element. Elements of the two sides of a thin region may share only ridge
// points and new points; where the rim of a sheet turns a corner, three ridge points can make
// a face that one side has already meshed over, and an element of the other side built on
// the same three points would start a second layer of elements over the meshed space. (Without
// environments every face the element could share is on the front and visible.)
bool side_is_a_meshed_face(MesherState& s, const Triangle (&sides)[3], Index p) {
  std::vector<Index>& around = s.tets_around;
  for (const Triangle& side : sides) {
    if (s.front.find({side[0], side[2], side[1]})) continue;  // the face this side closes
    around.clear();
    s.incidence.elements_of(s.tets, p, around);
    for (const Index t : around) {
      if (has_corner(s.tets[t], side[0]) && has_corner(s.tets[t], side[1])) return true;
    }
  }
  return false;
}

// Not in the paper: whether a point lies within `gap` of one of the element's new faces `sides`
// (element_crosses_front's `gap`). Most points are farther than that from each face's plane,
// which their unit normals tell at once (a degenerate face's normal is zero: every point is
// then measured against the face itself).
class NearSides {
 public:
  NearSides(const std::vector<Point>& x, const Triangle (&sides)[3], double gap)
      : x_(x), sides_(sides), gap_(gap) {
    if (!(gap > 0)) return;
    for (int i = 0; i < 3; ++i) {
      const Point& a = x[sides[i][0]];
      const Point n = cross(sub(x[sides[i][1]], a), sub(x[sides[i][2]], a));
      const double length = norm(n);
      normals_[i] = length > 0 ? scale(n, 1.0 / length) : Point{0.0, 0.0, 0.0};
    }
  }

  bool near(const Point& q) const {
    if (!(gap_ > 0)) return false;
    for (int i = 0; i < 3; ++i) {
      const Triangle& t = sides_[i];
      // Farther than the gap from the face's plane: farther from the face too.
      if (std::abs(dot(normals_[i], sub(q, x_[t[0]]))) >= gap_) continue;
      const Point c = closest_point_on_triangle(q, x_[t[0]], x_[t[1]], x_[t[2]]);
      if (squared_norm(sub(q, c)) < gap_ * gap_) return true;
    }
    return false;
  }

 private:
  const std::vector<Point>& x_;
  const Triangle (&sides_)[3];
  double gap_;
  Point normals_[3];
};

}  // namespace

bool element_crosses_front(MesherState& s, Index face, Index p, Index* crossed, double gap) {
  if (crossed) *crossed = kInvalidIndex;
  const Triangle v = s.front.item(face).v;
  const Index env = s.front.item(face).env;
  const std::vector<Point>& x = s.points;
  const Tet tet{v[0], v[1], v[2], p};
  const Box box = tet_box(x, tet);
  // The element's faces other than `face`, oriented out of it, with the corner each leaves out.
  const Triangle sides[3] = {{v[0], v[1], p}, {v[1], v[2], p}, {v[2], v[0], p}};
  const Index opposite[3] = {v[2], v[0], v[1]};

  if (!s.point_env.empty() && side_is_a_meshed_face(s, sides, p)) return true;

  TetPlanes planes(s, tet);
  // Does the element meet front face g improperly?
  const auto crosses_face = [&](Index g) {
    ++s.face_tests;
    if (g == face) return false;
    const Triangle& w = s.front.item(g).v;
    // A front face on p and two corners of `face` is the face one side of the element closes.
    // It must look at the element (F10), whatever its environment: a face of another
    // environment on the element's own points (three ridge points, say, where the rim of a
    // thin sheet turns a corner) that looks away from it would make the element start a second
    // layer of elements over that face's side.
    const bool has_p = has_corner(w, p);
    const int on_face = has_corner(v, w[0]) + has_corner(v, w[1]) + has_corner(v, w[2]);
    if (has_p && on_face == 2) {
      int i = 0;  // the side on w's corners leaves out the corner of `face` that w lacks
      while (has_corner(w, opposite[i])) ++i;
      return orient3d(x[w[0]], x[w[1]], x[w[2]], x[opposite[i]]) <= 0;
    }
    if (!face_visible(s, env, g)) return false;
    const std::uint8_t all = planes.code(w[0]) & planes.code(w[1]) & planes.code(w[2]);
    // Separating plane: for one face of the element, every corner of w is a corner of that face
    // or strictly outside it. Then w meets the closed element only in the hull of the corners it
    // shares with that face: a proper contact.
    if (all & 0x0F) return false;
    // The other way round: the element's corners against w's plane. Bit k of `above` (`below`):
    // corner k is a corner of w or strictly above (below) that plane.
    const Orient3dPlane w_plane(x[w[0]], x[w[1]], x[w[2]]);
    unsigned above = 0, below = 0;
    for (int k = 0; k < 4; ++k) {
      if (has_corner(w, tet[k])) {
        above |= 1u << k;
        below |= 1u << k;
        continue;
      }
      const int side = w_plane.side(x[tet[k]]);
      if (side > 0) above |= 1u << k;
      if (side < 0) below |= 1u << k;
    }
    for (int i = 0; i < 3; ++i) {
      // Every corner of w is a corner of side i or strictly inside its plane, or every corner of
      // side i is a corner of w or strictly on one side of w's plane: they meet only in the
      // hull of the corners they share.
      if (all & (32u << i)) continue;
      if ((above & kSideCorners[i]) == kSideCorners[i]) continue;
      if ((below & kSideCorners[i]) == kSideCorners[i]) continue;
      if (triangles_intersect_improperly(x, sides[i], w)) return true;
    }
    return false;
  };
  // Not in the paper (F7.3 tests the faces near the element in any order): the face that met the
  // last crossing element is tested first, as the candidates of one face are checked in a row
  // and one front face blocks most of them. On fronts of long slivers the element's box spans
  // hundreds of cells and the walk meets ~70 faces before the one that crosses (OCCT's sh2.stl
  // at its mean edge: 68 face tests per check before, 7 after). crosses_face is exact wherever
  // the face lies, so the answer is the same; only the work and the face reported change.
  const Index last = s.last_crossed_face;
  if (last != kInvalidIndex && s.front.item(last).alive && crosses_face(last)) {
    if (crossed) *crossed = last;
    return true;
  }
  if (s.front.bins().find_item_near(box, [&](Index g) {
        if (!crosses_face(g)) return false;
        if (crossed) *crossed = g;
        s.last_crossed_face = g;
        return true;
      }))
    return true;

  const bool positive = planes.positive();
  bool contains_point = false;
  const NearSides near_sides(x, sides, gap);
  s.front.bins().for_each_point_near(grown(box, gap), [&](Index q) {
    ++s.face_tests;
    ++s.bins_watch.points;
    if (contains_point || has_corner(tet, q) || !point_visible(s, env, q)) return;
    // In the closed positive element: on no face plane's outer side (the barycentric signs of
    // point_in_tet are the face planes' sides, negated).
    contains_point = positive ? (planes.code(q) & 0x0F) == 0
                              : point_in_tet(x[q], x[v[0]], x[v[1]], x[v[2]], x[p]) >= 0;
    if (!contains_point && gap > 0 && !s.is_input_sliver_point(q))
      contains_point = near_sides.near(x[q]);
  });
  return contains_point;
}

void adapt_bins_when_crowded(MesherState& s) {
  ++s.bins_watch.queries;
  if (s.bins_watch.crowded(kBinsWindow, kCrowdedPointsPerSearch)) s.front.use_adaptive_bins();
}

}  // namespace afmesh::volume
