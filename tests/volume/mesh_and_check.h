// The integration check shared by the volume tests: mesh a front the way a user would and check
// the result against invariants.
#pragma once

#include "core/quality/validate.h"
#include "core/volume/generate_volume_mesh.h"
#include "gtest/gtest.h"

namespace afmesh {

// Meshes `front` and checks the result the way a user would: valid, boundary equal to the front,
// volumes adding up, and no element worse than the quality bar.
inline VolumeResult mesh_and_check(const Mesh& front, double h, double growth = 1.0) {
  VolumeParams params;
  params.size = h;
  params.growth = growth;
  absl::StatusOr<VolumeResult> result = generate_volume_mesh(front, params, no_progress());
  EXPECT_TRUE(result.ok()) << result.status();
  if (!result.ok()) return {};
  const ValidationReport report = validate_volume_mesh(result->mesh, &front);
  EXPECT_TRUE(report.valid()) << report.to_string();
  // The input front's points come first, unchanged.
  for (std::size_t p = 0; p < front.points.size(); ++p)
    EXPECT_EQ(result->mesh.points[p], front.points[p]) << "point " << p;
  return *std::move(result);
}

}  // namespace afmesh
