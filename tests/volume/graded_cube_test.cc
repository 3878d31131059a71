// Issue 4's check of the whole size chain: the unit cube with a point source at its corner
// (0, 0, 0), its surface graded to the specification (core/shapes/graded_surface.h), meshed by
// generate_volume_mesh with VolumeParams.spec. The mean tet edge length per bin of distance to
// the corner must follow the law within 10% of the law's size at the bin's centre (20% in the
// bins past r = 1.4, by the far corner).
//
// Parameters: delta0 = 0.03 on the source and within r0 = 0.05 of it, then the power law
// delta0 (1 + rho), rho = (r - r0) / r1 with r1 = 0.2 (gamma = 1: a linear ramp, so the law at a
// bin's centre is the mean of the law over the bin's range), capped by maxSize = 0.25 beyond
// r = 1.52. Sizes then span 0.03 to 0.25 (a factor 8) across the cube while the mesh stays near
// ten thousand tets (fast). The law grows by delta0 / r1 = 0.15 of a size per size travelled,
// a factor 1.15 per element layer; growth c_i = 1.5 (the paper's fast end) lets the sizes attached
// to the front follow it, so eq. 15's attached-size bound never binds before the law does.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <vector>

#include "absl/container/flat_hash_set.h"
#include "core/common/progress.h"
#include "core/geometry/vec.h"
#include "core/quality/validate.h"
#include "core/shapes/graded_surface.h"
#include "core/shapes/shapes.h"
#include "core/sizing/spec_size_field.h"
#include "core/volume/generate_volume_mesh.h"
#include "gtest/gtest.h"

namespace afmesh {
namespace {

constexpr double kDelta0 = 0.03, kR0 = 0.05, kR1 = 0.2, kMaxSize = 0.25, kGrowth = 1.5;

// eq. 10, 11, 14 for the corner source and maxSize.
double law(double r) {
  const double rho = std::max(0.0, (r - kR0) / kR1);
  return std::min(kMaxSize, kDelta0 * (1.0 + rho));
}

SizeSpec corner_source_spec() {
  SizeSpec spec;
  spec.max_size = kMaxSize;
  spec.growth = kGrowth;
  spec.sources.push_back(SizeSource{{{0.0, 0.0, 0.0}}, kDelta0, kR0, kR1, PowerLaw{.gamma = 1.0}});
  return spec;
}

// The unique edges of the tets, each as (a, b) with a < b.
std::vector<std::array<Index, 2>> tet_edges(const Mesh& mesh) {
  absl::flat_hash_set<std::uint64_t> seen;
  std::vector<std::array<Index, 2>> edges;
  for (const Tet& tet : mesh.tets) {
    for (int i = 0; i < 4; ++i) {
      for (int j = i + 1; j < 4; ++j) {
        const Index a = std::min(tet[i], tet[j]), b = std::max(tet[i], tet[j]);
        if (seen.insert((std::uint64_t(a) << 32) | std::uint32_t(b)).second)
          edges.push_back({a, b});
      }
    }
  }
  return edges;
}

struct Bin {
  double lo = 0.0, hi = 0.0;  // distance range [lo, hi) of edge midpoints to the corner
  int edges = 0;
  double length_sum = 0.0;
  double relative_sum = 0.0;  // sum of length / law(distance of the edge's midpoint)
};

TEST(GradedCube, MeanTetEdgeLengthPerDistanceBinFollowsThePointSourceLaw) {
  const SizeSpec spec = corner_source_spec();
  absl::StatusOr<SpecSizeField> field = SpecSizeField::create(spec, Box{{0, 0, 0}, {1, 1, 1}});
  ASSERT_TRUE(field.ok()) << field.status();
  absl::StatusOr<Mesh> surface = grade_surface(box_surface({0, 0, 0}, {1, 1, 1}, kMaxSize), *field);
  ASSERT_TRUE(surface.ok()) << surface.status();

  VolumeParams params;
  params.spec = spec;
  absl::StatusOr<VolumeResult> result = generate_volume_mesh(*surface, params, no_progress());
  ASSERT_TRUE(result.ok()) << result.status();
  const Mesh& mesh = result->mesh;
  const ValidationReport report = validate_volume_mesh(mesh, &*surface);
  EXPECT_TRUE(report.valid()) << report.to_string();

  // Bins narrow where the size is small (the law's range over a bin stays below ~40%).
  const std::vector<double> bounds = {0.0, 0.05, 0.1, 0.15, 0.2, 0.3, 0.4, 0.5,
                                      0.6, 0.8,  1.0, 1.2,  1.4, 1.6, 1.8};
  std::vector<Bin> bins;
  for (std::size_t i = 0; i + 1 < bounds.size(); ++i) bins.push_back({bounds[i], bounds[i + 1]});
  for (const auto& [a, b] : tet_edges(mesh)) {
    const double r = norm(lerp(mesh.points[a], mesh.points[b], 0.5));
    for (Bin& bin : bins) {
      if (r >= bin.lo && r < bin.hi) {
        const double length = distance(mesh.points[a], mesh.points[b]);
        ++bin.edges;
        bin.length_sum += length;
        bin.relative_sum += length / law(r);
      }
    }
  }

  std::printf("graded cube: %zu surface triangles, %zu tets, %zu points\n",
              surface->triangles.size(), mesh.tets.size(), mesh.points.size());
  // ratio = mean edge / law at the bin's centre (the check); edge/law(mid) = mean over the
  // bin of each edge's length over the law at its own midpoint (no binning effect).
  std::printf("%4s %13s %7s %9s %9s %7s %14s\n", "bin", "distance", "edges", "law size",
              "mean edge", "ratio", "edge/law(mid)");
  constexpr int kMinEdges = 30;  // fewer edges make no mean worth testing (the corner's tip)
  int tested = 0;
  for (std::size_t i = 0; i < bins.size(); ++i) {
    const Bin& bin = bins[i];
    if (bin.edges == 0) continue;
    const double expected = law(0.5 * (bin.lo + bin.hi));
    const double mean = bin.length_sum / bin.edges;
    const double ratio = mean / expected;
    std::printf("%4zu %6.2f-%-6.2f %7d %9.4f %9.4f %7.3f %14.3f%s\n", i, bin.lo, bin.hi, bin.edges,
                expected, mean, ratio, bin.relative_sum / bin.edges,
                bin.edges < kMinEdges ? "  (too few edges: not tested)" : "");
    if (bin.edges < kMinEdges) continue;
    ++tested;
    // Issue 10: within 10% along the law's ramp; 20% in the last bins, where the cap and the
    // cube's far corner meet (its elements lean on the boundary's triangles).
    const double tolerance = bin.hi <= 1.4 + 1e-12 ? 0.10 : 0.20;
    EXPECT_NEAR(ratio, 1.0, tolerance) << "bin " << i << " [" << bin.lo << ", " << bin.hi << ")";
  }
  EXPECT_GE(tested, 10);
}

}  // namespace
}  // namespace afmesh
