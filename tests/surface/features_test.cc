// Tests of ridges, corners, discrete lines and patches (end of paper §3) on hand-built shapes
// with known answers and on CAD parts of the corpus.
#include "core/surface/features.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <set>
#include <string>
#include <tuple>
#include <numbers>
#include <cmath>
#include <utility>

#include "core/quality/measures.h"
#include "core/shapes/shapes.h"
#include "core/quality/validate.h"
#include "core/sizing/size_field.h"
#include "core/surface/generate_surface_mesh.h"
#include "tests/surface/surface_test_shapes.h"

namespace afmesh {
namespace {

using testing::surface_model;
using Model = testing::SurfaceModel;

// What every result must satisfy: patches partition the faces; faces adjacent across an edge
// that is not on a line share a patch; lines run corner to corner over input edges; corners
// list the lines that end at them.
void expect_consistent(const Model& m) {
  const SurfaceFeatures& f = m.features;
  const DiscreteSurface& s = m.surface;
  ASSERT_EQ(f.face_patch.size(), static_cast<std::size_t>(s.face_count()));
  Index faces = 0;
  for (const Patch& p : f.patches) faces += p.face_count;
  EXPECT_EQ(faces, s.face_count());
  for (PatchId p : f.face_patch) {
    ASSERT_GE(index_of(p), 0);
    ASSERT_LT(index_of(p), static_cast<Index>(f.patches.size()));
  }
  std::set<std::pair<Index, Index>> line_edges;
  std::set<Index> corner_vertices;
  for (const Corner& c : f.corners) corner_vertices.insert(c.vertex);
  for (const DiscreteLine& line : f.lines) {
    ASSERT_GE(line.vertices.size(), 2u);
    EXPECT_TRUE(corner_vertices.count(line.vertices.front()));
    EXPECT_TRUE(corner_vertices.count(line.vertices.back()));
    for (std::size_t i = 1; i + 1 < line.vertices.size(); ++i) {
      EXPECT_FALSE(corner_vertices.count(line.vertices[i])) << "corner inside a line";
    }
    for (std::size_t i = 0; i + 1 < line.vertices.size(); ++i) {
      const Index a = line.vertices[i], b = line.vertices[i + 1];
      EXPECT_TRUE(line_edges.insert({std::min(a, b), std::max(a, b)}).second) << "edge twice";
    }
    EXPECT_FALSE(line.patches.empty());
  }
  EXPECT_EQ(static_cast<std::int64_t>(line_edges.size()), f.line_edge_count);
  for (Index t = 0; t < s.face_count(); ++t) {
    for (int k = 0; k < 3; ++k) {
      const Index g = s.neighbours().across[t][k];
      if (g == kInvalidIndex || f.face_patch[t] == f.face_patch[g]) continue;
      const Index a = s.triangles()[t][k], b = s.triangles()[t][(k + 1) % 3];
      EXPECT_TRUE(line_edges.count({std::min(a, b), std::max(a, b)}))
          << "faces " << t << " and " << g << " in different patches across a non-line edge";
    }
  }
  for (Index c = 0; c < static_cast<Index>(f.corners.size()); ++c) {
    for (LineId l : f.corners[c].lines) {
      const DiscreteLine& line = f.lines[index_of(l)];
      EXPECT_TRUE(line.vertices.front() == f.corners[c].vertex ||
                  line.vertices.back() == f.corners[c].vertex);
    }
  }
}

// Four faces in the plane z = 0 round a sliver wound against its three neighbours: b and c are
// 0.05 apart, c just past b on the ray from a, and the sliver (b, a, c) faces -z where its
// neighbours face +z (as at each blade's root of occt-misc's propeller.stl).
Mesh four_faces_round_a_folded_sliver() {
  Mesh m;
  m.points = {{0, 0, 0}, {1, 0, 0}, {1.05, 0.01, 0}, {0.5, 1, 0}, {0.5, -1, 0}};
  const Index a = 0, b = 1, c = 2, x = 3, y = 4;
  m.triangles = {{a, b, x}, {b, c, x}, {b, a, c}, {c, a, y}};
  return m;
}

TEST(FoldedFaces, FindsASliverTurnedAgainstAllThreeNeighbours) {
  const Mesh m = four_faces_round_a_folded_sliver();
  const absl::StatusOr<DiscreteSurface> s = DiscreteSurface::build(m);
  ASSERT_TRUE(s.ok()) << s.status();
  EXPECT_EQ(folded_faces(*s), std::vector<FaceId>{FaceId{2}});
  // Wound the other way it faces +z, but against its neighbours' winding: still folded.
  Mesh wound = m;
  wound.triangles[2] = {0, 1, 2};
  const absl::StatusOr<DiscreteSurface> w = DiscreteSurface::build(wound);
  ASSERT_TRUE(w.ok()) << w.status();
  EXPECT_EQ(folded_faces(*w), std::vector<FaceId>{FaceId{2}});
  // Nothing folds on a closed sphere or on a cube, whose ridges turn by 90 degrees.
  for (const Mesh& clean :
       {testing::uv_sphere({0, 0, 0}, 1.0, 24, 12), box_surface({0, 0, 0}, {1, 1, 1}, 0.25)}) {
    const absl::StatusOr<DiscreteSurface> t = DiscreteSurface::build(clean);
    ASSERT_TRUE(t.ok()) << t.status();
    EXPECT_TRUE(folded_faces(*t).empty());
  }
}

TEST(SurfaceFeatures, CubeHasTwelveLinesEightCornersSixPatches) {
  const Model m = surface_model(box_surface({0, 0, 0}, {1, 1, 1}, 0.25));
  expect_consistent(m);
  EXPECT_EQ(m.features.lines.size(), 12u);
  EXPECT_EQ(m.features.corners.size(), 8u);
  EXPECT_EQ(m.features.patches.size(), 6u);
  EXPECT_EQ(m.features.line_edge_count, 12 * 4);
  for (const DiscreteLine& line : m.features.lines) {
    EXPECT_EQ(line.kinds, kRidgeEdge);
    EXPECT_FALSE(line.closed);
    EXPECT_EQ(line.vertices.size(), 5u);
    EXPECT_EQ(line.patches.size(), 2u);
  }
  for (const Corner& c : m.features.corners) {
    EXPECT_EQ(c.kinds, kJunction);
    EXPECT_EQ(c.lines.size(), 3u);
  }
  for (const Patch& p : m.features.patches) {
    EXPECT_EQ(p.face_count, 32);
    EXPECT_EQ(p.lines.size(), 4u);
  }
}

TEST(SurfaceFeatures, SphereAndTorusHaveNoLinesAndOnePatch) {
  for (const Mesh& mesh : {sphere_surface({0, 0, 0}, 1.0, 0.1), torus_surface(1.0, 0.3, 0.05)}) {
    const Model m = surface_model(mesh);
    expect_consistent(m);
    EXPECT_TRUE(m.features.lines.empty());
    EXPECT_TRUE(m.features.corners.empty());
    ASSERT_EQ(m.features.patches.size(), 1u);
    EXPECT_EQ(m.features.patches[0].face_count, m.surface.face_count());
  }
}

// A round terrain patch: its rim is one closed boundary line, started at its smallest vertex.
TEST(SurfaceFeatures, OpenTerrainHasOneClosedBoundaryLine) {
  const Mesh mesh = testing::terrain_disk(
      0, 0, 100.0, 12, 48, [](double x, double y) { return 3.0 * std::sin(0.05 * x) + 0.01 * y; });
  const Model m = surface_model(mesh);
  expect_consistent(m);
  ASSERT_EQ(m.features.lines.size(), 1u);
  const DiscreteLine& rim = m.features.lines[0];
  EXPECT_TRUE(rim.closed);
  EXPECT_EQ(rim.kinds, kBoundaryEdge);
  EXPECT_EQ(rim.vertices.size(), 49u);
  ASSERT_EQ(m.features.corners.size(), 1u);
  EXPECT_EQ(m.features.corners[0].kinds, kLoopStart);
  EXPECT_EQ(m.features.corners[0].vertex, 1 + 11 * 48);  // the rim's first point
  EXPECT_EQ(m.features.corners[0].lines.size(), 2u);     // the loop, at both ends
  EXPECT_EQ(m.features.patches.size(), 1u);
}

// A rectangular terrain: the rim turns by 90° at the four corners and is split there.
TEST(SurfaceFeatures, RectangularTerrainRimSplitsAtItsFourTurns) {
  const Mesh mesh = testing::terrain_grid(0, 0, 4, 3, 8, [](double x, double) { return 0.1 * x; });
  const Model m = surface_model(mesh);
  expect_consistent(m);
  EXPECT_EQ(m.features.lines.size(), 4u);
  ASSERT_EQ(m.features.corners.size(), 4u);
  for (const Corner& c : m.features.corners) EXPECT_EQ(c.kinds, kTurn);
  EXPECT_EQ(m.features.line_edge_count, 4 * 8);
  // Never split (corner_angle_deg 180): one loop.
  FeatureParams params;
  params.corner_angle_deg = 180.0;
  const Model unsplit = surface_model(mesh, params);
  ASSERT_EQ(unsplit.features.lines.size(), 1u);
  EXPECT_TRUE(unsplit.features.lines[0].closed);
}

TEST(SurfaceFeatures, CylinderHasTwoCircularRidgesAndThreePatches) {
  const Model m = surface_model(testing::closed_cylinder(1.0, 2.0, 32, 6));
  expect_consistent(m);
  ASSERT_EQ(m.features.lines.size(), 2u);
  for (const DiscreteLine& line : m.features.lines) {
    EXPECT_TRUE(line.closed);
    EXPECT_EQ(line.kinds, kRidgeEdge);
    EXPECT_EQ(line.vertices.size(), 33u);
    EXPECT_EQ(line.patches.size(), 2u);
  }
  EXPECT_EQ(m.features.corners.size(), 2u);
  ASSERT_EQ(m.features.patches.size(), 3u);
  std::multiset<Index> sizes;
  for (const Patch& p : m.features.patches) sizes.insert(p.face_count);
  EXPECT_EQ(sizes, (std::multiset<Index>{32, 32, 32 * 6 * 2}));
  // Above the rims' 90°, nothing is a ridge.
  FeatureParams params;
  params.ridge_angle_deg = 95.0;
  EXPECT_EQ(
      surface_model(testing::closed_cylinder(1.0, 2.0, 32, 6), params).features.patches.size(), 1u);
}

TEST(SurfaceFeatures, TaggedHalvesOfASphereMeetOnOneLine) {
  const Model m = surface_model(testing::uv_sphere({0, 0, 0}, 1.0, 40, 19));
  expect_consistent(m);
  ASSERT_EQ(m.features.lines.size(), 1u);
  EXPECT_EQ(m.features.lines[0].kinds, kTagEdge);
  EXPECT_TRUE(m.features.lines[0].closed);
  EXPECT_EQ(m.features.lines[0].vertices.size(), 41u);
  ASSERT_EQ(m.features.patches.size(), 2u);
  EXPECT_EQ(m.features.patches[0].tag + m.features.patches[1].tag, 3);
  EXPECT_EQ(m.features.patches[0].face_count, m.features.patches[1].face_count);
}

// Three sheets on one segment: that segment is a non-manifold line; each sheet's rim is three
// boundary lines (split at its two free corners, where it turns by 90°, and at the junctions).
TEST(SurfaceFeatures, NonManifoldTOfThreePlanes) {
  const Model m = surface_model(testing::three_sheet_t(4));
  expect_consistent(m);
  EXPECT_EQ(m.features.patches.size(), 3u);
  EXPECT_EQ(m.features.lines.size(), 10u);
  int non_manifold = 0;
  for (const DiscreteLine& line : m.features.lines) {
    if (line.kinds & kNonManifoldEdge) {
      ++non_manifold;
      EXPECT_EQ(line.vertices.size(), 5u);
      EXPECT_EQ(line.patches.size(), 3u);
    } else {
      EXPECT_EQ(line.kinds, kBoundaryEdge);
    }
  }
  EXPECT_EQ(non_manifold, 1);
  int junctions = 0, turns = 0;
  for (const Corner& c : m.features.corners) {
    junctions += c.kinds == kJunction;
    turns += c.kinds == kTurn;
  }
  EXPECT_EQ(junctions, 2);
  EXPECT_EQ(turns, 6);
}

TEST(SurfaceFeatures, RefusesAnglesOutOfRange) {
  absl::StatusOr<DiscreteSurface> s = DiscreteSurface::build(box_surface({0, 0, 0}, {1, 1, 1}, 1));
  ASSERT_TRUE(s.ok());
  FeatureParams params;
  params.ridge_angle_deg = 0.0;
  EXPECT_EQ(find_surface_features(*s, params).status().code(), absl::StatusCode::kInvalidArgument);
  params.ridge_angle_deg = 30.0;
  params.corner_angle_deg = 200.0;
  EXPECT_EQ(find_surface_features(*s, params).status().code(), absl::StatusCode::kInvalidArgument);
}

// The features of a corpus file, checked as every result is, with its counts printed for the
// record (lines with the given LineKind bit counted apart).
Model corpus_features(const std::string& name, std::uint8_t kind, int& lines_of_kind) {
  const Model m = surface_model(testing::corpus_mesh(name));
  expect_consistent(m);
  lines_of_kind = 0;
  for (const DiscreteLine& line : m.features.lines) lines_of_kind += (line.kinds & kind) != 0;
  std::printf(
      "%s: %d faces, %lld line edges, %zu lines (%d of kind %d), %zu corners, %zu patches\n",
      name.c_str(), m.surface.face_count(), static_cast<long long>(m.features.line_edge_count),
      m.features.lines.size(), lines_of_kind, kind, m.features.corners.size(),
      m.features.patches.size());
  return m;
}

// CAD parts of the corpus (netgen and gmsh examples): ridges are found and the patches
// partition the faces. The counts are printed for the record.
TEST(SurfaceFeatures, CorpusCadPartsHaveRidgesAndPatchesPartitionTheFaces) {
  for (const std::string name :
       {"netgen_part1.stl", "netgen_hinge.stl", "gmsh_lever.stl", "cgal_pinion.stl"}) {
    SCOPED_TRACE(name);
    int ridges = 0;
    const Model m = corpus_features(name, kRidgeEdge, ridges);
    EXPECT_GT(ridges, 0);
    EXPECT_GT(m.features.patches.size(), 1u);
  }
}

// Open terrains of the corpus (gmsh's terrain demo, openfoam's river bed): their rims are
// boundary lines, and the patches still partition the faces.
TEST(SurfaceFeatures, CorpusTerrainsHaveBoundaryLines) {
  for (const std::string name : {"gmsh_terrain_stl_data.stl", "of_AcrossRiver.stl"}) {
    SCOPED_TRACE(name);
    int rim = 0;
    corpus_features(name, kBoundaryEdge, rim);
    EXPECT_GT(rim, 0);
  }
}

TEST(SurfaceFeatures, ResultDependsOnlyOnTheInput) {
  const Mesh mesh = testing::three_sheet_t(3);
  const Model a = surface_model(mesh), b = surface_model(mesh);
  ASSERT_EQ(a.features.lines.size(), b.features.lines.size());
  for (std::size_t i = 0; i < a.features.lines.size(); ++i) {
    EXPECT_EQ(a.features.lines[i].vertices, b.features.lines[i].vertices);
  }
  EXPECT_EQ(a.features.face_patch, b.features.face_patch);
}

// Short free ridges (FeatureParams::short_ridge_sizes) at a size of the mean edge: a terrain
// scan and a hand scan lose some of their ridges, each chain of them ending freely, and a CAD
// part whose ridges all run corner to corner loses none. The results stay consistent (faces
// either side of a dropped edge share their patch), the patches are those found with every
// ridge but where a small island's ridges went too (the terrain has one: its patches then join
// the one around it), and the counts add up.
TEST(SurfaceFeatures, ShortFreeRidgesGoAndThePatchesStay) {
  for (const std::string name : {"cgal_three_peaks.stl", "cgal_hand.stl", "netgen_part1.stl"}) {
    SCOPED_TRACE(name);
    const Mesh mesh = testing::corpus_mesh(name);
    ASSERT_FALSE(mesh.triangles.empty());
    const Model all = surface_model(mesh);
    const UniformSize size(mean_edge_length(mesh));
    FeatureParams params;
    params.sizes = &size;
    const Model pruned = surface_model(mesh, params);
    expect_consistent(pruned);
    const SurfaceFeatures& f = pruned.features;
    std::printf("%s: %lld of %lld line edges dropped in %lld short free ridges; lines %zu -> "
                "%zu, corners %zu -> %zu, patches %zu\n",
                name.c_str(), static_cast<long long>(f.short_ridge_edges_dropped),
                static_cast<long long>(all.features.line_edge_count),
                static_cast<long long>(f.short_ridges_dropped), all.features.lines.size(),
                f.lines.size(), all.features.corners.size(), f.corners.size(),
                f.patches.size());
    EXPECT_EQ(all.features.short_ridges_dropped, 0);
    EXPECT_EQ(all.features.island_ridges_dropped, 0);
    EXPECT_EQ(f.line_edge_count + f.short_ridge_edges_dropped + f.island_ridge_edges_dropped,
              all.features.line_edge_count);
    if (f.island_ridges_dropped == 0) {
      EXPECT_EQ(f.face_patch, all.features.face_patch);
    } else {
      EXPECT_LT(f.patches.size(), all.features.patches.size());
    }
    EXPECT_EQ(f.island_ridges_dropped > 0, name == "cgal_three_peaks.stl");
    if (name == "netgen_part1.stl") {
      EXPECT_EQ(f.short_ridges_dropped, 0);
    } else {
      EXPECT_GT(f.short_ridges_dropped, 0);
      EXPECT_LT(f.lines.size(), all.features.lines.size());
    }
  }
}

// Ridges round a small island (drop_small_island_ridges): a flat disk of radius 2 (rings of
// 0.25) with one triangle at (1, 0) replaced by a three-sided pyramid whose faces turn by 31°
// from the disk (and under 60° from each other). Every pyramid face is an island of one face,
// and its six ridges are no line at a size of 1: one patch, the rim its only line. At a size of
// 0.1 they stay (longer than two sizes), and so they do for a steep pyramid (faces at 70°: the
// front cannot mesh over that). The surface meshed at 1 is valid, with the pyramid meshed over.
TEST(SurfaceFeatures, RidgesRoundASmallIslandAreNoLine) {
  Mesh disk = testing::terrain_disk(0.0, 0.0, 2.0, 8, 32, [](double, double) { return 0.0; });
  // The triangle whose centroid is nearest (1, 0), split at its raised incentre (the point as
  // far from its three edges, so that the three new faces tilt alike).
  std::size_t nearest = 0;
  double best = 1e9;
  for (std::size_t t = 0; t < disk.triangles.size(); ++t) {
    Point c{-1.0, 0.0, 0.0};
    for (const Index v : disk.triangles[t]) c = add(c, scale(disk.points[v], 1.0 / 3.0));
    if (norm(c) < best) {
      best = norm(c);
      nearest = t;
    }
  }
  const Triangle base = disk.triangles[nearest];
  Point apex{0.0, 0.0, 0.0};
  double perimeter = 0.0;
  for (int k = 0; k < 3; ++k) {
    const double opposite =
        distance(disk.points[base[(k + 1) % 3]], disk.points[base[(k + 2) % 3]]);
    apex = add(apex, scale(disk.points[base[k]], opposite));
    perimeter += opposite;
  }
  apex = scale(apex, 1.0 / perimeter);
  const double inradius = norm(cross(sub(disk.points[base[1]], disk.points[base[0]]),
                                     sub(disk.points[base[2]], disk.points[base[0]]))) /
                          perimeter;
  // The disk with the base triangle split at the apex raised to tilt the new faces by `tilt`.
  const auto with_pyramid = [&](double tilt_deg) {
    Mesh m = disk;
    const auto top = static_cast<Index>(m.points.size());
    m.points.push_back({apex[0], apex[1], inradius * std::tan(tilt_deg * std::numbers::pi / 180.0)});
    m.triangles[nearest] = {base[0], base[1], top};
    m.triangles.push_back({base[1], base[2], top});
    m.triangles.push_back({base[2], base[0], top});
    m.triangle_tags.assign(m.triangles.size(), 0);
    return m;
  };
  const UniformSize one(1.0);
  FeatureParams at_one;
  at_one.sizes = &one;
  EXPECT_EQ(surface_model(with_pyramid(70.0), at_one).features.island_ridges_dropped, 0)
      << "steep";
  disk = with_pyramid(31.0);
  for (const auto& [size, islands, patches] :
       {std::tuple{1.0, 1, std::size_t{1}}, std::tuple{0.1, 0, std::size_t{4}}}) {
    SCOPED_TRACE(size);
    const UniformSize sizes(size);
    FeatureParams params;
    params.sizes = &sizes;
    const Model m = surface_model(disk, params);
    expect_consistent(m);
    EXPECT_EQ(m.features.island_ridges_dropped, islands);
    EXPECT_EQ(m.features.patches.size(), patches);
    if (islands > 0) {
      EXPECT_EQ(m.features.island_ridge_edges_dropped, 6);
      ASSERT_EQ(m.features.lines.size(), 1u);
      EXPECT_TRUE(m.features.lines[0].closed);
    }
  }
  SurfaceParams params;
  params.size = 1.0;
  const absl::StatusOr<SurfaceResult> r = generate_surface_mesh(disk, params);
  ASSERT_TRUE(r.ok()) << r.status().message();
  EXPECT_EQ(r->report.patches, 1);
  const ValidationReport report = validate_surface(r->mesh);
  for (const Check& c : report.checks) {
    if (c.name == check::kClosed || c.name == check::kPositiveEnclosedVolume) continue;
    EXPECT_TRUE(c.passed()) << c.name << ": " << c.summary;
  }
}

}  // namespace
}  // namespace afmesh
