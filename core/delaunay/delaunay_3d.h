// Incremental Delaunay tetrahedralisation (Bowyer 1981, Watson 1981), not in the paper.
//
// The volume front (F1–F11) builds its elements one at a time and can stop where the front it
// was given leaves no room for a well-shaped element (a CAD tessellation's slivers, issue 10
// part 3). The fill of such a region starts from a tetrahedralisation of its points that needs
// no front at all; this module makes it.
//
// Robustness: every decision is an exact predicate (core/geometry/predicates.h). Ties of the
// empty-sphere test (five or more points on one sphere, a grid's points) are broken by a
// symbolic perturbation, as if each point's lift |x|^2 onto the paraboloid were raised by an
// infinitesimal that grows with the order in which the points came (Edelsbrunner & Mücke 1990,
// "Simulation of simplicity"; Devillers & Teillaud 2011 for this use): the triangulation is then
// the unique one of the perturbed points, every cavity of the insertion is star-shaped about
// its new point and no flat element is ever made, whatever the input's degeneracies.
//
// The points are enclosed in a tetrahedron of four far corners made first; elements on a far
// corner are not reported, so near the points' convex hull the result can lack a few elements
// of the points' own Delaunay tetrahedralisation (those whose circumsphere reaches a far corner).
// Points are inserted in Z order (core/spatial/z_order.h) and located by a walk from the last
// element made, so that a walk is short: O(N log N) for the sort, about O(1) per point after it
// for points spread evenly.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "absl/container/flat_hash_map.h"
#include "absl/status/statusor.h"
#include "core/mesh/mesh.h"
#include "core/spatial/box.h"

namespace afmesh {

// An incremental Delaunay tetrahedralisation of points inside a box fixed at construction.
class Delaunay3 {
 public:
  // Starts with the one element of four far corners enclosing `bounds` (any box, even of no
  // extent, with finite corners).
  explicit Delaunay3(const Box& bounds);

  // Inserts x (inside the constructor's box, or at least inside the far corners' tetrahedron)
  // and returns its vertex (0 for the first point inserted, and so on). A point equal to one
  // inserted before is not inserted again: that point's vertex is returned. INVALID_ARGUMENT when
  // x is not finite or lies outside the far corners' tetrahedron.
  absl::StatusOr<Index> insert(const Point& x);

  // The points inserted, by vertex (N×3).
  const std::vector<Point>& points() const { return points_; }
  // The elements none of whose corners is a far corner (K×4, vertices of points(), positive).
  std::vector<Tet> tets() const;

 private:
  static constexpr int kFar = 4;  // the far corners are vertices 0..3 of vertices_
  struct Element {
    Tet v;                                  // vertices_ ids, positive
    std::array<Index, 4> across{};          // the element across the face opposite v[i]
    bool alive = true;
  };
  // The element whose closed interior holds x, by a walk from `start` choosing among the faces
  // x lies beyond in a pseudo-random order (a stochastic walk: it cannot cycle), or none
  // (kInvalidIndex) when x is beyond the far corners' tetrahedron.
  Index locate(const Point& x, Index start);
  // Sign of the perturbed empty-sphere test: +1 when vertex `x` (the newest) lies inside the
  // circumsphere of element e, -1 when outside (ties broken as described above).
  int in_sphere(const Element& e, Index x) const;
  // Bowyer–Watson: the elements whose circumsphere holds vertex x (the cavity, grown from
  // `seed`), replaced by the elements joining x to the cavity's boundary faces.
  absl::Status fill_cavity(Index seed, Index x);
  Index new_element(const Tet& v);
  std::uint32_t next_random();

  std::vector<Point> vertices_;  // the far corners, then points_ in order
  std::vector<Point> points_;
  std::vector<Element> elements_;
  std::vector<Index> free_;  // dead elements whose slots new ones reuse (new_element)
  Index last_ = 0;           // an element made last: where the next walk starts
  std::uint32_t random_ = 0x9E3779B9u;
  // Per element: the insertion that last looked at it (cavity, or tested outside of it).
  std::vector<std::uint32_t> seen_;
  std::vector<bool> in_cavity_;
  std::uint32_t visit_ = 0;
  std::vector<Index> cavity_;
  struct BoundaryFace {
    Index element;  // in the cavity
    int face;       // opposite element.v[face]
  };
  std::vector<BoundaryFace> boundary_;
  struct Plan {  // a new element
    Tet v;
    int face;       // opposite the new vertex
    Index beyond;   // across that face, or none
    int back = -1;  // the face of `beyond` on the cavity
  };
  std::vector<Plan> plans_;
  struct Open {  // a new element's face on the new vertex
    Index element;
    int face;
  };
  // By the cavity's boundary edge the face holds (its two vertices, the lower in the high word).
  absl::flat_hash_map<std::uint64_t, Open> open_;
};

// The Delaunay tetrahedralisation of `points` (N×3), inserted in Z order. `vertex_of_point[i]`
// is the vertex of point i: points repeated map to the vertex of their first copy, so
// `tets` (K×4, positive) index the first copies, and a point given twice is one vertex.
// INVALID_ARGUMENT when a point is not finite.
struct DelaunayTets {
  std::vector<Tet> tets;                // indices into the input points
  std::vector<Index> vertex_of_point;   // N: for each input point, the input point it merged into
};
absl::StatusOr<DelaunayTets> delaunay_tetrahedralise(const std::vector<Point>& points);

}  // namespace afmesh
