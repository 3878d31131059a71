// Fronts of sliver triangles, as raw CAD tessellations give them (issue 10, part 3): they mesh as
// given, the boundary kept exactly. Small hand-built shapes with the patterns corpus files
// failed on.
#include <cmath>
#include <numbers>
#include <vector>

#include "core/mesh/mesh.h"
#include "core/quality/measures.h"
#include "gtest/gtest.h"
#include "tests/volume/mesh_and_check.h"

namespace afmesh {
namespace {

Index add_point(Mesh& m, double x, double y, double z) {
  m.points.push_back({x, y, z});
  return static_cast<Index>(m.points.size() - 1);
}

// A cylinder of radius 1 and height `height`, `rim` points on each rim, its discs fanned from
// one rim point: next to that point the disc's triangles are caps lying in one plane, their
// short edges on the rim (the fans of coplanar caps of gmsh_lever, where a boss meets a face).
Mesh cylinder_with_fanned_discs(int rim, double height) {
  Mesh m;
  for (const double z : {0.0, height})
    for (int i = 0; i < rim; ++i) {
      const double a = 2 * std::numbers::pi * i / rim;
      add_point(m, std::cos(a), std::sin(a), z);
    }
  const auto bottom = [&](int i) { return static_cast<Index>(i % rim); };
  const auto top = [&](int i) { return static_cast<Index>(rim + i % rim); };
  for (int i = 0; i < rim; ++i) {
    m.triangles.push_back({bottom(i), bottom(i + 1), top(i + 1)});
    m.triangles.push_back({bottom(i), top(i + 1), top(i)});
  }
  for (int i = 1; i + 1 < rim; ++i) {
    m.triangles.push_back({top(0), top(i), top(i + 1)});
    m.triangles.push_back({bottom(0), bottom(i + 1), bottom(i)});
  }
  m.triangle_tags.assign(m.triangles.size(), 0);
  return m;
}

// Regression for issue 10: on a fan of coplanar caps every element is a sliver; each cap failed
// in the early classes for want of a well-shaped one, the faces beside it were meshed over
// meanwhile, and no point was left that closed it ("stuck ... sliver triangles" at the fan's
// point). The caps now go first, each closed with the far corner of a neighbour across an edge.
TEST(Regression, Issue10CylinderWithFannedDiscsMeshes) {
  for (const int rim : {32, 36, 40}) {
    SCOPED_TRACE(testing::Message() << rim << " rim points");
    const Mesh front = cylinder_with_fanned_discs(rim, 3.0);
    mesh_and_check(front, mean_edge_length(front));
  }
}

}  // namespace
}  // namespace afmesh
