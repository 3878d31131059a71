// A tetrahedral mesh with face adjacency, for the local topological changes of the optimiser
// (optimise.h): walking around an edge, collecting the ball of a point, and replacing a small
// cavity of tets by new tets with the adjacency updated locally.
//
// The tets are those of a Mesh (K×4, positive, conforming: every face in one or two tets),
// edited in place. A face with no neighbour is a boundary face; replace() keeps the faces on the
// cavity's outside exactly as they are unless asked otherwise, so boundary faces are never
// removed by the optimiser's operations built on it. Deleted tets leave a slot (first index
// kInvalidIndex) that the next new tet reuses (last freed, first reused); compact() drops the
// empty slots at the end. Every result depends only on the order of calls, never on addresses or
// hashing.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "absl/status/statusor.h"
#include "absl/types/span.h"
#include "core/common/progress.h"
#include "core/mesh/mesh.h"

namespace afmesh {

// The tets around an edge (a, b): tets[i] = (a, b, ring[i], ring[i+1]) up to an even
// permutation (so orient3d(a, b, ring[i], ring[i+1]) > 0 for a positive mesh), indices mod n
// around an interior edge (TetComplex::edge_ring); around a boundary edge (edge_fan) ring has
// n + 1 corners and does not wrap.
struct EdgeRing {
  Index a = kInvalidIndex;
  Index b = kInvalidIndex;
  std::vector<Index> tets;  // n
  std::vector<Index> ring;  // n
};

class TetComplex {
 public:
  // Adjacency of mesh.tets over mesh.points (kept by reference; both are edited by the calls
  // below). O(K log v) time with v the mean number of tets at a point; 16 bytes per tet and 4
  // per point are kept, 12 bytes per tet more while building.
  // Fails with InvalidArgument, naming what is wrong, when an index is out of range or repeated
  // in a tet and when a face is in more than two tets.
  // CANCELLED within milliseconds once progress.cancelled() turns true.
  static absl::StatusOr<TetComplex> build(Mesh& mesh, Progress& progress = no_progress());

  const Mesh& mesh() const { return *m_; }
  const std::vector<Point>& points() const { return m_->points; }
  const Point& point(Index p) const { return m_->points[p]; }
  void move_point(Index p, const Point& x) { m_->points[p] = x; }
  const Tet& tet(Index t) const { return m_->tets[t]; }
  Index slots() const { return static_cast<Index>(m_->tets.size()); }
  bool alive(Index t) const { return m_->tets[t][0] != kInvalidIndex; }
  // The tet across the face of t opposite its corner `corner`, or kInvalidIndex at the boundary.
  Index neighbour(Index t, int corner) const { return adjacent_[t][corner]; }
  // Position (0..3) of point p in tet t, or -1.
  int corner_of(Index t, Index p) const;

  // The ring of tets around edge (a, b) of tet t. False when the edge is on the boundary (the
  // walk around it meets a face with no neighbour) or has more than max_tets tets around it.
  bool edge_ring(Index t, Index a, Index b, int max_tets, EdgeRing& out) const;
  // The tets around a boundary edge (a, b) of tet t, from one boundary face to the other:
  // tets[i] = (a, b, ring[i], ring[i+1]) up to an even permutation, so ring has one corner more
  // than tets. False for an interior edge or more than max_tets tets.
  bool edge_fan(Index t, Index a, Index b, int max_tets, EdgeRing& out) const;

  // The live tets that use point p, in the order of a breadth-first walk from a fixed start
  // (deterministic). Empty for a point no tet uses. Once replace(..., boundary_may_change) has
  // left part of a cavity empty, the tets at p may no longer be joined through faces (the
  // region pinches at p): the walk then finds those joined to the tet it starts from only.
  void ball(Index p, std::vector<Index>& out) const;

  // Replaces the distinct live tets `old` by `fresh` (positive tets filling the same region;
  // the caller checks the geometry). The faces of `fresh` must pair up among themselves
  // (opposite orientations) except for exactly the faces on the outside of `old`, with the same
  // orientation; every point of `old` must be used by `fresh`. When that holds the tets are
  // replaced, the new tets' slots are appended to `created` in the order of `fresh` (tags 0),
  // and the result is true; otherwise nothing changes and the result is false.
  // With boundary_may_change, outside faces of `old` may be left out (the tets beyond them get
  // a boundary face there), faces of `fresh` that pair with nothing become boundary faces, and
  // points of `old` may be left unused: a flip of the boundary itself (two coplanar boundary
  // faces turned), or a cavity refilled in part (recover_faces.h), whose geometry the caller
  // checks.
  // `dropped`, a point of `old`, may (and must) be left unused by `fresh`: an edge contraction's
  // removed point (propose_edge_contraction). It is used by no tet afterwards and compact()
  // removes it from mesh.points.
  bool replace(absl::Span<const Index> old, absl::Span<const Tet> fresh,
               std::vector<Index>& created, bool boundary_may_change = false,
               Index dropped = kInvalidIndex);

  // Appends a point to mesh.points (used by no tet yet) and returns its index.
  Index add_point(const Point& x);
  // Removes the last point, which no tet may use.
  void drop_last_point();

  // Moves the live tets to the front of mesh.tets (keeping their order) and drops the rest;
  // removes the points replace() dropped from mesh.points (the others keep their order, the
  // tets' indices follow). The complex must not be used afterwards.
  void compact();

 private:
  explicit TetComplex(Mesh& mesh) : m_(&mesh) {}
  // Clears `out` for edge (a, b) and sets u, v to t's other corners with t = (a, b, u, v) up to
  // an even permutation; false when a or b is not a corner of t.
  bool start_around(Index t, Index a, Index b, EdgeRing& out, Index& u, Index& v) const;
  // The corner of tet t other than a, b and c.
  Index other_corner(Index t, Index a, Index b, Index c) const;
  Index new_slot();

  Mesh* m_;
  std::vector<std::array<Index, 4>> adjacent_;  // K×4: neighbour across the face opposite corner i
  std::vector<Index> point_tet_;                // N: one live tet using the point, or kInvalidIndex
  std::vector<Index> free_;                     // deleted slots, reused last-in first-out
  std::vector<Index> dropped_;                  // points replace() dropped, for compact()
};

}  // namespace afmesh
