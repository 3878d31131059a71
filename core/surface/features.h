// Ridges, corners, discrete lines and surface patches of a discrete surface (end of paper §3).
//
// "In order to avoid gridding over 'edges' or 'corners', it is advisable to first identify
// these. A simple way to determine edges is by comparing the surface normals of adjacent faces.
// [...] Corners are defined as points where more than two edges meet. The definition of edges
// and corners [...] leads naturally to the definition of discrete lines and surface patches."
// The surface front then puts sides on the lines first (F3, split_lines.h) and grids each patch
// in turn.
//
// Steps (find_surface_features):
//  1. Line edges: an input edge becomes part of a discrete line when it is
//     - a ridge: two faces whose unit normals (the second turned when the two traverse the edge
//       the same way, i.e. disagree in orientation) make an angle above ridge_angle_deg
//       (n_1 · n_2 < cos(angle), the paper's "scalar product below a tolerance");
//     - a boundary edge (one face: the rim of an open surface);
//     - a non-manifold edge (three or more faces);
//     - a tag edge: two faces with different input tags (Medit references, Gmsh physical tags).
//     An edge next to a degenerate face (zero normal) is a ridge only for the other reasons (our
//     choice: such a face has no direction to compare).
//     Short free ridges are dropped (FeatureParams::short_ridge_sizes; not in the paper), and so
//     are the ridges round islands of a few faces shorter than that (a scan's spikes; not in
//     the paper either).
//  2. Corners: input vertices where a line ends (one line edge), where more than two line edges
//     meet (the paper's definition), or where a line turns by more than corner_angle_deg (these
//     two are ours: a line must keep its end, and a rim's sharp turn must not be cut by sides).
//  3. Lines: line edges chained from corner to corner through vertices with two line edges, as
//     polylines of input vertices. A closed loop without a corner (a cylinder's rim) starts and
//     ends at its smallest vertex index, which becomes a corner (CornerKind::kLoopStart), and
//     the line is marked closed: the 1-D discretisation needs fixed ends (our choice).
//  4. Patches: connected components of faces across edges that are not line edges, numbered by
//     their smallest face; each keeps its faces' input tag (one tag per patch, since tag edges
//     are line edges).
//
// Everything is ordered by vertex and face indices, so the output depends only on the input.
// Cost O(M log M) for M faces (the edge grouping sorts); chaining and patches are linear.
#pragma once

#include <cstdint>
#include <vector>

#include "absl/status/statusor.h"
#include "core/common/progress.h"
#include "core/mesh/mesh.h"
#include "core/sizing/size_field.h"
#include "core/surface/discrete_surface.h"

namespace afmesh {

// Distinct index types for lines and patches (positions in SurfaceFeatures::lines / patches).
enum class LineId : Index {};
enum class PatchId : Index {};
inline constexpr Index index_of(LineId l) { return static_cast<Index>(l); }
inline constexpr Index index_of(PatchId p) { return static_cast<Index>(p); }

// Why an edge is a line edge (a bit set: an edge may be several at once).
enum LineKind : std::uint8_t {
  kRidgeEdge = 1,
  kBoundaryEdge = 2,
  kNonManifoldEdge = 4,
  kTagEdge = 8,
};

// Why a vertex is a corner (a bit set).
enum CornerKind : std::uint8_t {
  kLineEnd = 1,    // one line edge: a line stops here
  kJunction = 2,   // three or more line edges meet
  kTurn = 4,       // two line edges at an angle above corner_angle_deg
  kLoopStart = 8,  // chosen as the ends of a closed loop without other corners
};

struct FeatureParams {
  // Angle between adjacent face normals above which their edge is a ridge, degrees in (0, 180).
  // 30° is netgen's STL default (yangle): a cube's edges and a cylinder's rims (90°) are ridges,
  // the 11.25° between the side faces of a cylinder with 32 faces around is not.
  double ridge_angle_deg = 30.0;
  // Angle by which a line may turn at a vertex before it is split there, degrees in (0, 180].
  // 60° is netgen's STL default (edgecornerangle): the corners of a square plate (90°) split its
  // rim, a circle of 7 or more segments (turns <= 51.4°) stays one line. 180 never splits.
  double corner_angle_deg = 60.0;
  // Short free ridges (not in the paper): a chain of ridge edges only, from a vertex where it
  // ends freely (one line edge) to its next corner, shorter than short_ridge_sizes times the
  // size at its middle vertex, is not a line. Scans have many (noise across a few facets, 173
  // free ends on cgal_hand at 30°), and a ridge shorter than two elements cannot be followed by
  // sides anyway; its short sides stop the front. Dropping a chain that ends freely never splits
  // or joins patches. Chains are dropped repeatedly, so a tree of short branches goes. No size
  // field keeps every ridge.
  const SizeField* sizes = nullptr;  // in the surface's global frame
  double short_ridge_sizes = 2.0;
};

struct Corner {
  Index vertex = 0;           // input point index
  std::uint8_t kinds = 0;     // CornerKind bits
  std::vector<LineId> lines;  // the lines ending here (a closed loop twice), ascending
};

struct DiscreteLine {
  // Input point indices from corner to corner (>= 2; first == last for a closed loop).
  std::vector<Index> vertices;
  bool closed = false;           // a loop: vertices.front() == vertices.back()
  std::uint8_t kinds = 0;        // LineKind bits, the union over its edges
  std::vector<PatchId> patches;  // the patches touching it, ascending (1 for a dangling ridge)
};

struct Patch {
  Index tag = 0;  // the input tag of its faces
  Index face_count = 0;
  FaceId first_face = kNoFace;  // its smallest face
  std::vector<LineId> lines;    // the lines on its rim or inside it, ascending
};

struct SurfaceFeatures {
  std::vector<Corner> corners;       // ascending by vertex
  std::vector<DiscreteLine> lines;   // in the order chained (from corners ascending)
  std::vector<Patch> patches;        // ascending by first_face
  std::vector<PatchId> face_patch;   // M: the patch of every face
  std::int64_t line_edge_count = 0;  // input edges on lines
  // The short free ridges that are not lines (FeatureParams::short_ridge_sizes): chains and
  // their input edges.
  std::int64_t short_ridges_dropped = 0;
  std::int64_t short_ridge_edges_dropped = 0;
  // The ridges round small islands that are not lines (drop_small_island_ridges in features.cc:
  // a scan's spikes and dimples), by connected set of ridge edges.
  std::int64_t island_ridges_dropped = 0;
  std::int64_t island_ridge_edges_dropped = 0;
};

// The features of `surface` (steps 1–4 above). INVALID_ARGUMENT for angles out of range,
// CANCELLED once progress.cancelled() turns true.
absl::StatusOr<SurfaceFeatures> find_surface_features(const DiscreteSurface& surface,
                                                      const FeatureParams& params = {},
                                                      Progress& progress = no_progress());

// Not in the paper: the faces of `surface` turned by more than kFoldedFaceTurnDeg against each of
// their three neighbours, ascending. Such a face lies folded back over its neighbours: an
// inverted sliver of a CAD tessellation, wound against all three neighbours (occt-misc's
// propeller.stl has one at each blade's root, 1/400 of its neighbours' area); turned to agree
// with them (repair_front), it folds over them, and a surface that follows it crosses itself.
// O(M).
inline constexpr double kFoldedFaceTurnDeg = 120.0;
std::vector<FaceId> folded_faces(const DiscreteSurface& surface);

}  // namespace afmesh
