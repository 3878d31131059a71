// The integration check shared by the volume tests: mesh a front the way a user would and check
// the result against invariants.
#pragma once

#include <string>

#include "core/quality/validate.h"
#include "core/volume/generate_volume_mesh.h"
#include "gtest/gtest.h"

namespace afmesh {

// Meshes `front` with `params` and checks the result the way a user would: valid, boundary
// equal to the front, volumes adding up, and no element worse than the quality bar.
inline VolumeResult mesh_and_check(const Mesh& front, const VolumeParams& params) {
  absl::StatusOr<VolumeResult> result = generate_volume_mesh(front, params, no_progress());
  EXPECT_TRUE(result.ok()) << result.status();
  if (!result.ok()) return {};
  // The front closed: it was not filled from its points instead (kDelaunayFillWords).
  for (const std::string& warning : result->warnings)
    EXPECT_EQ(warning.find(kDelaunayFillWords), std::string::npos) << warning;
  const ValidationReport report = validate_volume_mesh(result->mesh, &front);
  EXPECT_TRUE(report.valid()) << report.to_string();
  // The input front's points come first, unchanged.
  for (std::size_t p = 0; p < front.points.size(); ++p)
    EXPECT_EQ(result->mesh.points[p], front.points[p]) << "point " << p;
  return *std::move(result);
}

// The same at the uniform size h and growth c_i.
inline VolumeResult mesh_and_check(const Mesh& front, double h, double growth = 1.0) {
  VolumeParams params;
  params.size = h;
  params.growth = growth;
  return mesh_and_check(front, params);
}

}  // namespace afmesh
