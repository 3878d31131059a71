// The end game of the volume front (F11): a face that no candidate point can close usually
// bounds a small closed pocket of unmeshed space whose shape leaves no room for a well-shaped
// element. Such a pocket is filled from one point that sees every face of it: the pocket is then
// star-shaped about that point and the elements (face, point) tile it.
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <optional>
#include <vector>

#include "core/geometry/predicates.h"
#include "core/geometry/vec.h"
#include "core/sizing/attached_sizes.h"
#include "core/volume/front_steps.h"

namespace afmesh::volume {
namespace {

constexpr int kPocketChebyshevSteps = 64;
constexpr int kDeepestPointSteps = 2000;  // simplex pivots; a pocket has at most 256 faces

Box segment_box(const Point& a, const Point& b) {
  Box box{a, a};
  enclose(box, b);
  return box;
}

// Signed distance of x from the plane of face (a, b, c), positive on its unmeshed side.
double height_above(const Point& a, const Point& b, const Point& c, const Point& x) {
  const Point n = cross(sub(b, a), sub(c, a));
  const double len = norm(n);
  return len > 0 ? dot(n, sub(x, a)) / len : 0.0;
}

// A point inside the pocket far from all its face planes: starting from the centroid of the
// pocket's corners, repeatedly steps away from the nearest face plane (a subgradient ascent of
// the smallest height, an approximate Chebyshev centre). Exactness is not needed here: the
// elements it yields are checked by the exact predicates before they are added.
Point pocket_centre(const MesherState& s, const std::vector<Index>& pocket) {
  Point c{0, 0, 0};
  double count = 0;
  for (Index f : pocket)
    for (Index p : s.front.item(f).v) {
      c = add(c, s.points[p]);
      count += 1;
    }
  c = scale(c, 1.0 / count);
  double step = 0;
  for (Index f : pocket) {
    const Triangle& v = s.front.item(f).v;
    step = std::max(step, norm(sub(s.points[v[0]], c)));
  }
  step *= 0.25;
  for (int it = 0; it < kPocketChebyshevSteps; ++it) {
    double worst = 0;
    Point direction{0, 0, 0};
    bool first = true;
    for (Index f : pocket) {
      const Triangle& v = s.front.item(f).v;
      const Point& a = s.points[v[0]];
      const Point& b = s.points[v[1]];
      const Point& cc = s.points[v[2]];
      const double h = height_above(a, b, cc, c);
      if (first || h < worst) {
        worst = h;
        const Point n = cross(sub(b, a), sub(cc, a));
        direction = scale(n, 1.0 / norm(n));
        first = false;
      }
    }
    c = add(c, scale(direction, step));
    step *= 0.9;
  }
  return c;
}

// The point of box `box` highest above the lowest of the pocket's face planes: the linear
// program max t subject to n_f . (x - a_f) >= t for every face f (n_f its unit normal into the
// pocket, a_f a corner), solved by the simplex method (Bland's rule) on the tableau of
// y = (x - box.lo, t + M) >= 0, with M large enough that y = 0 is feasible. Returns false when
// the simplex does not end within its step limit or the best t is not positive (no kernel);
// `depth` is then set to that t, and `x` to its point, when the simplex ended. Floating point:
// the caller checks the point with the exact predicates.
bool deepest_point(const MesherState& s, const std::vector<Index>& pocket, const Box& box,
                   Point& x, double& depth) {
  const std::size_t m = pocket.size() + 3, n = 4, width = n + m + 1;
  std::vector<double> tab((m + 1) * width, 0.0);
  const auto at = [&](std::size_t r, std::size_t c) -> double& { return tab[r * width + c]; };
  double extent = 0;
  for (int k = 0; k < 3; ++k) extent = std::max(extent, box.hi[k] - box.lo[k]);
  const double big = 4.0 * extent;  // M: above every face's distance from box.lo
  for (std::size_t i = 0; i < pocket.size(); ++i) {
    const Triangle& v = s.front.item(pocket[i]).v;
    const Point& a = s.points[v[0]];
    Point nrm = cross(sub(s.points[v[1]], a), sub(s.points[v[2]], a));
    const double length = norm(nrm);
    if (!(length > 0)) return false;
    nrm = scale(nrm, 1.0 / length);
    // t - n . x' <= n . (lo - a)  becomes  (t + M) - n . x' <= n . (lo - a) + M.
    for (int k = 0; k < 3; ++k) at(i, k) = -nrm[k];
    at(i, 3) = 1.0;
    at(i, width - 1) = dot(nrm, sub(box.lo, a)) + big;
    if (at(i, width - 1) < 0) return false;
  }
  for (int k = 0; k < 3; ++k) {  // x'_k <= hi_k - lo_k
    at(pocket.size() + k, k) = 1.0;
    at(pocket.size() + k, width - 1) = box.hi[k] - box.lo[k];
  }
  for (std::size_t r = 0; r < m; ++r) at(r, n + r) = 1.0;  // slacks
  at(m, 3) = -1.0;  // maximise t + M
  std::vector<std::size_t> basis(m);
  for (std::size_t r = 0; r < m; ++r) basis[r] = n + r;
  for (int step = 0; step < kDeepestPointSteps; ++step) {
    std::size_t col = width;  // Bland's rule: the first column that improves
    for (std::size_t c = 0; c + 1 < width && col == width; ++c)
      if (at(m, c) < -1e-12) col = c;
    if (col == width) {  // optimal
      double y[4] = {0, 0, 0, 0};
      for (std::size_t r = 0; r < m; ++r)
        if (basis[r] < n) y[basis[r]] = at(r, width - 1);
      x = {box.lo[0] + y[0], box.lo[1] + y[1], box.lo[2] + y[2]};
      depth = y[3] - big;
      return depth > 0;
    }
    std::size_t row = m;
    double ratio = 0;
    for (std::size_t r = 0; r < m; ++r) {
      if (at(r, col) <= 1e-12) continue;
      const double q = at(r, width - 1) / at(r, col);
      if (row == m || q < ratio || (q == ratio && basis[r] < basis[row])) {
        row = r;
        ratio = q;
      }
    }
    if (row == m) return false;  // unbounded: cannot happen with the box
    const double pivot = at(row, col);
    for (std::size_t c = 0; c < width; ++c) at(row, c) /= pivot;
    for (std::size_t r = 0; r <= m; ++r) {
      if (r == row || at(r, col) == 0) continue;
      const double f = at(r, col);
      for (std::size_t c = 0; c < width; ++c) at(r, c) -= f * at(row, c);
    }
    basis[row] = col;
  }
  return false;
}

// Not in the paper: the deepest point of the pocket (deepest_point, over the box of its corners)
// as its kernel point, for a star-shaped pocket whose kernel pocket_centre's ascent misses:
// Regression.Issue10PocketWithAThinKernelMeshes, a pocket of 16 faces the front of gmsh_lever
// left, whose kernel is 0.02 high in a pocket 95 long. Appends it to the points, with its size,
// and returns its index; kInvalidIndex when it does not see every face (exact test).
template <typename SeesAll>
Index deepest_kernel_point(MesherState& s, const std::vector<Index>& pocket,
                           const std::vector<Index>& corners, SeesAll&& sees_all) {
  Box box = empty_box();
  for (Index q : corners) enclose(box, s.points[q]);
  Point x;
  double depth = 0;
  if (!deepest_point(s, pocket, box, x, depth)) return kInvalidIndex;
  const Index p = static_cast<Index>(s.points.size());
  s.points.push_back(x);
  if (!sees_all(p)) {
    s.points.pop_back();
    return kInvalidIndex;
  }
  s.point_size.push_back(new_point_size(s.size_field.size_at(x), 1.0, s.point_size, corners));
  return p;
}

// Shares of the way from a corner of the pocket to its centre at which
// kernel_point_beside_a_corner looks for a kernel point, nearest the centre first.
constexpr double kBesideCornerShares[] = {0.3, 0.1, 0.03, 0.01};

// Not in the paper: a kernel point of the pocket next to one of its corners, for a pocket whose
// kernel is a thin wedge at a corner that lies in the plane of other faces of the pocket (a
// planar CAD face triangulated across the diagonal the pocket's other faces do not share:
// Regression.Issue10PocketWithItsKernelAtACornerMeshes). The centre of pocket_centre misses such
// a kernel and the corner itself sees the coplanar faces edge-on; a point a small share of the
// way from the corner towards the centre can see them all. Appends it to the points, with its
// size, and returns its index; kInvalidIndex when no such point sees every face.
template <typename SeesAll>
Index kernel_point_beside_a_corner(MesherState& s, const std::vector<Index>& pocket,
                                   const std::vector<Index>& corners, SeesAll&& sees_all) {
  const Point c = pocket_centre(s, pocket);
  const Index p = static_cast<Index>(s.points.size());
  for (const double share : kBesideCornerShares)
    for (Index q : corners) {
      const Point x = add(s.points[q], scale(sub(c, s.points[q]), share));
      s.points.push_back(x);
      if (sees_all(p)) {
        s.point_size.push_back(
            new_point_size(s.size_field.size_at(x), 1.0, s.point_size, corners));
        return p;
      }
      s.points.pop_back();
    }
  return kInvalidIndex;
}

// Whether the new point at index `xi` closes front face g: it lies above g's plane and their
// element does not cross the front (F7.3).
bool closes_face(MesherState& s, Index g, Index xi) {
  const Triangle& v = s.front.item(g).v;
  return orient3d(s.points[v[0]], s.points[v[1]], s.points[v[2]], s.points[xi]) > 0 &&
         !element_crosses_front(s, g, xi);
}

// The index in `part` of the face to leave it next, for the new point at index `xi` (the part's
// deepest point; `inside` when it lies above every face plane): of the faces the point does not
// close (behind their plane, or the element crosses the front, F7.3), the one it is lowest above;
// when `keep` is the only one, the face other than `keep` it is lowest above, to move the point.
// Returns part.size() when the point closes every face, part.size() + 1 when only `keep` is left.
std::size_t face_to_drop(MesherState& s, const std::vector<Index>& part, Index xi, bool inside,
                         Index keep) {
  const Point& x = s.points[xi];
  const auto height = [&](Index g) {
    const Triangle& v = s.front.item(g).v;
    return height_above(s.points[v[0]], s.points[v[1]], s.points[v[2]], x);
  };
  std::size_t worst = part.size(), lowest_other = part.size();
  bool keep_fails = false;
  for (std::size_t i = 0; i < part.size(); ++i) {
    const bool closes = inside && closes_face(s, part[i], xi);
    if (part[i] == keep) {
      keep_fails = !closes;
      continue;
    }
    if (lowest_other == part.size() || height(part[i]) < height(part[lowest_other]))
      lowest_other = i;
    if (!closes && (worst == part.size() || height(part[i]) < height(part[worst]))) worst = i;
  }
  if (worst < part.size()) return worst;
  if (!keep_fails) return part.size();
  return lowest_other < part.size() ? lowest_other : part.size() + 1;
}

// Adds the elements of the new point at index x (its position set, its size not yet) and every
// face of `part`, which it closes (closes_face, checked for each face before any is added:
// elements with one apex that each cross no face of the front cannot overlap each other). x
// gets its size first: eq. 15 without growth (c_i = 1), as it is joined to every corner of the
// part. Returns the number of elements added.
std::int64_t add_part_elements(MesherState& s, const std::vector<Index>& part, Index x) {
  std::vector<Index> corners;
  std::vector<Triangle> faces;
  for (Index g : part) {
    faces.push_back(s.front.item(g).v);
    for (Index q : s.front.item(g).v) corners.push_back(q);
  }
  const Point c = s.points[x];
  s.point_size.push_back(new_point_size(s.size_field.size_at(c), 1.0, s.point_size, corners));
  std::int64_t added = 0;
  for (const Triangle& v : faces) {
    const std::optional<Index> g = s.front.find(v);
    if (!g) continue;
    add_element(s, *g, x);
    ++added;
  }
  return added;
}

// fill_grown_part_of_pocket's growth. From `face` alone, while the element of `face` and the
// part's deepest point crosses a front face g, the part grows: by g, or, when g is in it already
// (the point lies above g's plane, yet the element meets g: the pocket folds at an edge of g), by
// the faces of `pocket` (sorted) across g's edges. The point is sought in the box of the part's
// corners, which grows with it: over the box of the whole pocket, a bent pocket puts it far from
// `face`, outside the domain (seen on OCCT's shape.stl). True when the element crosses
// nothing; s.points[x] is then the point. False when the part cannot grow, exceeds `max_faces`,
// or has no point above all its faces.
bool grow_part_about_face(MesherState& s, Index face, const std::vector<Index>& pocket, Index x,
                          std::size_t max_faces, std::vector<Index>& part) {
  const auto in_part = [&](Index g) {
    return std::find(part.begin(), part.end(), g) != part.end();
  };
  Box box = empty_box();
  for (Index q : s.front.item(face).v) enclose(box, s.points[q]);
  part.assign(1, face);
  while (part.size() <= max_faces) {
    double depth = 0;
    if (!deepest_point(s, part, box, s.points[x], depth)) return false;
    const Triangle& v = s.front.item(face).v;
    if (orient3d(s.points[v[0]], s.points[v[1]], s.points[v[2]], s.points[x]) <= 0) return false;
    // The face the element meets as the bins' walk finds it, not the one F7.3 tests first
    // (MesherState::last_crossed_face): that is the face the last refused candidate of any face
    // met, which may lie far from `face`. On OCCT's sh2.stl the first stop was a needle face
    // under a lens 0.02 thick; grown by the last crossed face (a wall 60 away) the part had no
    // point, grown by the walk's it took three faces of the lens and closed it with 4 elements.
    s.last_crossed_face = kInvalidIndex;
    Index crossed = kInvalidIndex;
    if (!element_crosses_front(s, face, x, &crossed)) return true;
    if (crossed == kInvalidIndex) return false;  // a front point inside, or a meshed face
    const std::size_t before = part.size();
    if (!in_part(crossed)) {
      part.push_back(crossed);
    } else {
      const Triangle w = s.front.item(crossed).v;
      for (Index g : pocket) {
        const Triangle& u = s.front.item(g).v;
        if (has_corner(u, w[0]) + has_corner(u, w[1]) + has_corner(u, w[2]) == 2 && !in_part(g))
          part.push_back(g);
      }
    }
    if (part.size() == before) return false;
    for (std::size_t i = before; i < part.size(); ++i)
      for (Index q : s.front.item(part[i]).v) enclose(box, s.points[q]);
  }
  return false;
}

}  // namespace

std::int64_t fill_part_of_pocket(MesherState& s, Index face, std::size_t max_faces) {
  if (!s.point_env.empty()) return 0;  // thin regions keep the back-off they had
  std::vector<Index> part;
  if (!collect_pocket(s, face, max_faces, part)) return 0;
  const Index x = static_cast<Index>(s.points.size());
  s.points.push_back(Point{0, 0, 0});
  while (!part.empty()) {
    Box box = empty_box();
    for (Index g : part)
      for (Index q : s.front.item(g).v) enclose(box, s.points[q]);
    double depth = 0;
    const bool inside = deepest_point(s, part, box, s.points[x], depth);
    const std::size_t drop = face_to_drop(s, part, x, inside, face);
    if (drop > part.size()) break;  // `face` is left alone and the point does not close it
    if (drop < part.size()) {
      part.erase(part.begin() + static_cast<std::ptrdiff_t>(drop));
      continue;
    }
    return add_part_elements(s, part, x);  // x closes every face of the part (face_to_drop)
  }
  s.points.pop_back();
  return 0;
}

std::int64_t fill_grown_part_of_pocket(MesherState& s, Index face, std::size_t max_faces) {
  if (!s.point_env.empty()) return 0;  // thin regions keep the back-off they had
  std::vector<Index> pocket, part;
  if (!collect_pocket(s, face, max_faces, pocket)) return 0;
  const Index x = static_cast<Index>(s.points.size());
  s.points.push_back(Point{0, 0, 0});
  if (!grow_part_about_face(s, face, pocket, x, max_faces, part)) {
    s.points.pop_back();
    return 0;
  }
  // x closes `face`; the faces that joined the part may lie behind x or block its elements.
  std::erase_if(part, [&](Index g) { return g != face && !closes_face(s, g, x); });
  return add_part_elements(s, part, x);
}

bool collect_pocket(MesherState& s, Index face, std::size_t max_faces,
                    std::vector<Index>& pocket) {
  pocket.clear();
  pocket.push_back(face);
  std::vector<Index>& near = s.near_faces;
  for (std::size_t i = 0; i < pocket.size(); ++i) {
    const Triangle v = s.front.item(pocket[i]).v;
    for (int e = 0; e < 3; ++e) {
      const Index a = v[e], b = v[(e + 1) % 3];
      near.clear();
      s.front.bins().items_near(segment_box(s.points[a], s.points[b]), near);
      for (Index g : near) {
        const Triangle& w = s.front.item(g).v;
        if (!has_corner(w, a) || !has_corner(w, b)) continue;
        if (std::find(pocket.begin(), pocket.end(), g) != pocket.end()) continue;
        if (pocket.size() == max_faces) return false;
        pocket.push_back(g);
      }
    }
  }
  std::sort(pocket.begin(), pocket.end());
  return true;
}

std::int64_t fill_pocket(MesherState& s, Index face, std::size_t max_faces) {
  std::vector<Index> pocket;
  if (!collect_pocket(s, face, max_faces, pocket)) return 0;

  // The kernel point: a new point at the pocket's centre, else one of its corners.
  std::vector<Index> corners;
  for (Index f : pocket)
    for (Index p : s.front.item(f).v) corners.push_back(p);
  std::sort(corners.begin(), corners.end());
  corners.erase(std::unique(corners.begin(), corners.end()), corners.end());

  auto sees_all = [&](Index p) {
    for (Index f : pocket) {
      const Triangle& v = s.front.item(f).v;
      if (has_corner(v, p)) continue;
      if (orient3d(s.points[v[0]], s.points[v[1]], s.points[v[2]], s.points[p]) <= 0)
        return false;
    }
    return true;
  };

  Index kernel = kInvalidIndex;
  bool new_point = false;
  {
    const Point c = pocket_centre(s, pocket);
    s.points.push_back(c);
    const Index p = static_cast<Index>(s.points.size() - 1);
    if (sees_all(p)) {
      // Eq. 15 without growth (c_i = 1): the kernel point is joined to every corner of the
      // pocket, so its elements are no larger than the pocket's smallest corner size.
      s.point_size.push_back(
          new_point_size(s.size_field.size_at(c), 1.0, s.point_size, corners));
      kernel = p;
      new_point = true;
    } else {
      s.points.pop_back();
    }
  }
  if (kernel == kInvalidIndex) {
    for (Index q : corners)
      if (sees_all(q)) {
        kernel = q;
        break;
      }
  }
  if (kernel == kInvalidIndex) {
    kernel = kernel_point_beside_a_corner(s, pocket, corners, sees_all);
    if (kernel == kInvalidIndex) kernel = deepest_kernel_point(s, pocket, corners, sees_all);
    new_point = kernel != kInvalidIndex;
  }
  if (kernel == kInvalidIndex) return 0;

  // Every face of the pocket forms its element with the kernel; each element is checked against
  // the front (F7.3) exactly as in the normal loop, so the mesh stays valid whatever happens.
  // Adding an element frees and reuses face slots: remember which face each slot held.
  std::vector<std::uint32_t> stamps;
  for (Index f : pocket) stamps.push_back(s.front.item(f).stamp);
  std::int64_t added = 0;
  for (std::size_t i = 0; i < pocket.size(); ++i) {
    const Index f = pocket[i];
    const FrontItem<3>& ff = s.front.item(f);
    if (!ff.alive || ff.stamp != stamps[i] || has_corner(ff.v, kernel)) continue;
    if (element_crosses_front(s, f, kernel)) continue;
    add_element(s, f, kernel);
    ++added;
  }
  if (new_point && added == 0) {
    s.points.pop_back();
    s.point_size.pop_back();
  }
  return added;
}

}  // namespace afmesh::volume
