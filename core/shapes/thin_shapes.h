// Fronts with thin and crossing surfaces (paper §2 and §5 (a), (b)): the shipped examples
// examples/dome/dome.mesh and examples/sails/sails.mesh are these surfaces with the default
// parameters (written by the make-thin-examples tool in tests/environments/). Deterministic:
// the same parameters give the same points, triangles and tags, in the same order.
//
// Both are fronts of an air domain: closed, manifold, consistently oriented with normals
// pointing out of the air (into the solids and out of the outer box). The two sides of each
// thin structure are triangulated independently, so their triangles cross; the triangle tags are
// crossing-environment ids (environments.h), one per side, 0 elsewhere.
#pragma once

#include <cstdint>

#include "core/mesh/mesh.h"

namespace afmesh {

// ---------------------------------------------------------------------------------------------
// The paper's quarter dome (§5 (a), Figure 12): a hemispherical shell of inner radius r_i and
// outer radius r_o = r_i + thickness on the ground plane z = 0, in the octant x, y, z >= 0 of a
// box [0, L]^3. The domain is the air inside the shell (the octant of the ball r < r_i) and
// outside it (the box minus the ball r < r_o): two closed components. The symmetry planes x = 0,
// y = 0 and the ground z = 0 bound both; the shell's own cross-section (r_i < r < r_o) on them
// is not part of the domain.
//
// Triangulation: each sphere octant is the spherical triangle between the axes, subdivided into
// n^2 triangles with equal-angle arcs on the planes (inner n = inner_divisions, outer
// n = outer_divisions; different on purpose: the two sides are independent and, at a chord
// sag of about h^2 / (8 r) = 0.002-0.003 > r_o - r_i, they cross). The quarter disks r <= r_i
// on the planes are sector grids sharing the inner arcs; the outer planes (the square [0, L]^2
// minus the disk r < r_o) are grids from the outer arc to the square's edges with
// `radial_layers` rings growing geometrically, sharing the outer arcs; the box faces x, y, z = L
// are uniform grids of outer_divisions / 2 squares per edge.
//
// Tags (environment ids): the inner component (inner sphere and its three quarter disks) is
// kDomeInsideEnvironment, the outer sphere and the three outer planes are
// kDomeOutsideEnvironment, the box faces x, y, z = L are 0. The planes must carry the
// environments too: on each symmetry plane the inner disk's and the outer plane's polygons
// overlap along the shell's cut (both arcs are chords of circles 1/1000 apart), so these
// faces cross as well, and only faces of two different positive environments may cross.
// ---------------------------------------------------------------------------------------------
inline constexpr std::int32_t kDomeInsideEnvironment = 1;
inline constexpr std::int32_t kDomeOutsideEnvironment = 2;

struct QuarterDomeParams {
  double box_side = 3.0;        // L
  double inner_radius = 1.0;    // r_i
  double thickness = 0.001;     // r_o - r_i (1/1000 of the radius, as in the paper)
  int inner_divisions = 10;     // arc segments of a quarter circle of the inner sphere (>= 2)
  int outer_divisions = 12;     // likewise for the outer sphere; even (the box corners), >= 2
  int radial_layers = 7;        // rings of the outer planes between r_o and the box (>= 1)
  double radial_growth = 1.3;   // ratio of successive ring widths (>= 1)
};

Mesh quarter_dome_surface(const QuarterDomeParams& params = {});

// ---------------------------------------------------------------------------------------------
// The whole hemispherical shell of issue 10 (part 6): inner radius r_i, outer radius r_i +
// thickness, on the ground z = 0 in the box [-L/2, L/2]^2 x [0, L] (L = box_side, 4 r_i by
// default). As for the quarter dome, the domain is the air inside the shell (the half ball r <
// r_i) and outside it (the box minus the half ball r < r_o); the ground closes both.
//
// Triangulation by rings, each side on its own: a hemisphere of n rings (inner_rings,
// outer_rings) has ring k at elevation (pi/2) k / n with about 4 n cos(elevation) points (n = 1
// point at the pole), ring k turned by (phase + k / 2) of its step (inner_phase, outer_phase:
// different, so the two sides' points do not line up); consecutive rings are joined in the order
// of their angles. The inner ground disk has rings of the same step down to its centre; the
// ground outside r_o goes from the outer equator to the box's bottom edges through
// `radial_layers` rings growing geometrically; the box's four walls and its top are uniform grids
// of about `box_size` squares. At the default shell size (a quarter circle in 20 and 22 steps,
// 0.08 r_i) the chord sag exceeds the thickness: the sides cross.
//
// Tags: the inner hemisphere and the ground disk kDomeInsideEnvironment, the outer hemisphere and
// the ground outside it kDomeOutsideEnvironment, the walls and the top 0.
// ---------------------------------------------------------------------------------------------
struct HemisphericalShellParams {
  double inner_radius = 1.0;
  double thickness = 0.001;
  double box_side = 4.0;
  double box_size = 0.5;
  int inner_rings = 20;  // >= 2
  int outer_rings = 22;  // >= 2
  double inner_phase = 0.0;
  double outer_phase = 0.37;
  int radial_layers = 6;  // >= 1
  double radial_growth = 1.4;  // >= 1
};

Mesh hemispherical_shell_surface(const HemisphericalShellParams& params = {});

// ---------------------------------------------------------------------------------------------
// Two inclined sails (§5 (b), Figure 13): a jib and a mainsail, each a thin closed body about
// 30 m high whose two sides are `thickness` (1 mm) apart over the sail and meet at its rim,
// with a narrow slot (about 1 m) between the jib's trailing edge and the mainsail, heeled by
// `heel_deg` about the x axis, inside a box far larger than the sails.
//
// Each sail's mid-surface is a cambered trapezoid S(u, v), u along the chord (0 = luff, 1 =
// leech), v along the height; the sides are S ± (t(u, v) / 2) N with N the mid-surface normal
// and t = thickness (1 - (2u-1)^8)(1 - (2v-1)^8), which is the full thickness over most of the
// sail and 0 on the rim, where both sides share their points. Side A is the regular (u, v) grid
// cut along one diagonal; side B moves the interior grid points by a fraction of a cell and cuts
// along the other diagonal: independent triangulations, which cross since the chord sag of the
// cambered sail (centimetres) exceeds the thickness.
//
// Tags: jib side A 1, jib side B 2, main side A 3, main side B 4 (kSail... below), box 0.
// ---------------------------------------------------------------------------------------------
inline constexpr std::int32_t kJibSideA = 1;
inline constexpr std::int32_t kJibSideB = 2;
inline constexpr std::int32_t kMainSideA = 3;
inline constexpr std::int32_t kMainSideB = 4;

struct SailsParams {
  double thickness = 0.001;  // m
  double heel_deg = 10.0;    // inclination about the x axis
  double box_size = 10.0;    // edge length of the box's grid, m
  // Grid cells of each sail side per cell of the default grid, along the chord and the height
  // (>= 1): 1 gives 864 sail triangles, 4 about 13.8k (issue 10, part 6: sails of ~15k
  // triangles).
  int grid_scale = 1;
  // The box's extent about the sails' middle, as a multiple of the default box (70 x 60 x 65 m,
  // about 7 mainsail chords; >= 1). 3 puts the sails in a box about 20 chords wide.
  double box_scale = 1.0;
};

Mesh sails_surface(const SailsParams& params = {});

// ---------------------------------------------------------------------------------------------
// A crossing X of two thin plates (paper §2, Figures 3 and 4: crossing surfaces that are not
// the same, one environment per side of the troublesome region): plate A about the plane y = 0
// over x, z in [-1, 1] and plate B about the plane x = 0 over y, z in [-1, 1], each a thin
// body of thickness `thickness` in the middle tapering to 0 on its rim, its mid-surface
// optionally bulging by `camber` between the crossing and the rim, crossing each other along
// the z axis, in the box [-3, 3]^3. The front is the boundary of the union of the plates (plus
// the box): the air around the X is four quadrant wedges, and the side of quadrant (sign x,
// sign y) is one folded sheet -- plate A's face from the rim to the crossing, then plate B's
// face from the crossing to its rim -- so the sheets of the four quadrants meet only on the
// plates' rims and at the two apexes (0, 0, ±1), where the rims cross. Across each half plate
// the two quadrants' sheets are `thickness` apart and triangulated independently (quadrants 2
// and 4 move their grid); with a bulge whose chord sag exceeds the thickness they cross.
// Tags: the quadrant, 1 = (+x, +y), 2 = (-x, +y), 3 = (-x, -y), 4 = (+x, -y); box (and rim
// strips) 0.
// ---------------------------------------------------------------------------------------------
struct CrossingPlatesParams {
  double thickness = 0.001;
  // Bulge of each plate's mid-surface (0: flat plates, whose sides are `thickness` apart and do
  // not cross). At 0.02 the chord sag of the bulge is several times the thickness, so the two
  // sides of each half plate cross, as on the dome and the sails.
  double camber = 0.02;
  int divisions = 4;  // grid cells across a half plate (rim to crossing); 2 × this in z
  double box_size = 1.0;  // edge length of the box's grid
  // The angle between the plates (degrees, in (0, 180)): plate B is turned about the z axis
  // from the plane x = 0 so that the quadrant (+x, +y) spans this angle. 60 is issue 10's plates
  // crossing at ±30°.
  double angle_deg = 90.0;
  // Plates of the same thickness everywhere whose rims are closed by narrow strips (`thickness`
  // wide, tag 0: the faces of no environment a user would leave untagged) instead of tapering to
  // 0 on the rim; at z = ±1 a small cap joins the strips where the corner lines end.
  bool rim_strips = false;
};

Mesh crossing_plates_surface(const CrossingPlatesParams& params = {});

}  // namespace afmesh
