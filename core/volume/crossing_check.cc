// F7.3 of the volume front: does the new element cross the front?
#include <algorithm>

#include "core/geometry/intersect.h"
#include "core/geometry/predicates.h"
#include "core/volume/front_steps.h"

namespace afmesh::volume {
namespace {

bool is_corner(const Tet& tet, Index q) {
  return q == tet[0] || q == tet[1] || q == tet[2] || q == tet[3];
}

bool is_corner(const Triangle& t, Index q) { return q == t[0] || q == t[1] || q == t[2]; }

// Exact separating-plane test: true when, for one face of `tet` (corners `x`), every corner of
// triangle w is either a corner of that face or strictly outside its plane. Then w meets the
// closed tet only in the hull of the corners it shares with that face: a proper contact.
bool separated_by_a_face_plane(const std::vector<Point>& x, const Tet& tet, const Triangle& w) {
  // Faces of the positive tet (a, b, c, d), oriented out of it.
  static constexpr int kFaces[4][3] = {{0, 2, 1}, {0, 1, 3}, {1, 2, 3}, {0, 3, 2}};
  for (const auto& f : kFaces) {
    const Index i = tet[f[0]], j = tet[f[1]], k = tet[f[2]];
    bool outside = true;
    for (Index q : w) {
      if (q == i || q == j || q == k) continue;
      if (orient3d(x[i], x[j], x[k], x[q]) <= 0) {
        outside = false;
        break;
      }
    }
    if (outside) return true;
  }
  return false;
}

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
    if (s.front.find(side[0], side[2], side[1])) continue;  // the face this side closes
    around.clear();
    s.incidence.tets_of(s.tets, p, around);
    for (const Index t : around) {
      const Tet& k = s.tets[t];
      const auto has = [&](Index q) { return k[0] == q || k[1] == q || k[2] == q || k[3] == q; };
      if (has(side[0]) && has(side[1])) return true;
    }
  }
  return false;
}

}  // namespace

bool element_crosses_front(MesherState& s, Index face, Index p) {
  const Triangle v = s.front.face(face).v;
  const Index env = s.front.face(face).env;
  const std::vector<Point>& x = s.points;
  const Tet tet{v[0], v[1], v[2], p};
  const Box box = tet_box(x, tet);
  // The element's faces other than `face`, oriented out of it, with the corner each leaves out.
  const Triangle sides[3] = {{v[0], v[1], p}, {v[1], v[2], p}, {v[2], v[0], p}};
  const Index opposite[3] = {v[2], v[0], v[1]};

  if (!s.point_env.empty() && side_is_a_meshed_face(s, sides, p)) return true;

  s.near_faces.clear();
  s.front.bins().faces_near(box, s.near_faces);
  for (Index g : s.near_faces) {
    if (g == face) continue;
    const Triangle& w = s.front.face(g).v;
    // A front face on p and two corners of `face` is the face one side of the element closes.
    // It must look at the element (F10), whatever its environment: a face of another
    // environment on the element's own points (three ridge points, say, where the rim of a
    // thin sheet turns a corner) that looks away from it would make the element start a second
    // layer of elements over that face's side.
    const bool has_p = w[0] == p || w[1] == p || w[2] == p;
    const int on_face = is_corner(v, w[0]) + is_corner(v, w[1]) + is_corner(v, w[2]);
    if (has_p && on_face == 2) {
      int i = 0;  // the side on w's corners leaves out the corner of `face` that w lacks
      while (is_corner(w, opposite[i])) ++i;
      if (orient3d(x[w[0]], x[w[1]], x[w[2]], x[opposite[i]]) <= 0) return true;
      continue;
    }
    if (!face_visible(s, env, g)) continue;
    if (separated_by_a_face_plane(x, tet, w)) continue;
    for (const Triangle& side : sides)
      if (triangles_intersect_improperly(x, side, w)) return true;
  }

  s.near_points.clear();
  s.front.bins().points_near(box, s.near_points);
  for (Index q : s.near_points) {
    if (is_corner(tet, q) || !point_visible(s, env, q)) continue;
    if (point_in_tet(x[q], x[v[0]], x[v[1]], x[v[2]], x[p]) >= 0) return true;
  }
  return false;
}

}  // namespace afmesh::volume
