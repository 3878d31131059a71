// Element quality measures for tetrahedra and triangles, and a deterministic quality summary of
// a mesh (statistics and fixed-bin histograms).
//
// These are floating-point measurements, not predicates: they are accurate to a few ulps for
// well-shaped elements and tend continuously to their degenerate values (angle 0 or 180°, radius
// ratio 0) as an element flattens. Whether an element is exactly degenerate or inverted is the
// business of the exact predicates (core/geometry/predicates.h) and of validate.h.
//
// Radius ratios (Frey & George, "Mesh Generation", 2nd ed., §18.2):
//   tet:      3 r_in / r_circ, with r_in = 3|V| / (sum of face areas) and r_circ the
//             circumradius; 1 for the regular tetrahedron, 0 for a flat one.
//   triangle: 2 r_in / r_circ, with r_in = 2A / perimeter and r_circ = abc / (4A);
//             1 for the equilateral triangle, 0 for a flat one.
// Both are orientation-free (an inverted tet has the ratio of its mirror image); the sign of a
// tet lives in its signed volume.
#pragma once

#include <cstdint>
#include <limits>
#include <span>
#include <vector>

#include "absl/status/statusor.h"
#include "core/common/progress.h"
#include "core/mesh/mesh.h"

namespace afmesh {

// Quality of one tetrahedron.
struct TetQuality {
  double min_dihedral_deg = 0.0;  // smallest of the 6 dihedral angles, degrees in [0, 180]
  double max_dihedral_deg = 0.0;  // largest of the 6 dihedral angles, degrees in [0, 180]
  double radius_ratio = 0.0;      // 3 r_in / r_circ in [0, 1]
  double volume = 0.0;            // signed: det[b-a, c-a, d-a] / 6 (> 0 for a positive tet)
};

// Quality of one triangle.
struct TriangleQuality {
  double min_angle_deg = 0.0;  // smallest corner angle, degrees in [0, 60]
  double radius_ratio = 0.0;   // 2 r_in / r_circ in [0, 1]
  double area = 0.0;           // >= 0
};

// Signed volume det[b-a, c-a, d-a] / 6 of tet (a, b, c, d), in length units cubed.
double tet_signed_volume(const Point& a, const Point& b, const Point& c, const Point& d);

// Quality of tet (a, b, c, d). A tet with zero volume has radius ratio 0; one with coincident
// points has dihedral angles 0 where they are undefined.
TetQuality tet_quality(const Point& a, const Point& b, const Point& c, const Point& d);

// Quality of `tet` of `points` (N×3). Indices must be in range.
TetQuality tet_quality(const std::vector<Point>& points, const Tet& tet);

// Quality of triangle (a, b, c). A triangle with coincident points has min angle 0.
TriangleQuality triangle_quality(const Point& a, const Point& b, const Point& c);

// triangle_quality(a, b, c).min_angle_deg, bit for bit, without the area and radius ratio.
double triangle_min_angle_deg(const Point& a, const Point& b, const Point& c);

// Quality of `triangle` of `points` (N×3). Indices must be in range.
TriangleQuality triangle_quality(const std::vector<Point>& points, const Triangle& triangle);

// Mean length of the edges of `surface.triangles` (each shared edge counted from both sides), in
// length units. Triangles with an index out of range are skipped (callers that have not
// validated the surface yet); 1 when no triangle is left.
double mean_edge_length(const Mesh& surface);

// The `triangles` (over `points`) that come within `radius` of x: how many, their shortest and
// longest edges and their smallest angle (not in the paper: what a failure message says of the
// input where a front stopped). A scan of all triangles, for a job that has already failed.
// With none near, count is 0 and the rest as initialised.
struct TrianglesNear {
  std::int64_t count = 0;
  double shortest_edge = std::numeric_limits<double>::infinity();
  double longest_edge = 0.0;
  double smallest_angle_deg = 180.0;
};
TrianglesNear triangles_near(std::span<const Point> points, std::span<const Triangle> triangles,
                             const Point& x, double radius);
// Whether triangle t (over `points`) comes within `radius` of x (its closest point to x does):
// the triangles that triangles_near counts. A long input triangle passing by counts though its
// corners lie far away.
bool comes_near(std::span<const Point> points, const Triangle& t, const Point& x, double radius);

// A histogram with `bins` equal bins over [lo, hi]. A value below lo counts in the first bin and
// one at or above hi in the last (measures may overshoot their range by rounding); NaN values
// are counted in `nan_count` only.
struct Histogram {
  double lo = 0.0;
  double hi = 1.0;
  std::vector<std::int64_t> counts;  // bins entries; bin i covers [lo + i w, lo + (i+1) w)
  std::int64_t nan_count = 0;

  Histogram() = default;
  Histogram(double lo, double hi, int bins);

  void add(double value);
  // Lower edge of bin i.
  double bin_lo(int i) const;
  // Sum of all counts, nan_count included: the number of values added.
  std::int64_t total() const;
};

// Count, extremes and mean of one measure over a mesh. All zero when count is 0.
struct MeasureStats {
  std::int64_t count = 0;
  double min = 0.0;
  double max = 0.0;
  double mean = 0.0;
};

// Quality of a whole mesh. Histograms: dihedral angles 0..180° in 5° bins (36), triangle min
// angle 0..60° in 2° bins (30), radius ratios 0..1 in 0.05 bins (20).
struct QualitySummary {
  std::int64_t tet_count = 0;
  std::int64_t triangle_count = 0;

  MeasureStats tet_min_dihedral_deg;
  MeasureStats tet_max_dihedral_deg;
  MeasureStats tet_radius_ratio;
  MeasureStats tet_volume;
  std::int64_t tets_with_nonpositive_volume = 0;  // floating-point volume <= 0
  double share_min_dihedral_below_10 = 0.0;       // share of tets, in [0, 1]
  double share_min_dihedral_below_20 = 0.0;
  Histogram tet_min_dihedral_hist{0.0, 180.0, 36};
  Histogram tet_max_dihedral_hist{0.0, 180.0, 36};
  Histogram tet_radius_ratio_hist{0.0, 1.0, 20};

  MeasureStats triangle_min_angle_deg;
  MeasureStats triangle_radius_ratio;
  Histogram triangle_min_angle_hist{0.0, 60.0, 30};
  Histogram triangle_radius_ratio_hist{0.0, 1.0, 20};

  // The tets away from the boundary's slivers (not in the paper): what the mesher made where the
  // boundary leaves it free. A tet on a boundary triangle with a corner angle theta has a
  // dihedral angle of about theta or less (the dihedrals at a corner are the angles of a
  // spherical triangle one of whose sides is theta), and the optimiser may not move boundary
  // points, so the tets round a boundary sliver are about as flat as it is: on gmsh-meshed OCC
  // solids with thin steps (bench/sweep), tets of 0.2-5 degrees lay within two tets of
  // triangles of 0.15-0.8 degrees, and away from them the smallest was 16.2-20.1 degrees. A
  // boundary triangle whose smallest angle is under kSliverTriangleDeg is a sliver; a tet is
  // near one when a corner of it is a corner of a tet that has a corner on a sliver. What else
  // the boundary forces is not told apart: a step thinner than the boundary's triangles, spanned
  // by tets of four boundary points (the sweep's s013_box_cut: 12.66 degrees away from its five
  // slivers of 9.5 degrees, at every size).
  std::int64_t boundary_slivers = 0;
  std::int64_t tets_away_from_slivers = 0;
  MeasureStats away_min_dihedral_deg;
  double share_away_below_20 = 0.0;  // of the tets away from slivers
};

// A boundary triangle whose smallest corner angle is under this (degrees) is a sliver
// (QualitySummary::boundary_slivers).
inline constexpr double kSliverTriangleDeg = 20.0;

// Quality of every tet and triangle of `mesh`, visited in array order (so the result is
// deterministic: means use compensated summation in that order).
// Fails with InvalidArgument, naming the element, when an index is out of range, and with
// CANCELLED within milliseconds once progress.cancelled() turns true.
absl::StatusOr<QualitySummary> summarize_quality(const Mesh& mesh,
                                                 Progress& progress = no_progress());

}  // namespace afmesh
