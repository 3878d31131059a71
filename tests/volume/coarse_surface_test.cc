// A target size well below the input surface's edge lengths (paper §1, F5/F9 with eq. 15): the
// front must shrink its elements from the coarse boundary down to the size wanted inside and
// still close, also along the solid's edges, where two boundary faces meet at 90°.
#include <array>
#include <cstdint>
#include <map>
#include <string>
#include <tuple>
#include <utility>

#include "core/geometry/vec.h"
#include "core/io/mesh_io.h"
#include "core/quality/validate.h"
#include "core/shapes/shapes.h"
#include "core/volume/end_game_watch.h"
#include "core/volume/generate_volume_mesh.h"
#include "gtest/gtest.h"

namespace afmesh {
namespace {

void expect_valid_volume_mesh(const Mesh& surface, double size) {
  VolumeParams params;
  params.size = size;
  absl::StatusOr<VolumeResult> result = generate_volume_mesh(surface, params, no_progress());
  ASSERT_TRUE(result.ok()) << "size " << size << ": " << result.status();
  const ValidationReport report = validate_volume_mesh(result->mesh, &surface);
  EXPECT_TRUE(report.valid()) << "size " << size << ": " << report.to_string();
}

// A plate [0, w]² × [0, t], its top cut into `top` × `top` squares and its bottom into
// `bottom` × `bottom`, each square split along alternating diagonals; each side is a strip of
// triangles between the top's and the bottom's divisions of its edge. Outward-oriented.
Mesh plate_surface(double w, double t, int top, int bottom) {
  Mesh m;
  std::map<std::array<double, 3>, Index> ids;
  const auto id = [&](double x, double y, double z) {
    const auto [it, added] = ids.emplace(std::array<double, 3>{x, y, z}, m.points.size());
    if (added) m.points.push_back({x, y, z});
    return it->second;
  };
  // Adds triangle (a, b, c) turned so that its normal points along `out`.
  const auto add = [&](Index a, Index b, Index c, const Point& out) {
    const Point n = cross(sub(m.points[b], m.points[a]), sub(m.points[c], m.points[a]));
    m.triangles.push_back(dot(n, out) > 0 ? Triangle{a, b, c} : Triangle{a, c, b});
  };
  const auto at = [&](int n, int i) { return w * i / n; };
  for (const auto& [n, z, up] : {std::tuple{top, t, 1.0}, std::tuple{bottom, 0.0, -1.0}})
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < n; ++j) {
        const Index p00 = id(at(n, i), at(n, j), z), p10 = id(at(n, i + 1), at(n, j), z),
                    p11 = id(at(n, i + 1), at(n, j + 1), z), p01 = id(at(n, i), at(n, j + 1), z);
        const Point out{0, 0, up};
        if ((i + j) % 2 == 0) {
          add(p00, p10, p11, out);
          add(p00, p11, p01, out);
        } else {
          add(p00, p10, p01, out);
          add(p10, p11, p01, out);
        }
      }
  // The four sides: along s in [0, w] at fixed x or y, the top's divisions against the bottom's.
  for (const auto& [axis, fixed] : {std::pair{0, 0.0}, std::pair{0, w}, std::pair{1, 0.0},
                                    std::pair{1, w}}) {
    const auto side_point = [&](double along, double z) {
      return axis == 0 ? id(fixed, along, z) : id(along, fixed, z);
    };
    Point out{0, 0, 0};
    out[axis] = fixed > 0 ? 1.0 : -1.0;
    int i = 0, j = 0;
    while (i < top || j < bottom) {
      if (j < bottom && (i == top || at(bottom, j + 1) <= at(top, i + 1))) {
        add(side_point(at(bottom, j), 0), side_point(at(bottom, j + 1), 0), side_point(at(top, i), t),
            out);
        ++j;
      } else {
        add(side_point(at(bottom, j), 0), side_point(at(top, i + 1), t), side_point(at(top, i), t),
            out);
        ++i;
      }
    }
  }
  m.triangle_tags.assign(m.triangles.size(), 0);
  return m;
}

// The shipped cube (unstructured triangles with edges 0.12–0.20) at about 0.4 × its edges.
TEST(CoarseSurface, CubeExampleMeshesAtSizeWellBelowItsEdges) {
  absl::StatusOr<Mesh> cube = read_mesh(std::string(AFMESH_SOURCE_DIR) + "/examples/cube/cube.msh");
  ASSERT_TRUE(cube.ok()) << cube.status();
  cube->tets.clear();
  cube->tet_tags.clear();
  expect_valid_volume_mesh(*cube, 0.07);
}

// A structured box surface with edges 0.25 (right triangles) at 0.4 × its edges.
TEST(CoarseSurface, BoxMeshesAtSizeWellBelowItsEdges) {
  expect_valid_volume_mesh(box_surface({0, 0, 0}, {1, 1, 1}, 0.25), 0.1);
}

// Regression for issue 10 (a valid closed front closes at growth 1): a plate 2 thick whose
// triangles are 5.5 long, at size 1.145, as in the thin walls of gmsh_t13_data's surface. The
// coarse faces, deferred when their first rules found no point (the best point too near the
// opposite wall), waited while the finer front filled the gap under them with ever smaller
// elements: over its budget after 46k tets for 11k asked. Retried at once under the later rules,
// they take the point across the wall while it is still there.
TEST(Regression, Issue10ThinWallCoarserThanTheSizeMeshes) {
  expect_valid_volume_mesh(plate_surface(30, 2, 5, 18), 1.145);
}

// Regression for issue 10: the shipped cube at 0.02, 7.5 × under its edges, meshed all but 2e-4
// of its volume after 1M steps and then built ever smaller elements in the last gaps along its
// faces without end (no answer after 400 s; since the end game's watch, EndGameWatch, "the front
// stopped closing"). With the coarse faces retrying their later rules at once, it closes.
TEST(Regression, Issue10CubeFarBelowItsEdgesCloses) {
  absl::StatusOr<Mesh> cube = read_mesh(std::string(AFMESH_SOURCE_DIR) + "/examples/cube/cube.msh");
  ASSERT_TRUE(cube.ok()) << cube.status();
  cube->tets.clear();
  cube->tet_tags.clear();
  VolumeParams params;
  params.size = 0.02;
  params.optimise = false;
  absl::StatusOr<VolumeResult> result = generate_volume_mesh(*cube, params, no_progress());
  ASSERT_TRUE(result.ok()) << result.status();
  const ValidationReport report = validate_volume_mesh(result->mesh, &*cube);
  EXPECT_TRUE(report.valid()) << report.to_string();
}

// Issue 10 part 2 (never hang): the end game's watch. Before the elements hold all but
// EndGameWatch::kShare of the volume it never fires; after, a front that does not beat its
// smallest size for kSteps + kStepsPerFace × that size has stalled, and every new record starts
// the count again.
TEST(EndGameWatch, FiresOnlyWhenTheLastFacesStopShrinking) {
  using volume::EndGameWatch;
  EndGameWatch watch;
  const double all = 1.0, nearly = 1.0 - 0.5 * EndGameWatch::kShare;
  for (std::int64_t step = 0; step < 10 * EndGameWatch::kSteps; ++step)
    ASSERT_FALSE(watch.stalled(0.5, all, 100, step)) << step;  // not in the end game yet
  const std::int64_t start = 10 * EndGameWatch::kSteps;
  const std::int64_t patience = EndGameWatch::kSteps + EndGameWatch::kStepsPerFace * 100;
  EXPECT_FALSE(watch.stalled(nearly, all, 100, start));  // the first record
  EXPECT_EQ(watch.smallest_front(), 100);
  EXPECT_FALSE(watch.stalled(nearly, all, 150, start + patience));  // larger: not a record
  EXPECT_TRUE(watch.stalled(nearly, all, 150, start + patience + 1));
  EXPECT_FALSE(watch.stalled(nearly, all, 99, start + patience + 2));  // a record: count again
  EXPECT_EQ(watch.smallest_front(), 99);
  const std::int64_t record = start + patience + 2;
  const std::int64_t patience_now = EndGameWatch::kSteps + EndGameWatch::kStepsPerFace * 99;
  EXPECT_FALSE(watch.stalled(nearly, all, 120, record + patience_now));
  EXPECT_TRUE(watch.stalled(nearly, all, 120, record + patience_now + 1));
}

}  // namespace
}  // namespace afmesh
