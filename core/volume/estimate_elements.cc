#include "core/volume/estimate_elements.h"

#include <algorithm>
#include <cmath>
#include <memory>
#include <optional>
#include <vector>

#include "core/geometry/vec.h"
#include "core/quality/validate_common.h"
#include "core/spatial/box.h"
#include "core/volume/generate_volume_mesh.h"

namespace afmesh {
namespace {

// Tetrahedra per volume of a regular tetrahedron of edge h, h^3 / (6 sqrt 2): an advancing-front
// mesh of edges about h is not made of regular tetrahedra only. Measured where the size is the
// surface's own (no boundary layer): 1.06 to 1.08 on the sphere, torus, box and L-block
// (estimate_elements_test.cc).
constexpr double kTetsPerRegularVolume = 1.07;
// How fast sizes grow away from a finer boundary, per unit distance and per unit of (growth - 1):
// measured on the sphere of surface edges 0.1 meshed at 0.3 (13,442 tets). An element of size s is
// about 0.816 s thick, so growing by the factor g per element alone would give (g - 1) / 0.816;
// the optimiser's smoothing grows them a little faster.
constexpr double kLayerGrowthRate = 1.35;
// Points per tetrahedron: 189,507 points for 1,098,436 tets (the L-block example at 0.045), 0.17.
constexpr double kPointsPerTet = 0.18;
// Peak bytes of a job per tetrahedron: the front's state, the optimiser, the validator and the
// mesh being streamed out together. afmesh-server's peak RSS over that L-block job was 213,744 KB,
// 199 bytes per tet with the process's own baseline; a quarter more for headroom.
constexpr double kBytesPerTet = 250;
// Per triangle of the input front: its copy, adjacency, bins and front faces. Not measured apart
// from the tets; an upper bound from the structures' sizes.
constexpr double kBytesPerFrontTriangle = 600;
// The size field is read at the nodes of a lattice of at most about this many points.
constexpr double kLatticePoints = 1 << 18;

double regular_tet_volume(double h) { return h * h * h / (6.0 * std::sqrt(2.0)); }

// Element density (tets per unit volume) for the edge length h.
double density(double h) { return kTetsPerRegularVolume / regular_tet_volume(h); }

// The cumulative integral of the density along x: C(x, y, z) = integral from lo.x to x of
// density(size(s, y, z)) ds, tabulated at the nodes of a lattice over the front's box and
// interpolated trilinearly in between. By the divergence theorem with the field (C, 0, 0), the
// integral of the density over the enclosed domain is the sum over the front's triangles of
// C(centroid) n_x area; exact for a uniform size, since C is then linear in x.
class CumulativeDensity {
 public:
  CumulativeDensity(const Box& box, const SizeField& size_field, double max_size) : lo_(box.lo) {
    double extent[3];
    double volume = 1.0;
    for (int k = 0; k < 3; ++k) {
      extent[k] = std::max(box.hi[k] - box.lo[k], 1e-300);
      volume *= extent[k];
    }
    const double cell = std::cbrt(volume / kLatticePoints);
    for (int k = 0; k < 3; ++k) {
      n_[k] = std::clamp(static_cast<int>(std::ceil(extent[k] / cell)), 1, 1 << 12) + 1;
      step_[k] = extent[k] / (n_[k] - 1);
    }
    table_.assign(static_cast<std::size_t>(n_[0]) * n_[1] * n_[2], 0.0);
    std::vector<Point> row(static_cast<std::size_t>(n_[0]));
    std::vector<double> sizes(row.size());
    for (int j = 0; j < n_[1]; ++j) {
      for (int k = 0; k < n_[2]; ++k) {
        for (int i = 0; i < n_[0]; ++i)
          row[i] = {lo_[0] + i * step_[0], lo_[1] + j * step_[1], lo_[2] + k * step_[2]};
        size_field.sizes_at(row, sizes);
        double previous = density(std::min(sizes[0], max_size));
        double sum = 0.0;
        for (int i = 1; i < n_[0]; ++i) {  // trapezoid rule along the row
          const double d = density(std::min(sizes[i], max_size));
          sum += 0.5 * (previous + d) * step_[0];
          previous = d;
          table_[index(i, j, k)] = sum;
        }
      }
    }
  }

  double at(const Point& p) const {
    int cell[3];
    double t[3];
    for (int k = 0; k < 3; ++k) {
      const double u = std::clamp((p[k] - lo_[k]) / step_[k], 0.0, n_[k] - 1.0);
      cell[k] = std::min(static_cast<int>(u), n_[k] - 2);
      t[k] = u - cell[k];
    }
    double value = 0.0;
    for (int corner = 0; corner < 8; ++corner) {
      double weight = 1.0;
      int node[3];
      for (int k = 0; k < 3; ++k) {
        const int bit = (corner >> k) & 1;
        node[k] = cell[k] + bit;
        weight *= bit ? t[k] : 1.0 - t[k];
      }
      value += weight * table_[index(node[0], node[1], node[2])];
    }
    return value;
  }

 private:
  std::size_t index(int i, int j, int k) const {
    return (static_cast<std::size_t>(k) * n_[1] + j) * n_[0] + i;
  }

  Point lo_;
  int n_[3] = {2, 2, 2};
  double step_[3] = {1, 1, 1};
  std::vector<double> table_;
};

// The tets of the layer along a front triangle of edges e where the size field asks for h > e:
// sizes grow from e with the distance d, size(d) = e + beta d, beta = kLayerGrowthRate (g - 1),
// up to the distance D = (h - e) / beta, or to `depth` when the domain is thinner than that. Per
// unit area: the integral from 0 to D of density(size(d)) dd, minus the density(h) D that the
// interior integral already counted there.
double boundary_layer_tets_per_area(double e, double h, double growth, double depth) {
  if (!(h > e) || !(e > 0)) return 0.0;
  const double beta = kLayerGrowthRate * (growth - 1.0);
  const double d = std::min((h - e) / beta, depth);
  const double outer = e + beta * d;
  const double k = kTetsPerRegularVolume * 6.0 * std::sqrt(2.0);  // density(s) = k / s^3
  const double layer = k / (2.0 * beta) * (1.0 / (e * e) - 1.0 / (outer * outer));
  return std::max(0.0, layer - density(h) * d);
}

}  // namespace

VolumeEstimate estimate_volume_mesh(const Mesh& front, const SizeField& size_field,
                                    double max_size, double growth) {
  const double g = std::max(growth, kMinAttachedGrowth);
  Box box = empty_box();
  for (const Point& p : front.points) enclose(box, p);
  if (is_empty(box) || front.triangles.empty()) return {};
  const bool uniform = dynamic_cast<const UniformSize*>(&size_field) != nullptr;
  const double uniform_size = uniform ? std::min(size_field.size_at(box.lo), max_size) : 0.0;
  const std::optional<CumulativeDensity> cumulative =
      uniform ? std::nullopt : std::make_optional<CumulativeDensity>(box, size_field, max_size);

  // One pass over the triangles: their area, mean edge and size, and the interior integral.
  const std::size_t m = front.triangles.size();
  std::vector<double> areas(m), edges(m), sizes(m);
  std::vector<Point> centroids(m);
  double total_area = 0.0;
  double interior = 0.0;
  for (std::size_t i = 0; i < m; ++i) {
    const Point& a = front.points[front.triangles[i][0]];
    const Point& b = front.points[front.triangles[i][1]];
    const Point& c = front.points[front.triangles[i][2]];
    const Point normal = cross(sub(b, a), sub(c, a));  // twice the area, outward
    areas[i] = 0.5 * norm(normal);
    total_area += areas[i];
    edges[i] = (distance(a, b) + distance(b, c) + distance(c, a)) / 3.0;
    centroids[i] = scale(add(add(a, b), c), 1.0 / 3.0);
    if (cumulative) interior += cumulative->at(centroids[i]) * 0.5 * normal[0];
  }
  const double volume = enclosed_volume(front.points, front.triangles, nullptr);
  if (uniform) {
    interior = volume * density(uniform_size);
    std::fill(sizes.begin(), sizes.end(), uniform_size);
  } else {
    size_field.sizes_at(centroids, sizes);
    for (double& h : sizes) h = std::min(h, max_size);
  }

  // The layers grow from every side: none is deeper than twice the domain's mean half-thickness
  // V / A (a slab of thickness t has V / A = t / 2; a ball of radius r, r / 3).
  const double depth = total_area > 0 ? 2.0 * std::max(0.0, volume) / total_area : 0.0;
  double layer = 0.0;
  VolumeEstimate estimate;
  for (std::size_t i = 0; i < m; ++i) {
    layer += areas[i] * boundary_layer_tets_per_area(edges[i], sizes[i], g, depth);
    const double ratio = edges[i] / sizes[i];
    if (ratio > kCoarseFrontRatio) {
      ++estimate.coarse_front_triangles;
      estimate.coarsest_front_ratio = std::max(estimate.coarsest_front_ratio, ratio);
    }
  }

  estimate.tets = std::max(0.0, interior) + layer;
  estimate.points = static_cast<double>(front.points.size()) + kPointsPerTet * estimate.tets;
  estimate.bytes = kBytesPerTet * estimate.tets + kBytesPerFrontTriangle * static_cast<double>(m);
  return estimate;
}

absl::StatusOr<VolumeEstimate> estimate_volume_mesh(const Mesh& front, const VolumeParams& params) {
  absl::StatusOr<std::unique_ptr<SizeField>> size_field = make_size_field(params, front);
  if (!size_field.ok()) return size_field.status();
  const double max_size = params.spec ? params.spec->max_size : params.size;
  const double growth = params.spec ? params.spec->growth : params.growth;
  return estimate_volume_mesh(front, **size_field, max_size, growth);
}

}  // namespace afmesh
