// The size specification: how a user says where small elements go (paper §4.1–4.2).
//
// Plain C++ data, the form the wire / JSON specification is converted to (design.md, "Size
// specification"). The size wanted at x is
//
//   delta(x) = min(max_size, delta_1(x), ..., delta_m(x), delta_bg(x))        (eq. 14)
//
// over the sources delta_i (eq. 1–13) and the background grid delta_bg; inside a front the sizes
// attached to the front's points, grown by `growth` (c_i), also bound it (eq. 15).
//
// Each source is a point, a segment or a triangle (1, 2 or 3 points). With r(x) the Euclidean
// distance from x to that closed set and rho = max(0, (r - r0) / r1) (eq. 10), its size is
//   power        delta0 (1 + rho^gamma)             (eq. 11)
//   exponential  delta0 exp(gamma rho)              (eq. 12)
//   polynomial   delta0 (1 + sum_i a_i rho^i)       (eq. 13), coefficients = [a_1, ..., a_n]
// Every law must grow (or stay constant) with distance: the smallest size of a source is delta0,
// on the source and up to r0 from it. validate_size_spec enforces that (gamma > 0 for power,
// gamma >= 0 for exponential, a_i >= 0), and the evaluation's pruning relies on it.
#pragma once

#include <optional>
#include <variant>
#include <vector>

#include "absl/status/status.h"
#include "core/mesh/mesh.h"

namespace afmesh {

// eq. 11: delta0 (1 + rho^gamma). gamma > 0; typically 1 <= gamma <= 2.
struct PowerLaw {
  double gamma = 1.0;
};

// eq. 12: delta0 exp(gamma rho). gamma >= 0.
struct ExponentialLaw {
  double gamma = 1.0;
};

// eq. 13: delta0 (1 + a_1 rho + ... + a_n rho^n), coefficients = [a_1, ..., a_n], each >= 0.
// An empty list is the constant delta0. The paper finds n = 2 enough.
struct PolynomialLaw {
  std::vector<double> coefficients;
};

// No law was given (an unset choice on the wire): validate_size_spec rejects it.
struct NoLaw {};

using DecayLaw = std::variant<NoLaw, PowerLaw, ExponentialLaw, PolynomialLaw>;

// One point, line or surface source (eq. 1–13).
struct SizeSource {
  std::vector<Point> points;  // 1, 2 or 3 points (×3): point, segment or triangle
  double delta0 = 0.0;        // size on the source (> 0)
  double r0 = 0.0;            // radius of constant size delta0 around the source (>= 0)
  double r1 = 0.0;            // scaling length (> 0)
  DecayLaw law;
};

// A tetrahedral background grid with a size at every point, interpolated linearly inside each
// tet; points outside the grid take the size of the nearest grid point.
struct BackgroundGridSpec {
  std::vector<Point> points;  // N×3, N >= 4
  std::vector<Tet> tets;      // K×4 point indices, K >= 1, each positive (mesh.h convention)
  std::vector<double> sizes;  // N, one size (> 0) per point
};

struct SizeSpec {
  // Upper bound on the size everywhere (> 0). Also the size at the nodes of the default
  // background grid (the input's bounding box split into five tets) when `background` is unset.
  double max_size = 0.0;
  // Growth factor c_i of eq. 15 (>= 1): 1 keeps elements uniform, 1.5 lets them grow fast.
  double growth = 1.0;
  std::vector<SizeSource> sources;
  std::optional<BackgroundGridSpec> background;
};

// OK when `spec` can be evaluated; otherwise INVALID_ARGUMENT naming the first offending field as
// the JSON specification spells it (design.md), e.g.
//   "sources[3].r1 must be > 0, got -1"
//   "sources[0].points must hold 1, 2 or 3 points (point, line or triangle source), got 4"
//   "background.tets[7] is inverted (negative volume): ..."
// Checks: finite numbers everywhere; max_size > 0; growth >= 1; per source 1–3 points, delta0 >
// 0, r0 >= 0, r1 > 0, a law with valid parameters; for the background grid (validated as by
// validate_background_grid below).
absl::Status validate_size_spec(const SizeSpec& spec);

// OK when `grid` is a usable background grid; errors name fields under `field` (e.g.
// "background"): at least 4 finite points and 1 tet, one finite size > 0 per point, tet indices
// in range, every tet of positive volume (exact orientation test). Overlap between tets is not
// checked: the grid must be conforming (tets meet only in shared faces, edges and points).
absl::Status validate_background_grid(const BackgroundGridSpec& grid,
                                      const char* field = "background");

}  // namespace afmesh
