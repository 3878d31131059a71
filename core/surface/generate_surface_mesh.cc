// MeshSurface (paper §3): see generate_surface_mesh.h for the steps.
#include "core/surface/generate_surface_mesh.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <initializer_list>
#include <limits>
#include <memory>
#include <numbers>
#include <optional>
#include <span>
#include <string>

#include "absl/container/flat_hash_map.h"
#include "absl/container/flat_hash_set.h"
#include "absl/strings/str_cat.h"
#include "absl/strings/str_join.h"
#include "absl/strings/str_format.h"
#include "core/geometry/predicates.h"
#include "core/geometry/vec.h"
#include "core/mesh/simplex_incidence.h"
#include "core/quality/measures.h"
#include "core/quality/mesh_topology.h"
#include "core/quality/validate.h"
#include "core/sizing/size_field.h"
#include "core/sizing/spec_size_field.h"
#include "core/spatial/box.h"
#include "core/surface/collapse_edges.h"
#include "core/surface/curvature_sizes.h"
#include "core/surface/discrete_surface.h"
#include "core/surface/features.h"
#include "core/surface/flip_edges.h"
#include "core/surface/patch_from_input.h"
#include "core/surface/gap_sizes.h"
#include "core/surface/wall_sizes.h"
#include "core/surface/sliver_repairs.h"
#include "core/surface/smooth_points.h"
#include "core/surface/split_lines.h"
#include "core/surface/surface_front.h"
#include "core/volume/generate_volume_mesh.h"  // kMinAttachedGrowth
#include "core/volume/repair_front.h"

namespace afmesh {
namespace {

absl::Status check_params(const SurfaceParams& params) {
  if (!params.spec && (!(params.size > 0) || !std::isfinite(params.size)))
    return absl::InvalidArgumentError(absl::StrFormat("size must be > 0, got %g", params.size));
  if (!params.spec && (!(params.growth >= 1.0) || !std::isfinite(params.growth)))
    return absl::InvalidArgumentError(
        absl::StrFormat("growth must be >= 1, got %g", params.growth));
  if (!(params.curvature_angle_deg == 0.0 ||
        (params.curvature_angle_deg > 0.0 && params.curvature_angle_deg < 180.0)))
    return absl::InvalidArgumentError(absl::StrFormat(
        "curvature angle must be in (0, 180) degrees, or 0 for none; got %g",
        params.curvature_angle_deg));
  if (!(params.curvature_deviation >= 0.0 && params.curvature_deviation < 1.0))
    return absl::InvalidArgumentError(absl::StrFormat(
        "curvature deviation must be in [0, 1) of the model size (0: no chord bound); got %g",
        params.curvature_deviation));
  if (!(params.wall_sizes >= 0.0) || !std::isfinite(params.wall_sizes))
    return absl::InvalidArgumentError(absl::StrFormat(
        "wall sizes must be a finite number >= 0 of wall thicknesses (0: none); got %g",
        params.wall_sizes));
  return absl::OkStatus();
}

// Step 1 (not in the paper, which assumes a clean triangulation): drops what carries no
// surface (triangles repeating a point or of zero area, repeats of a triangle, points on no
// triangle) and orients closed components consistently and outward (repair_front). Every
// change is counted in `report`. CANCELLED soon after progress.cancelled() turns true.
// `neighbours`: the edge neighbours of the cleaned triangles when repair_front found them (its
// steps 2-3 ran), else empty.
absl::StatusOr<Mesh> clean_surface_input(const Mesh& input, SurfaceReport& report,
                                          Progress& progress, EdgeNeighbours& neighbours) {
  const Index n = static_cast<Index>(input.points.size());
  report.input_points = n;
  report.input_triangles = static_cast<std::int64_t>(input.triangles.size());
  if (input.triangles.empty()) return absl::InvalidArgumentError("the surface has no triangles");
  if (!input.triangle_tags.empty() && input.triangle_tags.size() != input.triangles.size())
    return absl::InvalidArgumentError(
        absl::StrFormat("triangle_tags has %d entries for %d triangles",
                        input.triangle_tags.size(), input.triangles.size()));
  for (Index p = 0; p < n; ++p)
    for (const double c : input.points[p])
      if (!std::isfinite(c))
        return absl::InvalidArgumentError(
            absl::StrFormat("point %d has a coordinate that is not a finite number", p));
  Mesh out;
  absl::flat_hash_set<Triangle> seen;
  std::vector<Index> new_index(static_cast<std::size_t>(n), kInvalidIndex);
  CancelCheck cancel(progress);
  for (std::size_t t = 0; t < input.triangles.size(); ++t) {
    if (cancel.due()) return absl::CancelledError("surface meshing cancelled");
    const Triangle& v = input.triangles[t];
    for (int k = 0; k < 3; ++k)
      if (v[k] < 0 || v[k] >= n)
        return absl::InvalidArgumentError(absl::StrFormat(
            "triangle %d refers to point %d, out of range [0, %d)", t, v[k], n));
    if (!has_distinct_indices(v) ||
        collinear(input.points[v[0]], input.points[v[1]], input.points[v[2]])) {
      ++report.degenerate_triangles_dropped;
      continue;
    }
    if (!seen.insert(sorted_triangle(v)).second) {
      ++report.duplicate_triangles_dropped;
      continue;
    }
    Triangle w;
    for (int k = 0; k < 3; ++k) {
      if (new_index[v[k]] == kInvalidIndex) {
        new_index[v[k]] = static_cast<Index>(out.points.size());
        out.points.push_back(input.points[v[k]]);
      }
      w[k] = new_index[v[k]];
    }
    out.triangles.push_back(w);
    out.triangle_tags.push_back(input.triangle_tags.empty() ? 0 : input.triangle_tags[t]);
  }
  if (out.triangles.empty())
    return absl::InvalidArgumentError(
        "the surface has no triangle with an area: every triangle repeats a point or has its "
        "corners on a line");
  report.unused_points_dropped = n - static_cast<Index>(out.points.size());
  const FrontRepairReport repair = repair_front(out, &neighbours);
  report.triangles_reoriented = repair.triangles_reoriented;
  return out;
}

// For every line, whether another open line runs between the same two corners and this one has
// more than one segment. Split into one side each, two such lines would give the same chord: a
// patch between them (a lens, or one input face with ridges on all three edges of which two
// meet at a point that is not a corner, as in gmsh_t13_data at curvature angle 0) would be
// bounded by a side and its own reverse, and the front cannot close it. Such a line gets at least
// two sides, its middle point on its own polyline, off the other line's chord. Not in the paper.
std::vector<bool> lines_sharing_their_corners(const SurfaceFeatures& features) {
  absl::flat_hash_map<std::pair<Index, Index>, int> lines_between;
  const auto ends = [](const DiscreteLine& line) {
    const Index a = line.vertices.front(), b = line.vertices.back();
    return std::pair<Index, Index>{std::min(a, b), std::max(a, b)};
  };
  for (const DiscreteLine& line : features.lines)
    if (!line.closed) ++lines_between[ends(line)];
  std::vector<bool> sharing(features.lines.size(), false);
  for (std::size_t l = 0; l < features.lines.size(); ++l) {
    const DiscreteLine& line = features.lines[l];
    sharing[l] = !line.closed && line.vertices.size() > 2 && lines_between[ends(line)] > 1;
  }
  return sharing;
}

// Step 4 (F3): the sides along every line, shared by the patches on both sides; fills
// patch_sides with each patch's initial front, oriented with the patch on the left, and
// side_origins with where each of those sides comes from. The lines are split along
// `split_sizes` (the size field, or less near sides that crossed: lay_initial_fronts).
struct SideOrigin {
  Index line = kInvalidIndex;
  bool on_one_segment = false;  // no vertex of the line's polyline lies between its ends
};

absl::Status sides_along_lines(SurfaceMeshState& s, const SizeField& split_sizes,
                               std::vector<std::vector<Side>>& patch_sides,
                               std::vector<std::vector<SideOrigin>>& side_origins) {
  const DiscreteSurface& surface = s.surface;
  const SurfaceFeatures& features = s.features;
  const std::vector<LineEndSizes> ends = line_end_sizes(surface, features);
  const std::vector<bool> sharing = lines_sharing_their_corners(features);
  absl::flat_hash_map<Index, Index> corner_point;  // input vertex -> output point
  auto corner = [&](Index vertex) {
    auto [it, fresh] = corner_point.try_emplace(vertex, kInvalidIndex);
    if (fresh) {
      const Point& x = surface.local_points()[vertex];
      it->second = s.add_point(x, s.field_size(x), FaceId{surface.faces_at(vertex)[0]}, vertex);
    }
    return it->second;
  };
  std::vector<Index> forward, backward;
  std::vector<Point> polyline;
  for (std::size_t l = 0; l < features.lines.size(); ++l) {
    const DiscreteLine& line = features.lines[l];
    polyline.clear();
    for (const Index v : line.vertices) polyline.push_back(surface.local_points()[v]);
    SplitLineParams split_params;
    split_params.field_origin = surface.origin();
    split_params.start_size = ends[l].start;
    split_params.end_size = ends[l].end;
    split_params.growth = s.growth;
    if (line.closed) split_params.min_sides = 3;
    if (sharing[l]) split_params.min_sides = 2;
    absl::StatusOr<LineSplit> split = split_line(polyline, split_sizes, split_params);
    if (!split.ok()) return split.status();
    std::vector<Index> ids(split->points.size());
    const std::size_t last = ids.size() - 1;
    ids[0] = corner(line.vertices.front());
    ids[last] = line.closed ? ids[0] : corner(line.vertices.back());
    for (std::size_t i = 1; i < last; ++i) {
      const Index seg = split->segment[i];
      const Index a = line.vertices[seg], b = line.vertices[seg + 1];
      ids[i] = s.add_point(split->points[i], s.field_size(split->points[i]),
                           surface.face_at_edge(a, b), a);
    }
    s.points_along_lines.push_back({ids, split->segment});
    // Attached sizes (eq. 15's delta_A): a line point carries the length of its sides.
    for (std::size_t i = 0; i < last; ++i) {
      s.line_sides.insert({std::min(ids[i], ids[i + 1]), std::max(ids[i], ids[i + 1])});
      const double length = norm(sub(s.points[ids[i + 1]], s.points[ids[i]]));
      for (const Index p : {ids[i], ids[i + 1]})
        s.point_size[p] = std::min(s.point_size[p], length);
    }
    // Each patch along the line gets its sides with the patch on their left: forward where a
    // face of the patch traverses the line's first segment the line's way.
    surface.faces_at_edge(line.vertices[0], line.vertices[1], forward, backward);
    for (const PatchId patch : line.patches) {
      const auto in = [&](const std::vector<Index>& faces) {
        return std::any_of(faces.begin(), faces.end(),
                           [&](Index f) { return features.face_patch[f] == patch; });
      };
      std::vector<Side>& out = patch_sides[index_of(patch)];
      std::vector<SideOrigin>& origins = side_origins[index_of(patch)];
      const auto origin = [&](std::size_t i) {
        return SideOrigin{static_cast<Index>(l), split->segment[i + 1] == split->segment[i]};
      };
      if (in(forward))
        for (std::size_t i = 0; i < last; ++i)
          out.push_back({ids[i], ids[i + 1]}), origins.push_back(origin(i));
      if (in(backward))
        for (std::size_t i = 0; i < last; ++i)
          out.push_back({ids[i + 1], ids[i]}), origins.push_back(origin(i));
    }
  }
  return absl::OkStatus();
}

// Step 4 (F3) until no patch's initial front crosses itself (crossing_sides in
// surface_front.h; not in the paper): where a side of a line crosses another side of its patch,
// the lines are split again with the size there halved (a point source at the side's middle,
// delta0 half its length, growing back at the growth c_i of eq. 15: sides_near_crossings),
// at most kMaxSideDoublings times. Shorter chords follow their polylines closer (the chords of a
// ledge narrower than their sagitta, gmsh_lever). The halving is local: doubling the whole
// line's sides instead put 640 sides of 0.03 along gmsh_lever's 25-long rim of its side face
// (size 1.76 there) to follow a tongue of it 1.4 degrees wide at one end, and the patch beside
// filled with triangles of that size (28,530 triangles in all became 36,716 once the seam's
// sliver steps were gone). A side that lies on one segment of its polyline already follows it:
// where two such sides cross, the input's lines themselves touch (TR12J_OCC), no split parts
// them, and no size is halved for it (there, 6 doublings took a line of 84 sides to 5,376 and
// its patch ran away). A front that still crosses is left to the patch front, which stops where
// it cannot close. Every line is split along the halved sizes, so a line beside one that
// crossed at a shared corner grades down with it (cgal_hand's fin, two ridges 10 degrees apart,
// once put sides of 0.011 beside sides of 0.0012 at one corner, and the front stopped there).
constexpr int kMaxSideDoublings = 6;

// The size field of lay_initial_fronts' halvings: `sources` (a point source at the middle of
// each side that crossed) over `box` (the surface's, global frame), its extent elsewhere.
absl::StatusOr<std::unique_ptr<SpecSizeField>> sides_near_crossings(
    const std::vector<SizeSource>& sources, const Box& box) {
  double extent = 0.0;
  for (int a = 0; a < 3; ++a) extent = std::max(extent, box.hi[a] - box.lo[a]);
  SizeSpec spec;
  spec.max_size = std::max(extent, 1.0);
  spec.sources = sources;
  absl::StatusOr<SpecSizeField> field = SpecSizeField::create(spec, box);
  if (!field.ok()) return field.status();
  return std::make_unique<SpecSizeField>(*std::move(field));
}

absl::Status lay_initial_fronts(std::optional<SurfaceMeshState>& state,
                                const DiscreteSurface& surface, const SurfaceFeatures& features,
                                const SizeField& sizes, double growth,
                                std::vector<std::vector<Side>>& patch_sides) {
  std::vector<SizeSource> halved;  // where sides crossed, in the global frame
  Box box = empty_box();           // the surface's, global frame, when a side first crosses
  std::unique_ptr<SpecSizeField> near_crossings;
  std::optional<SmallerOfSizes> split_sizes;
  for (int round = 0;; ++round) {
    state.emplace(surface, features, sizes, growth);
    patch_sides.assign(features.patches.size(), {});
    std::vector<std::vector<SideOrigin>> side_origins(features.patches.size());
    if (absl::Status st = sides_along_lines(*state, split_sizes ? *split_sizes : sizes,
                                            patch_sides, side_origins);
        !st.ok())
      return st;
    if (round == kMaxSideDoublings) return absl::OkStatus();
    const std::size_t before = halved.size();
    for (std::size_t p = 0; p < features.patches.size(); ++p) {
      const PatchId patch{static_cast<Index>(p)};
      const auto pairs = crossing_sides(*state, patch, patch_sides[p]);
      std::vector<std::size_t> crossed;
      for (const auto& [i, j] : pairs) crossed.insert(crossed.end(), {i, j});
      std::sort(crossed.begin(), crossed.end());
      crossed.erase(std::unique(crossed.begin(), crossed.end()), crossed.end());
      for (const std::size_t i : crossed) {
        if (side_origins[p][i].on_one_segment) continue;
        const Side& side = patch_sides[p][i];
        const Point& a = state->points[side[0]];
        const Point& b = state->points[side[1]];
        const double length = distance(a, b);
        if (!(length > 0.0)) continue;
        const double delta0 = 0.5 * length;
        halved.push_back({.points = {surface.to_global(lerp(a, b, 0.5))},
                          .delta0 = delta0,
                          .r0 = 0.0,
                          .r1 = delta0 / std::max(growth - 1.0, 1e-3),
                          .law = PowerLaw{.gamma = 1.0}});
      }
    }
    if (halved.size() == before) return absl::OkStatus();
    split_sizes.reset();
    if (is_empty(box))
      for (const Point& x : surface.local_points()) enclose(box, surface.to_global(x));
    absl::StatusOr<std::unique_ptr<SpecSizeField>> field = sides_near_crossings(halved, box);
    if (!field.ok()) return field.status();
    near_crossings = *std::move(field);
    split_sizes.emplace(sizes, *near_crossings);
  }
}

// The boxes of the patches (their input faces), padded by 1% of their extent.
std::vector<Box> patch_boxes(const DiscreteSurface& surface, const SurfaceFeatures& features) {
  std::vector<Box> boxes(features.patches.size(), empty_box());
  for (Index f = 0; f < surface.face_count(); ++f)
    for (const Index q : surface.triangles()[f])
      enclose(boxes[index_of(features.face_patch[f])], surface.local_points()[q]);
  for (Box& box : boxes) {
    double extent = 0;
    for (int a = 0; a < 3; ++a) extent = std::max(extent, box.hi[a] - box.lo[a]);
    for (int a = 0; a < 3; ++a) box.lo[a] -= 0.01 * extent, box.hi[a] += 0.01 * extent;
  }
  return boxes;
}

// Not in the paper: the triangles each patch should get, its input faces' areas over the area
// of an equilateral triangle of the size wanted at their centroids (a bound for the front: a
// patch meshed far finer than asked stops, kMaxTrianglesOverExpected), plus
// kTrianglesPerInitialSide for each side the patch starts with: sides far shorter than the size
// (lines split finer where they run close, crossing_sides; gap sizes) grade out over several
// rings of triangles each. Sizes growing from a side of length l at the rate c_i - 1 per unit
// distance (eq. 15 over a distance) to the size h take about (1 - l / h) / (0.433 (c_i - 1))
// triangles per side, at most 11.5 at the least growth, 1.2 (kMinAttachedGrowth): 24 is twice
// that. (gmsh_lever at twice its mean edge: 4 per side stopped it, 8 closed it once; since the
// gap sizes it stopped at 8 with 395 sides left in a patch of 14,904 triangles, and closes at 24
// with 52,692 triangles in all.)
constexpr double kMaxTrianglesOverExpected = 10.0;
constexpr double kTrianglesPerInitialSide = 24.0;
// The front's own bound is tighter: on the corpus and OCCT's STL files at their mean edges no
// patch whose front closed made more than 1.29 times its expected triangles plus
// kTrianglesPerInitialSide per side and 1000 (2,134 patches), while fronts that run away over a
// crease no line follows build 8 times them before they stop (TR12J_OCC's patch 2: 320k built
// where 39.5k were expected, 1.6-1.9 of its 7.5-8.1 s). The patch re-triangulated from its
// input keeps kMaxTrianglesOverExpected: it starts from the input's triangles, which a fine input
// has many more of than its size asks.
constexpr double kMaxFrontTrianglesOverExpected = 3.0;
// And a front whose triangles cover more than this many times its patch's input area has run
// over its own triangles (PatchFrontParams::max_area; not in the paper): its triangles' corners
// lie on the input, so a cover of the patch has about the patch's area. cgal_hand's main patch
// crossed a ridge that ends inside it at ~11,700 triangles, its whole area, and then went on
// over its own triangles until the triangle bound stopped it at 57,585, 4.3 times its area.
constexpr double kMaxFrontAreaOverPatch = 1.25;
// What a patch should get: its input faces' area, and its triangles: their areas over the area
// of an equilateral triangle of the size wanted at their centroids.
struct PatchEstimate {
  double area = 0.0;
  double triangles = 0.0;
};
// Not in the paper: the back-offs allowed in a patch (PatchFrontParams::max_back_offs), a few
// plus one per this many of the triangles it should get.
constexpr std::int64_t kMinBackOffs = 50;
constexpr double kExpectedTrianglesPerBackOff = 100.0;
// The vertices of `triangles` round which they form two fans or more (analyze_triangle_topology,
// whose cost is in the highest index: over a copy numbered from 0), with their own indices.
std::vector<VertexFans> fanned_vertices(const std::vector<Triangle>& triangles) {
  absl::flat_hash_map<Index, Index> local;
  std::vector<Index> global;
  std::vector<Triangle> renumbered;
  renumbered.reserve(triangles.size());
  for (const Triangle& t : triangles) {
    Triangle r;
    for (int k = 0; k < 3; ++k) {
      const auto [it, added] = local.try_emplace(t[k], static_cast<Index>(global.size()));
      if (added) global.push_back(t[k]);
      r[k] = it->second;
    }
    renumbered.push_back(r);
  }
  std::vector<VertexFans> fans = analyze_triangle_topology(renumbered).nonmanifold_vertices;
  for (VertexFans& v : fans) v.vertex = global[v.vertex];
  return fans;
}

// Not in the paper: the triangles a patch's front made (from `first_triangle` on) form no more
// fans round each of its line points than the patch's input faces do round the same place (one
// on an input edge; at an input vertex, as many as the patch's faces there). A front that
// closed a corner's wedge on the wrong side of its lines leaves a fan of its own there, over
// another patch's place: TR12J_OCC, where a dangling ridge of patch 196 ends at a corner of the
// three-face patch 384, and the wedge between 384's two lines, seen from 196 across a sharp
// crease, was closed by one triangle of 196; the job failed later, when the patches were
// checked together (check_patches_meet_on_lines). FAILED_PRECONDITION now, so that the patch is
// re-triangulated from its input (patch_from_input.h) before the next one is meshed. O(T log T)
// for the patch's T triangles.
absl::Status check_patch_fans(const SurfaceMeshState& s, PatchId patch,
                              std::size_t first_triangle) {
  // mesh_patch compacted the patch before it returned: every triangle from first_triangle on
  // is live.
  const std::vector<Triangle> mine(
      s.triangles.begin() + static_cast<std::ptrdiff_t>(first_triangle), s.triangles.end());
  for (const VertexFans& v : fanned_vertices(mine)) {
    if (v.vertex >= s.line_points) continue;
    // A line point inside an input edge has the patch's faces on one side, or on both of a
    // line inside the patch: one fan. At an input vertex (its anchor, the same point), the
    // patch's faces there may form several.
    int input = 1;
    if (const Index anchor = s.anchor[v.vertex];
        anchor != kInvalidIndex && s.points[v.vertex] == s.surface.local_points()[anchor]) {
      std::vector<Triangle> faces;
      for (const Index f : s.surface.faces_at(anchor))
        if (s.features.face_patch[f] == patch) faces.push_back(s.surface.triangles()[f]);
      for (const VertexFans& u : fanned_vertices(faces))
        if (u.vertex == anchor) input = u.fan_count;
    }
    if (v.fan_count <= input) continue;
    const Point x = s.surface.to_global(s.points[v.vertex]);
    return absl::FailedPreconditionError(absl::StrFormat(
        "the surface front of patch %d (input tag %d) left %d fans of triangles round line point "
        "%d near (%g, %g, %g), where the patch's input faces form %d: a triangle closed a corner "
        "on the far side of its lines",
        index_of(patch), s.features.patches[index_of(patch)].tag, v.fan_count, v.vertex, x[0],
        x[1], x[2], input));
  }
  return absl::OkStatus();
}

// The patches together: an edge off the discrete lines is used by two triangles, once each way
// (not in the paper; each patch is checked closed by mesh_patch, but two patches could still
// cover the same place, where their lines leave a gap between corners), and the triangles
// round each point form one fan wherever the input's do (two patches that cover the same place
// round a line point meet it in two fans: cgal_dino with 0.001 of its diagonal asked as the
// deviation came out with such a point and 8 crossing pairs of triangles, returned as a
// success). Where the input itself has several fans (a non-manifold vertex, or a vertex of a
// non-manifold edge), so may the output at the points of its lines there. A fault is a
// FAILED_PRECONDITION naming where, never a folded or open surface. O(M log M) for M triangles.
absl::Status check_patches_meet_on_lines(const SurfaceMeshState& s) {
  const TriangleTopology topology = analyze_triangle_topology(s.triangles);
  if (!topology.nonmanifold_vertices.empty()) {
    const TriangleTopology input = analyze_triangle_topology(s.surface.triangles());
    absl::flat_hash_set<Index> several_fans;  // input vertices where the input has several
    for (const VertexFans& v : input.nonmanifold_vertices) several_fans.insert(v.vertex);
    for (const EdgeGroup& g : input.nonmanifold_edges) several_fans.insert({g.a, g.b});
    for (const VertexFans& v : topology.nonmanifold_vertices) {
      const Index anchor = s.anchor[v.vertex];
      if (anchor != kInvalidIndex && several_fans.contains(anchor)) continue;
      const Point x = s.surface.to_global(s.points[v.vertex]);
      std::vector<Index> patch_ids;
      for (const Index t : v.triangles) patch_ids.push_back(s.triangle_patch[t]);
      std::sort(patch_ids.begin(), patch_ids.end());
      patch_ids.erase(std::unique(patch_ids.begin(), patch_ids.end()), patch_ids.end());
      const std::string patches = absl::StrJoin(patch_ids, ", ");
      return absl::FailedPreconditionError(absl::StrFormat(
          "the surface fronts of the patches overlap: the triangles round point %d near (%g, %g, "
          "%g), of patches %s, form %d fans where the input's form one",
          v.vertex, x[0], x[1], x[2], patches, v.fan_count));
    }
  }
  for (const auto* groups :
       {&topology.open_edges, &topology.nonmanifold_edges, &topology.misoriented_edges}) {
    for (const EdgeGroup& g : *groups) {
      if (s.line_sides.contains({std::min(g.a, g.b), std::max(g.a, g.b)})) continue;
      const Point x = s.surface.to_global(s.points[g.a]);
      std::string patches;
      for (const Index t : g.triangles)
        absl::StrAppend(&patches, patches.empty() ? "" : ", ", s.triangle_patch[t]);
      return absl::FailedPreconditionError(absl::StrFormat(
          "the surface fronts of the patches did not meet: edge (%d, %d) near (%g, %g, %g), off "
          "the discrete lines, is used by %d triangles of patches %s",
          g.a, g.b, x[0], x[1], x[2], g.triangles.size(), patches));
    }
  }
  return absl::OkStatus();
}

// Each patch's input area, and the triangles it should get (PatchEstimate above).
std::vector<PatchEstimate> patch_estimates(const SurfaceMeshState& s) {
  std::vector<PatchEstimate> estimates(s.features.patches.size());
  const std::vector<Point>& p = s.surface.local_points();
  for (Index f = 0; f < s.surface.face_count(); ++f) {
    const Triangle& t = s.surface.triangles()[f];
    const double h = s.field_size(s.surface.centroid(FaceId{f}));
    const double area = triangle_area(p[t[0]], p[t[1]], p[t[2]]);
    PatchEstimate& e = estimates[index_of(s.features.face_patch[f])];
    e.area += area;
    e.triangles += area / (0.25 * std::sqrt(3.0) * h * h);
  }
  return estimates;
}

// Step 6: the largest distance from samples of `from` (vertices, edge midpoints, centroids) to
// `to`, or `floor` when that is larger. Both in the same frame. CANCELLED soon after
// progress.cancelled() turns true.
// An edge's midpoint is sampled once, from the triangle of the smaller id where the edge has a
// neighbour (`from_neighbours`, edge adjacency of from.triangles): once a sample has been
// looked at, the maximum is at least its distance, so a second look could not raise it.
// With `hosts` (a face of `to` near each point of `from`; they are moved nearer), a sample's
// distance to the host of a corner it lies between is an upper bound of its distance to `to`:
// at or below the largest distance so far (or the floor) it cannot raise the maximum, and the
// sample needs nothing more. Above, the sample is located by the surface's walk from the
// nearest of those hosts (S2), a few steps where the tree's query costs several times that, and
// the walk's face gives a nearer bound; only a sample still above is asked of the tree (a walk
// that did not settle has asked the tree already). The maximum is the tree's (or the scan's,
// the same), exactly (not in the paper).
// `to` may come without its tree: a few samples ask (11 on the 1M sphere), and the scans
// of all faces that answer them without it cost less than the tree until kScansBeforeTree; then
// the tree is built, so a surface that needs many answers costs at most that many scans more.
constexpr int kScansBeforeTree = 16;

absl::StatusOr<double> sampled_distance(const Mesh& from, const EdgeNeighbours& from_neighbours,
                                        DiscreteSurface& to, std::vector<FaceId>* hosts,
                                        double floor, double* vertex_max, Progress& progress) {
  CancelCheck cancel(progress, 1024);  // each sample a nearest-face query at most
  int scans = 0;
  // Counts a nearest_face answer; the tree once the scans have cost about as much.
  auto answered = [&] {
    if (!to.has_tree() && ++scans >= kScansBeforeTree) to.build_tree(&cancel);
  };
  // The squared distance of x from `to`, or a bound of it at or below `worst2`; x lies between
  // the points `corners` of `from`. A vertex sample (one corner, x itself) that had to be
  // located leaves its face as its host: a nearer start for the samples round it.
  auto at = [&](const Point& x, std::initializer_list<Index> corners, double worst2) {
    if (hosts != nullptr) {
      FaceId nearest = kNoFace;
      double bound = std::numeric_limits<double>::infinity();
      for (const Index q : corners) {
        const FaceId host = (*hosts)[q];
        if (host == kNoFace || host == nearest) continue;
        const double d = to.squared_distance_to_face(x, host);
        if (d <= worst2) return d;
        if (d < bound) bound = d, nearest = host;
      }
      if (nearest != kNoFace) {
        const Located walked = to.locate(x, nearest);
        if (walked.used_tree) answered();
        if (corners.size() == 1) (*hosts)[*corners.begin()] = walked.face;
        if (walked.used_tree || walked.squared_distance <= worst2) return walked.squared_distance;
      }
    }
    const Located found = to.nearest_face(x);
    answered();
    if (hosts != nullptr && corners.size() == 1) (*hosts)[*corners.begin()] = found.face;
    return found.squared_distance;
  };
  double worst2 = floor * floor;
  for (Index v = 0; v < static_cast<Index>(from.points.size()); ++v) {
    if (cancel.due()) return absl::CancelledError("surface distance: cancelled");
    worst2 = std::max(worst2, at(from.points[v], {v}, worst2));
  }
  if (vertex_max != nullptr) *vertex_max = std::sqrt(worst2);
  for (Index f = 0; f < static_cast<Index>(from.triangles.size()); ++f) {
    if (cancel.due()) return absl::CancelledError("surface distance: cancelled");
    const Triangle& t = from.triangles[f];
    const Point& a = from.points[t[0]];
    const Point& b = from.points[t[1]];
    const Point& c = from.points[t[2]];
    worst2 = std::max(worst2, at(scale(add(a, add(b, c)), 1.0 / 3.0), {t[0], t[1], t[2]}, worst2));
    const auto first_look = [&](int k) {
      const Index g = from_neighbours.across[f][k];
      return g == kInvalidIndex || f < g;
    };
    if (first_look(0)) worst2 = std::max(worst2, at(scale(add(a, b), 0.5), {t[0], t[1]}, worst2));
    if (first_look(1)) worst2 = std::max(worst2, at(scale(add(b, c), 0.5), {t[1], t[2]}, worst2));
    if (first_look(2)) worst2 = std::max(worst2, at(scale(add(c, a), 0.5), {t[2], t[0]}, worst2));
  }
  return std::max(floor, std::sqrt(worst2));
}

// A face of `output` near each point of `input` (N values, kNoFace where none is reachable), for
// Not in the paper: the two-sided sampled distance (sampled_distance) between the output `local`
// (in the frame of `surface`, the input as repaired) and `given`, the input before the sliver
// repairs (repair_sliver_steps, collapse_folded_slivers) moved it by up to the step heights and
// edges they report: the distance the user asked about is to the input sent (gmsh_lever at diag
// / 40: 0.145 from the repaired input, 0.39 from the one sent). Run only when a repair changed
// something; without hosts, the trees answer.
absl::StatusOr<double> distance_to_input_as_given(const Mesh& local, DiscreteSurface& output,
                                                  const DiscreteSurface& surface,
                                                  const Mesh& given, Progress& progress) {
  absl::StatusOr<DiscreteSurface> reference = DiscreteSurface::build(given, {}, progress);
  if (!reference.ok()) return reference.status();
  Mesh output_in_reference_frame;
  output_in_reference_frame.points.reserve(local.points.size());
  for (const Point& x : local.points)
    output_in_reference_frame.points.push_back(reference->to_local(surface.to_global(x)));
  output_in_reference_frame.triangles = local.triangles;
  const absl::StatusOr<double> out_to_in =
      sampled_distance(output_in_reference_frame, output.neighbours(), *reference, nullptr, 0.0,
                       nullptr, progress);
  if (!out_to_in.ok()) return out_to_in.status();
  Mesh given_in_output_frame;
  given_in_output_frame.points.reserve(reference->local_points().size());
  for (const Point& p : reference->local_points())
    given_in_output_frame.points.push_back(
        output.to_local(surface.to_local(reference->to_global(p))));
  given_in_output_frame.triangles = reference->triangles();
  return sampled_distance(given_in_output_frame, reference->neighbours(), output, nullptr,
                          *out_to_in, nullptr, progress);
}

// sampled_distance's walk from input to output: each output point p lies on its host input face
// host[p] (S2), so the corners of that face get a face of `output` at p; the other input points
// take the hint of the nearest hinted point by input edges (a breadth-first search from all the
// hinted points at once). O(N + M) for M input faces; a hint only starts a walk, so its quality
// costs time, never accuracy (not in the paper).
std::vector<FaceId> output_faces_near_input_points(const DiscreteSurface& input,
                                                   const DiscreteSurface& output,
                                                   const std::vector<FaceId>& host) {
  std::vector<FaceId> hint(static_cast<std::size_t>(input.point_count()), kNoFace);
  std::vector<Index> queue;
  for (Index p = 0; p < output.point_count(); ++p) {
    if (output.faces_at(p).empty()) continue;
    for (const Index v : input.triangle(host[p])) {
      if (hint[v] != kNoFace) continue;
      hint[v] = FaceId{output.faces_at(p)[0]};
      queue.push_back(v);
    }
  }
  for (std::size_t next = 0; next < queue.size(); ++next) {
    const Index v = queue[next];
    for (const Index f : input.faces_at(v))
      for (const Index w : input.triangles()[f]) {
        if (hint[w] != kNoFace) continue;
        hint[w] = hint[v];
        queue.push_back(w);
      }
  }
  return hint;
}

// The report's components: joined across edges of two triangles, closed when none of their
// triangles has an edge without exactly one other triangle across it (open or non-manifold).
// CANCELLED soon after progress.cancelled() turns true (no face is joined any more then).
absl::Status count_components(const DiscreteSurface& surface, SurfaceReport& report,
                              Progress& progress) {
  const EdgeNeighbours& neighbours = surface.neighbours();
  std::vector<Index> label;
  CancelCheck cancel(progress);
  const Index count =
      label_components(neighbours, [&](Index, int) { return !cancel.due(); }, label);
  if (cancel.stopped()) return absl::CancelledError("surface meshing cancelled");
  std::vector<bool> open(static_cast<std::size_t>(count), false);
  for (std::size_t t = 0; t < label.size(); ++t)
    for (int k = 0; k < 3; ++k)
      if (neighbours.across[t][k] == kInvalidIndex) open[label[t]] = true;
  report.components = count;
  report.closed_components = std::count(open.begin(), open.end(), false);
  return absl::OkStatus();
}

}  // namespace

absl::StatusOr<SurfaceCrossings> surface_crossings(const Mesh& mesh,
                                                   std::span<const std::int32_t> components,
                                                   Progress& progress) {
  ValidationParams params;
  params.max_findings_per_check = 1;
  params.face_environments = components;
  const absl::StatusOr<Check> check = check_surface_self_intersections(mesh, params, progress);
  if (!check.ok()) return check.status();
  if (check->outcome == CheckOutcome::kNotRun)
    return absl::InternalError(absl::StrCat("the crossing check could not run: ", check->summary));
  SurfaceCrossings crossings;
  if (check->outcome != CheckOutcome::kFailed || check->findings.empty() ||
      check->findings[0].triangles.empty())
    return crossings;
  const Triangle& t = mesh.triangles[check->findings[0].triangles[0]];
  crossings.pairs = check->finding_count;
  crossings.first =
      scale(add(mesh.points[t[0]], add(mesh.points[t[1]], mesh.points[t[2]])), 1.0 / 3.0);
  return crossings;
}

absl::Status check_result_does_not_cross_itself(const Mesh& result,
                                                std::span<const std::int32_t> components,
                                                Progress& progress) {
  const absl::StatusOr<SurfaceCrossings> crossings =
      surface_crossings(result, components, progress);
  if (!crossings.ok()) return crossings.status();
  if (crossings->pairs == 0) return absl::OkStatus();
  const Point& c = crossings->first;
  return absl::FailedPreconditionError(absl::StrFormat(
      "the re-triangulated surface crosses itself: %d pairs of its triangles within one "
      "component cross, the first near (%g, %g, %g); it is not returned. Where a wall is "
      "thinner than the size, the triangles of its two sides can cross: a bound on the "
      "triangles across a wall's thickness (--wall-sizes 1 or more), the curvature bound "
      "(--curvature-angle) or a smaller size keeps them apart",
      crossings->pairs, c[0], c[1], c[2]));
}

std::int64_t thin_triangles_at_thinner_input(const Mesh& output, std::span<const FaceId> hosts,
                                             std::span<const Index> triangle_patch,
                                             const DiscreteSurface& input, double thin_deg) {
  // An input face kept as it is has the same angle up to the rounding of its points' moves
  // between frames.
  constexpr double kSameAngleDeg = 1e-6;
  std::optional<SimplexIncidence<3>> incidence;  // made at the first thin triangle that needs it
  std::vector<Index> fan;
  std::int64_t count = 0;
  for (Index self = 0; self < static_cast<Index>(output.triangles.size()); ++self) {
    const Triangle& t = output.triangles[self];
    const double angle =
        triangle_min_angle_deg(output.points[t[0]], output.points[t[1]], output.points[t[2]]);
    if (!(angle < thin_deg)) continue;
    const Point centroid = scale(
        add(output.points[t[0]], add(output.points[t[1]], output.points[t[2]])), 1.0 / 3.0);
    const FaceId hint = static_cast<std::size_t>(t[0]) < hosts.size() ? hosts[t[0]] : kNoFace;
    const Located at = input.locate(centroid, hint);
    if (at.face != kNoFace) {
      const Triangle& f = input.triangle(at.face);
      const std::vector<Point>& p = input.local_points();
      if (triangle_min_angle_deg(p[f[0]], p[f[1]], p[f[2]]) <= angle + kSameAngleDeg) {
        ++count;
        continue;
      }
    }
    if (triangle_patch.size() != output.triangles.size()) continue;
    // The smallest angle is at the corner facing the shortest edge.
    int corner = 0;
    double shortest = std::numeric_limits<double>::infinity();
    for (int k = 0; k < 3; ++k) {
      const double l =
          squared_norm(sub(output.points[t[(k + 2) % 3]], output.points[t[(k + 1) % 3]]));
      if (l < shortest) {
        shortest = l;
        corner = k;
      }
    }
    if (!incidence) incidence.emplace(SimplexIncidence<3>::of(output.triangles));
    fan.clear();
    incidence->elements_of(output.triangles, t[corner], fan);
    if (std::none_of(fan.begin(), fan.end(), [&](Index u) {
          return u != self && triangle_patch[u] == triangle_patch[self];
        }))
      ++count;
  }
  return count;
}

namespace {

// What explain_stuck and mesh_surface say of an input that crosses itself.
std::string input_crossings_text(const SurfaceCrossings& crossings) {
  const Point& c = crossings.first;
  return absl::StrFormat(
      "The input surface intersects itself: %d pairs of its triangles cross, the first near "
      "(%g, %g, %g); repair the crossings (or re-export the surface) and send it again",
      crossings.pairs, c[0], c[1], c[2]);
}

}  // namespace

absl::Status explain_stuck(absl::Status stuck, const Mesh& clean, Progress& progress,
                           const DiscreteSurface* surface) {
  if (stuck.code() != absl::StatusCode::kFailedPrecondition) return stuck;
  const absl::StatusOr<SurfaceCrossings> crossings = surface_crossings(clean, {}, progress);
  if (!crossings.ok()) return crossings.status();
  if (crossings->pairs == 0) {
    const std::vector<FaceId> folded = surface ? folded_faces(*surface) : std::vector<FaceId>{};
    if (folded.empty()) return stuck;
    const Point c = surface->to_global(surface->centroid(folded[0]));
    return absl::FailedPreconditionError(absl::StrFormat(
        "%s. The input surface folds back on itself: %d of its triangles turn by more than %g "
        "degrees against each of their three neighbours (slivers wound against them), the first "
        "near (%g, %g, %g); remove them (or re-export the surface) and send it again",
        stuck.message(), folded.size(), kFoldedFaceTurnDeg, c[0], c[1], c[2]));
  }
  return absl::FailedPreconditionError(
      absl::StrCat(stuck.message(), ". ", input_crossings_text(*crossings)));
}

namespace {

// A size wanted below this share of the size asked is named in a failure message.
constexpr double kSmallWantedSize = 0.25;

// curvature_point_sizes bounds one chord of the size by its epsilon; the triangles made are
// longer and wider than that chord: the front's sides run up to ~1.3 times the size (1.69 times
// the sagitta), and a triangle's centroid lies 4/3 as deep as an edge's midpoint, so the user's
// deviation is divided by 1.69 x 4/3 ~ 2.25 first (not in the paper). Measured on 14 corpus files
// at 0.001 and 0.0005 of the diagonal, the two-sided distance came out within 0.94 and 1.03 of
// the deviation asked (without it, up to 2.8 times).
constexpr double kDeviationMargin = 2.25;

// Not in the paper: the more rounds of flips, collapses and smoothing after a patch was
// re-triangulated from its input (patch_from_input.h), in which the collapses work on every
// triangle under kInputPatchBadAngleDeg (not only on those under 15°, as after the front): the
// splits of the input's triangles leave rows of points closer than the size where long thin
// triangles were split across (a coarse torus whose every input vertex lies on a ridge: 32.6%
// of 30° or more after the rounds with 15°, 99.6% with 25°, 100% with 30°, 99.96% with 35°;
// cgal_hand at its mean edge: 90.9% after one round, 94.9% after three with 15°, 99.2% with 30°).
constexpr int kCleanUpRoundsAfterInputPatches = 2;
constexpr double kInputPatchBadAngleDeg = 30.0;

// Not in the paper: what the input looks like where a patch's front stopped, so that the message
// names a cause the user can act on, as the volume front's does: the input's triangles near
// there (their edges and smallest angle), the sharpest turn between two adjacent faces of one
// patch there (above the ridge angle: a crease on a ridge too short to be a line, or one that
// ends inside the patch, which the front must mesh across), and the size the front wanted
// against the size asked (the curvature bound and the gaps between lines lower it). A scan of
// the input, once, when the job has already failed.
absl::Status describe_where_stopped(absl::Status stopped, const SurfaceMeshState& s,
                                    const SizeField& asked, double ridge_angle_deg) {
  if (stopped.code() != absl::StatusCode::kFailedPrecondition || !s.stopped_at) return stopped;
  const DiscreteSurface& surface = s.surface;
  const std::vector<Point>& p = surface.local_points();
  const Point& x = s.stopped_at->x;
  const double reach = s.stopped_at->reach;
  const TrianglesNear near = triangles_near(p, surface.triangles(), x, reach);
  if (near.count == 0) return stopped;
  double sharpest = 0.0;  // degrees
  for (Index f = 0; f < surface.face_count(); ++f) {
    if (!comes_near(p, surface.triangles()[f], x, reach)) continue;
    for (int k = 0; k < 3; ++k) {
      const Index g = surface.neighbours().across[f][k];
      if (g == kInvalidIndex || s.features.face_patch[f] != s.features.face_patch[g]) continue;
      const Point& n_f = surface.normal(FaceId{f});
      const Point& n_g = surface.normal(FaceId{g});
      if (!(squared_norm(n_f) > 0.0) || !(squared_norm(n_g) > 0.0)) continue;
      const double c = (surface.neighbours().same_way[f][k] ? -1.0 : 1.0) * dot(n_f, n_g);
      sharpest = std::max(sharpest, std::acos(std::clamp(c, -1.0, 1.0)) * 180.0 / std::numbers::pi);
    }
  }
  std::string text = absl::StrFormat(
      "%s; the input's %d triangles within %g of there have edges %g to %g long and angles down "
      "to %.3g degrees, and adjacent faces of the patch there turn by up to %.3g degrees",
      stopped.message(), near.count, reach, near.shortest_edge, near.longest_edge,
      near.smallest_angle_deg, sharpest);
  if (sharpest > ridge_angle_deg)
    absl::StrAppend(&text, absl::StrFormat(
                               " (over the ridge angle, %g: a crease on a ridge too short to be "
                               "kept as a line, or on one that ends inside the patch, which the "
                               "front meshes across)",
                               ridge_angle_deg));
  const double wanted = s.field_size(x);
  const double size = asked.size_at(surface.to_global(x));
  if (wanted < kSmallWantedSize * size)
    absl::StrAppend(&text, absl::StrFormat(
                               "; the size wanted there, %g, is %.3g times below the size asked, "
                               "%g: the curvature bound (--curvature-angle) or a gap between lines "
                               "lowers it",
                               wanted, size / wanted, size));
  return absl::FailedPreconditionError(text);
}

// generate_surface_mesh, its clean-ups' flips tested against the rest of the surface or not
// (FlipParams::keep_uncrossed); `crossed_itself` set when the result crossed itself.
absl::StatusOr<SurfaceResult> mesh_surface(const Mesh& input, const SurfaceParams& params,
                                           Progress& progress, bool flips_keep_uncrossed,
                                           bool& crossed_itself) {
  SurfaceResult result;
  StageClock clock(result.timings);
  if (absl::Status st = check_params(params); !st.ok()) return st;
  EdgeNeighbours clean_neighbours;
  absl::StatusOr<Mesh> clean =
      clean_surface_input(input, result.report, progress, clean_neighbours);
  if (!clean.ok()) return clean.status();
  absl::StatusOr<std::unique_ptr<SizeField>> field =
      make_size_field(params.spec, params.size, clean->points);
  if (!field.ok()) return field.status();
  // With a bound on the distance from the input asked, a step higher than the share of it left
  // to the chords (kDeviationMargin) stays: removed, it would move the surface by its height
  // (gmsh_lever at diag / 40 and 0.001 of the diagonal: its steps 0.33 and 0.62 high went, and the
  // result lay 0.18% of the diagonal from the input as given).
  double step_bound = std::numeric_limits<double>::infinity();
  if (params.curvature_deviation > 0) {
    Box box = empty_box();
    for (const Point& x : clean->points) enclose(box, x);
    step_bound = params.curvature_deviation * norm(sub(box.hi, box.lo)) / kDeviationMargin;
  }
  // The input before the sliver repairs (here and below) change it: the distance reported is to
  // it (distance_to_input_as_given). Copied by the first repair made, if any.
  std::optional<Mesh> as_given;
  const StepRepairs steps =
      repair_sliver_steps(*clean, **field, params.ridge_angle_deg, step_bound, &as_given);
  if (steps.count > 0) clean_neighbours = {};  // other triangles now
  result.report.sliver_steps_removed = steps.count;
  result.report.highest_sliver_step = steps.highest;
  clock.lap("input");
  if (progress.cancelled()) return absl::CancelledError("surface meshing cancelled");
  // S2, S3
  absl::StatusOr<DiscreteSurface> surface =
      DiscreteSurface::build(*clean, {}, progress, std::move(clean_neighbours));
  if (!surface.ok()) return surface.status();
  if (const std::vector<FaceId> folded = folded_faces(*surface); !folded.empty()) {
    const FoldedCollapses collapsed = collapse_folded_slivers(*clean, folded, &as_given);
    result.report.folded_slivers_collapsed = collapsed.count;
    result.report.longest_folded_edge_collapsed = collapsed.longest_edge;
    if (collapsed.count > 0) {
      surface = DiscreteSurface::build(*clean, {}, progress);
      if (!surface.ok()) return surface.status();
    }
  }
  if (absl::Status st = count_components(*surface, result.report, progress); !st.ok()) return st;
  clock.lap("surface");
  if (progress.cancelled()) return absl::CancelledError("surface meshing cancelled");
  FeatureParams feature_params;
  feature_params.ridge_angle_deg = params.ridge_angle_deg;
  feature_params.corner_angle_deg = params.corner_angle_deg;
  feature_params.sizes = field->get();
  absl::StatusOr<SurfaceFeatures> features =
      find_surface_features(*surface, feature_params, progress);
  if (!features.ok()) return features.status();
  result.report.model_size = surface->size();
  result.report.patches = static_cast<std::int64_t>(features->patches.size());
  result.report.lines = static_cast<std::int64_t>(features->lines.size());
  result.report.corners = static_cast<std::int64_t>(features->corners.size());
  result.report.short_ridges_dropped = features->short_ridges_dropped;
  clock.lap("features");

  const double growth = std::max(params.spec ? params.spec->growth : params.growth,
                                 kMinAttachedGrowth);
  // Sizes attached to the input's points (§4.2, §4.4): bounded where the input curves (eq.
  // 20–22) and across the gaps between lines narrower than the size (gap_sizes.h), graded.
  const SizeField* sizes = field->get();
  std::unique_ptr<CurvatureLimitedSize> limited;
  std::vector<double> point_sizes(surface->local_points().size(),
                                  std::numeric_limits<double>::infinity());
  // With the deviation bound, the sizes it gives the input's edges hold over their faces
  // (CurvatureLimitedSize's face caps).
  std::vector<double> face_caps;
  if (params.curvature_angle_deg > 0 || params.curvature_deviation > 0) {
    absl::StatusOr<std::vector<double>> curved = curvature_point_sizes(
        *surface, *features, params.curvature_angle_deg,
        params.curvature_deviation * surface->size() / kDeviationMargin, **field, progress,
        params.curvature_deviation > 0 ? &face_caps : nullptr);
    if (!curved.ok()) return curved.status();
    point_sizes = *std::move(curved);
  }
  const std::vector<double> gaps = line_gap_sizes(*surface, *features, **field);
  // Not in the paper: the thickness of the walls, for a surface that is to be a volume's front.
  std::vector<double> walls;
  if (params.wall_sizes > 0.0) {
    absl::StatusOr<std::vector<double>> w =
        wall_thickness_sizes(*surface, params.wall_sizes, **field, progress);
    if (!w.ok()) return w.status();
    walls = *std::move(w);
  }
  bool attached = false;
  std::vector<bool> at_gap(point_sizes.size(), false);
  for (std::size_t v = 0; v < point_sizes.size(); ++v) {
    point_sizes[v] = std::min(point_sizes[v], gaps[v]);
    if (!walls.empty()) point_sizes[v] = std::min(point_sizes[v], walls[v]);
    at_gap[v] = std::isfinite(gaps[v]);
    attached = attached || std::isfinite(point_sizes[v]);
  }
  if (attached) {
    if (absl::Status st = grade_point_sizes(*surface, growth, point_sizes, progress); !st.ok())
      return st;
    limited = std::make_unique<CurvatureLimitedSize>(**field, *surface, std::move(point_sizes),
                                                     std::move(at_gap), std::move(face_caps));
    sizes = limited.get();
  }
  clock.lap("curvature");
  if (progress.cancelled()) return absl::CancelledError("surface meshing cancelled");
  std::optional<SurfaceMeshState> state;
  std::vector<std::vector<Side>> patch_sides;
  if (absl::Status st = lay_initial_fronts(state, *surface, *features, *sizes, growth, patch_sides);
      !st.ok())
    return st;
  SurfaceMeshState& s = *state;
  s.line_points = static_cast<Index>(s.points.size());
  clock.lap("lines");
  if (progress.cancelled()) return absl::CancelledError("surface meshing cancelled");

  const std::vector<Box> boxes = patch_boxes(*surface, *features);
  const std::vector<PatchEstimate> estimates = patch_estimates(s);
  // The sizes attached to the geometry (curvature, gaps) can ask for far more triangles than
  // the server's estimate from the size field alone: refused here, before the front runs, as
  // the server refuses its own estimate.
  double expected_total = 0.0;
  for (const PatchEstimate& e : estimates) expected_total += e.triangles;
  if (expected_total > static_cast<double>(params.max_triangles))
    return absl::ResourceExhaustedError(absl::StrFormat(
        "the sizes attached to the surface (its curvature and the gaps between its lines, with "
        "the size field) ask for about %.3g triangles, over the limit of %d",
        expected_total, params.max_triangles));
  if (params.admit_expected)
    if (absl::Status admitted = params.admit_expected(expected_total); !admitted.ok())
      return admitted;
  for (std::size_t p = 0; p < features->patches.size(); ++p) {
    const PatchId patch{static_cast<Index>(p)};
    const double per_sides =
        kTrianglesPerInitialSide * static_cast<double>(patch_sides[p].size()) + 1000.0;
    const PatchEstimate& expected = estimates[p];
    const auto max_from_input =
        static_cast<std::int64_t>(kMaxTrianglesOverExpected * expected.triangles + per_sides);
    PatchFrontParams front_params;
    front_params.max_triangles =
        static_cast<std::int64_t>(kMaxFrontTrianglesOverExpected * expected.triangles + per_sides);
    front_params.max_back_offs =
        kMinBackOffs + static_cast<std::int64_t>(expected.triangles / kExpectedTrianglesPerBackOff);
    front_params.max_area = kMaxFrontAreaOverPatch * expected.area;
    const std::size_t triangles_before = s.triangles.size();
    const Index points_before = static_cast<Index>(s.points.size());
    absl::Status st = params.every_patch_from_input
                          ? absl::OkStatus()
                          : mesh_patch(s, patch, patch_sides[p], boxes[p], front_params, progress);
    if (st.ok() && !params.every_patch_from_input)
      st = check_patch_fans(s, patch, triangles_before);
    if (!st.ok()) {
      st = describe_where_stopped(std::move(st), s, **field, params.ridge_angle_deg);
      if (st.code() != absl::StatusCode::kFailedPrecondition) return st;
      // The front's triangles and points go: the patch is as before it.
      s.take_back_patch(points_before, triangles_before);
      s.stopped_at.reset();
      result.report.front_stops.emplace_back(st.message());
    }
    // Not in the paper: the patch's own input triangles, split to the size, in lieu of a front
    // that stopped (patch_from_input.h); the report says which and why.
    if (!st.ok() || params.every_patch_from_input) {
      if (absl::Status fallback =
              patch_from_input(s, patch, patch_sides[p], max_from_input, progress);
          !fallback.ok()) {
        if (fallback.code() != absl::StatusCode::kFailedPrecondition) return fallback;
        return explain_stuck(absl::FailedPreconditionError(absl::StrCat(
                                 st.ok() ? "" : st.message(), st.ok() ? "" : "; ",
                                 fallback.message())),
                             *clean, progress, &*surface);
      }
      ++result.report.patches_from_input;
    }
    if (static_cast<std::int64_t>(s.triangles.size()) > params.max_triangles)
      return absl::ResourceExhaustedError(absl::StrFormat(
          "the surface has %d triangles after %d of its %d patches, over the limit of %d",
          s.triangles.size(), p + 1, features->patches.size(), params.max_triangles));
  }
  if (absl::Status st = check_patches_meet_on_lines(s); !st.ok())
    return explain_stuck(std::move(st), *clean, progress, &*surface);
  clock.lap("front");
  // The clean-ups: flips, collapses, flips again, smoothing; each stage timed when `lap`.
  const FlipParams flip_params{.keep_uncrossed = flips_keep_uncrossed};
  const auto clean_up = [&](bool lap, const CollapseParams& collapse = {}) -> absl::Status {
    if (absl::StatusOr<std::int64_t> flips = flip_edges(s.points, s.triangles, s.triangle_patch,
                                                         s.line_sides, flip_params, progress);
        !flips.ok())
      return flips.status();
    if (lap) clock.lap("flips");
    // Needles and caps that no flip mends lose their shortest edge (collapse_edges.h); the flips
    // then run again over what changed.
    if (absl::StatusOr<std::int64_t> collapses = collapse_edges(s, collapse, progress);
        !collapses.ok()) {
      return collapses.status();
    } else if (*collapses > 0) {
      if (absl::StatusOr<std::int64_t> flips = flip_edges(s.points, s.triangles, s.triangle_patch,
                                                           s.line_sides, flip_params, progress);
          !flips.ok())
        return flips.status();
    }
    if (lap) clock.lap("collapses");
    // The points inside the patches relax towards their neighbours' mean, on the input (flips
    // again after it change the angles by less than 0.1% of triangles on the corpus).
    if (absl::StatusOr<std::int64_t> moves = smooth_points(s, {}, progress); !moves.ok())
      return moves.status();
    if (lap) clock.lap("smoothing");
    return absl::OkStatus();
  };
  if (absl::Status st = clean_up(true); !st.ok()) return st;
  // A patch re-triangulated from its input starts from the input's triangles split in two
  // again and again: the clean-ups run kCleanUpRoundsAfterInputPatches more times then, their
  // collapses on triangles under kInputPatchBadAngleDeg (as CGAL's isotropic_remeshing repeats
  // its own and collapses short edges; not in the paper).
  if (result.report.patches_from_input > 0) {
    for (int round = 0; round < kCleanUpRoundsAfterInputPatches; ++round)
      if (absl::Status st = clean_up(false, {.bad_angle_deg = kInputPatchBadAngleDeg}); !st.ok())
        return st;
    clock.lap("more clean-ups");
  }

  Mesh local;
  local.points = s.points;
  local.triangles = std::move(s.triangles);
  local.triangle_tags = std::move(s.triangle_tags);
  // The output's tree is built only if the distance needs it (sampled_distance).
  DiscreteSurfaceParams output_params;
  output_params.tree = false;
  absl::StatusOr<DiscreteSurface> output = DiscreteSurface::build(local, output_params, progress);
  if (!output.ok()) return output.status();
  if (progress.cancelled()) return absl::CancelledError("surface meshing cancelled");
  std::vector<FaceId> output_hosts = s.host;
  result.report.thin_triangles_at_thinner_input =
      thin_triangles_at_thinner_input(local, s.host, s.triangle_patch, *surface);
  const absl::StatusOr<double> out_to_in =
      sampled_distance(local, output->neighbours(), *surface, &output_hosts, 0.0,
                       &result.report.max_vertex_distance, progress);
  if (!out_to_in.ok()) return out_to_in.status();
  if (as_given) {
    // A sliver repair moved the input: the distance reported is to the input as sent.
    const absl::StatusOr<double> given =
        distance_to_input_as_given(local, *output, *surface, *as_given, progress);
    if (!given.ok()) return given.status();
    result.report.hausdorff = *given;
  } else {
    // The input in the output's frame: `output` keeps its points relative to its own origin, the
    // centre of the output's bounding box, which is not the input's (1e-4 off on the bunny), and
    // sampled_distance needs both surfaces in one frame.
    Mesh input_in_output_frame;
    input_in_output_frame.points.reserve(surface->local_points().size());
    for (const Point& p : surface->local_points())
      input_in_output_frame.points.push_back(output->to_local(p));
    input_in_output_frame.triangles = surface->triangles();
    std::vector<FaceId> input_hints = output_faces_near_input_points(*surface, *output, s.host);
    // Only the larger of the two directions is reported: input samples no farther than the
    // output's largest distance need no exact distance of their own.
    const absl::StatusOr<double> hausdorff =
        sampled_distance(input_in_output_frame, surface->neighbours(), *output, &input_hints,
                         *out_to_in, nullptr, progress);
    if (!hausdorff.ok()) return hausdorff.status();
    result.report.hausdorff = *hausdorff;
  }
  clock.lap("distance");
  // Not in the paper: an assembly's components that cross each other are each re-triangulated
  // on its own (issue 11), and the result crosses where they do; the report says so.
  if (result.report.components > 1) {
    const absl::StatusOr<SurfaceCrossings> crossings = surface_crossings(*clean, {}, progress);
    if (!crossings.ok()) return crossings.status();
    result.report.input_crossing_pairs = crossings->pairs;
    result.report.first_input_crossing = crossings->first;
    clock.lap("crossings");
  }

  result.mesh = std::move(local);
  for (Point& x : result.mesh.points) x = surface->to_global(x);
  // Not in the paper: the result as returned (global frame) must not cross itself within a
  // component (check_result_does_not_cross_itself).
  if (absl::Status st = check_result_does_not_cross_itself(
          result.mesh, component_environments(output->neighbours()), progress);
      !st.ok()) {
    if (st.code() != absl::StatusCode::kFailedPrecondition) return st;
    // Not in the paper: where the input crosses itself within a component, its result does
    // too; no bound on the walls nor tested flips (generate_surface_mesh's runs again) mends
    // that (OCCT's motor.stl: 8,472 pairs; its two more runs took 26 s, and the refusal gave
    // the thin-wall advice before the input's crossings).
    const absl::StatusOr<SurfaceCrossings> input_crossings =
        surface_crossings(*clean, component_environments(surface->neighbours()), progress);
    if (!input_crossings.ok()) return input_crossings.status();
    if (input_crossings->pairs > 0)
      return absl::FailedPreconditionError(absl::StrCat(
          "the re-triangulated surface crosses itself where its input does, within one "
          "component; it is not returned. ",
          input_crossings_text(*input_crossings)));
    crossed_itself = true;
    // The input's folds, if any.
    return explain_stuck(std::move(st), *clean, progress, &*surface);
  }
  clock.lap("self-check");
  return result;
}

}  // namespace

absl::StatusOr<SurfaceResult> generate_surface_mesh(const Mesh& input, const SurfaceParams& params,
                                                    Progress& progress) {
  // Not in the paper: the clean-ups' flips are first made without testing each against the rest
  // of the surface, whose bins cost about as much as the flips (a third of the time on OCCT's
  // propeller, 486k triangles, whose rounds of clean-ups rebuild them). A flip can still make the
  // surface cross itself across a wall thinner than its quadrilateral's bend (flip_edges.h);
  // where the result does, the job runs again with every flip tested.
  bool crossed_itself = false;
  absl::StatusOr<SurfaceResult> result =
      mesh_surface(input, params, progress, /*flips_keep_uncrossed=*/false, crossed_itself);
  if (result.ok() || !crossed_itself) return result;
  result = mesh_surface(input, params, progress, /*flips_keep_uncrossed=*/true, crossed_itself);
  // A bound as tight as kVolumeFrontWallSizes or tighter was asked already (0: none asked).
  const bool walls_bounded = params.wall_sizes > 0 && params.wall_sizes <= kVolumeFrontWallSizes;
  if (result.ok() || !crossed_itself || walls_bounded) return result;
  // Not in the paper: still crossing, the two sides of a wall thinner than the size cross each
  // other (their chords pass through the wall); the job runs once more with its triangles no
  // longer than the walls' thickness, as a volume's front is (kVolumeFrontWallSizes), which is
  // smaller than the size asked only there, and says so (SurfaceReport), where it refused
  // before. gmsh_t13_data, a curved plate 2 thick, at 1.4 times its mean edge (13.7) with no
  // curvature bound: 6 pairs of triangles crossed; made again, valid.
  SurfaceParams walled = params;
  walled.wall_sizes = kVolumeFrontWallSizes;
  absl::StatusOr<SurfaceResult> again =
      mesh_surface(input, walled, progress, /*flips_keep_uncrossed=*/true, crossed_itself);
  if (!again.ok()) return result;  // the first refusal says what happened at the size asked
  again->report.wall_sizes_after_crossing = walled.wall_sizes;
  return again;
}

}  // namespace afmesh
