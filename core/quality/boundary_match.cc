// boundary_match: the tets' boundary faces against a given boundary mesh, as oriented triples
// counted with multiplicity.
#include "core/quality/boundary_match.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <tuple>
#include <utility>

#include "absl/container/flat_hash_map.h"
#include "absl/strings/str_format.h"
#include "core/quality/validate_common.h"

namespace afmesh {
namespace {

// Coordinates with -0.0 turned into 0.0, so that equal coordinates hash equally.
Point normalized(const Point& p) { return {p[0] + 0.0, p[1] + 0.0, p[2] + 0.0}; }

// True when the boundary's points are, exactly and in order, the first points of `volume`.
bool shares_leading_points(const Mesh& volume, const Mesh& boundary) {
  if (boundary.points.size() > volume.points.size()) return false;
  return std::equal(boundary.points.begin(), boundary.points.end(), volume.points.begin());
}

// Volume point index of each boundary point (kInvalidIndex when none has its coordinates).
std::vector<Index> match_points_by_coordinates(const Mesh& volume, const Mesh& boundary) {
  absl::flat_hash_map<Point, Index> index_of;
  index_of.reserve(volume.points.size());
  for (Index p = 0; p < static_cast<Index>(volume.points.size()); ++p) {
    index_of.try_emplace(normalized(volume.points[p]), p);
  }
  std::vector<Index> map(boundary.points.size(), kInvalidIndex);
  for (std::size_t p = 0; p < boundary.points.size(); ++p) {
    const auto it = index_of.find(normalized(boundary.points[p]));
    if (it != index_of.end()) map[p] = it->second;
  }
  return map;
}

// An oriented face in canonical rotation with its origin (a tet, or a boundary triangle).
struct OrientedFace {
  Triangle face;
  Index owner;
};

bool by_face(const OrientedFace& x, const OrientedFace& y) {
  return std::tie(x.face, x.owner) < std::tie(y.face, y.owner);
}

bool by_key(const OrientedFace& x, const OrientedFace& y) {
  return std::make_pair(sorted_triangle(x.face), x.owner) <
         std::make_pair(sorted_triangle(y.face), y.owner);
}

// Removes the faces that appear (as oriented faces, with multiplicity) in both sorted lists,
// leaving in each the faces the other lacks, ordered by unoriented key.
void remove_common_faces(std::vector<OrientedFace>& a, std::vector<OrientedFace>& b) {
  std::vector<OrientedFace> only_a, only_b;
  std::size_t i = 0, j = 0;
  while (i < a.size() || j < b.size()) {
    if (j == b.size() || (i < a.size() && a[i].face < b[j].face)) {
      only_a.push_back(a[i++]);
    } else if (i == a.size() || b[j].face < a[i].face) {
      only_b.push_back(b[j++]);
    } else {
      ++i;
      ++j;
    }
  }
  std::sort(only_a.begin(), only_a.end(), by_key);
  std::sort(only_b.begin(), only_b.end(), by_key);
  a = std::move(only_a);
  b = std::move(only_b);
}

// The boundary mesh's triangles in volume point indices and canonical rotation; a triangle
// using a boundary point with no volume counterpart is reported and left out.
std::vector<OrientedFace> mapped_boundary_triangles(const Mesh& boundary,
                                                    const std::vector<Index>& point_map,
                                                    CheckBuilder& builder) {
  std::vector<OrientedFace> mapped;
  for (Index t = 0; t < static_cast<Index>(boundary.triangles.size()); ++t) {
    Triangle face;
    Index unmatched = kInvalidIndex;
    for (int k = 0; k < 3; ++k) {
      face[k] = point_map[boundary.triangles[t][k]];
      if (face[k] == kInvalidIndex) unmatched = boundary.triangles[t][k];
    }
    if (unmatched == kInvalidIndex) {
      mapped.push_back({canonical_rotation(face), t});
      continue;
    }
    builder.add([&] {
      const Point& x = boundary.points[unmatched];
      return Finding{absl::StrFormat("boundary triangle %d has no matching face: its boundary "
                                     "point %d (%.17g, %.17g, %.17g) is not a point of the "
                                     "volume mesh",
                                     t, unmatched, x[0], x[1], x[2]),
                     {}, {t}, {}};
    });
  }
  std::sort(mapped.begin(), mapped.end(), by_face);
  return mapped;
}

// Reports the faces left after remove_common_faces, in key order: a key on both sides is a
// face with flipped orientation; otherwise a boundary triangle is missing from the tets'
// boundary, or a tet face is extra.
void report_face_differences(const std::vector<OrientedFace>& extra,
                             const std::vector<OrientedFace>& missing, CheckBuilder& builder) {
  std::size_t i = 0, j = 0;
  while (i < extra.size() || j < missing.size()) {
    const bool take_extra = j == missing.size() ||
                            (i < extra.size() && by_key(extra[i], missing[j]));
    const bool same_key = i < extra.size() && j < missing.size() &&
                          sorted_triangle(extra[i].face) == sorted_triangle(missing[j].face);
    if (same_key) {
      const OrientedFace& e = extra[i++];
      const OrientedFace& m = missing[j++];
      builder.add([&] {
        return Finding{absl::StrFormat("boundary triangle %d %s matches face %s of tet %d only "
                                       "with the opposite orientation",
                                       m.owner, format_triple(m.face), format_triple(e.face),
                                       e.owner),
                       {m.face.begin(), m.face.end()}, {m.owner}, {e.owner}};
      });
    } else if (take_extra) {
      const OrientedFace& e = extra[i++];
      builder.add([&] {
        return Finding{absl::StrFormat("face %s of tet %d is on the tets' boundary but not in "
                                       "the boundary mesh",
                                       format_triple(e.face), e.owner),
                       {e.face.begin(), e.face.end()}, {}, {e.owner}};
      });
    } else {
      const OrientedFace& m = missing[j++];
      builder.add([&] {
        return Finding{absl::StrFormat("boundary triangle %d %s is not a boundary face of the "
                                       "tets",
                                       m.owner, format_triple(m.face)),
                       {m.face.begin(), m.face.end()}, {m.owner}, {}};
      });
    }
  }
}

// boundary_match when the boundary mesh itself is broken: its bad indices and coordinates.
Check check_invalid_boundary(const Mesh& boundary, const ValidationParams& params) {
  CheckBuilder builder(check::kBoundaryMatch, params);
  const Index point_count = static_cast<Index>(boundary.points.size());
  for (Index t = 0; t < static_cast<Index>(boundary.triangles.size()); ++t) {
    for (Index v : boundary.triangles[t]) {
      if (v >= 0 && v < point_count) continue;
      builder.add([&] {
        return Finding{absl::StrFormat("boundary triangle %d has point index %d outside "
                                       "[0, %d)",
                                       t, v, point_count),
                       {}, {t}, {}};
      });
    }
  }
  for (Index p = 0; p < point_count; ++p) {
    const Point& x = boundary.points[p];
    if (std::isfinite(x[0]) && std::isfinite(x[1]) && std::isfinite(x[2])) continue;
    builder.add([&] {
      return Finding{absl::StrFormat("boundary point %d has a non-finite coordinate (%g, %g, %g)",
                                     p, x[0], x[1], x[2])};
    });
  }
  return builder.finish("", absl::StrFormat("the boundary mesh is invalid (%d bad %s): validate "
                                            "it with validate_surface",
                                            builder.count(),
                                            plural(builder.count(), "entry", "entries")));
}

}  // namespace

// boundary_match: the tets' boundary faces equal the boundary mesh's triangles.
Check check_boundary_match(const Mesh& mesh, const BoundaryFaces& faces, const Mesh& boundary,
                           const ValidationParams& params) {
  if (!indices_and_coordinates_ok(boundary.points, boundary.triangles)) {
    return check_invalid_boundary(boundary, params);
  }
  const bool by_index = shares_leading_points(mesh, boundary);
  std::vector<Index> point_map(boundary.points.size());
  if (by_index) {
    for (Index p = 0; p < static_cast<Index>(point_map.size()); ++p) point_map[p] = p;
  } else {
    point_map = match_points_by_coordinates(mesh, boundary);
  }
  CheckBuilder builder(check::kBoundaryMatch, params);
  std::vector<OrientedFace> missing = mapped_boundary_triangles(boundary, point_map, builder);
  std::vector<OrientedFace> extra;
  for (std::size_t i = 0; i < faces.triangles.size(); ++i) {
    extra.push_back({canonical_rotation(faces.triangles[i]), faces.tets[i]});
  }
  std::sort(extra.begin(), extra.end(), by_face);
  remove_common_faces(extra, missing);
  report_face_differences(extra, missing, builder);

  const std::string how =
      by_index ? absl::StrFormat("points matched by index: the boundary's %d points are the "
                                 "volume mesh's first points",
                                 boundary.points.size())
               : std::string("points matched by exact coordinates");
  return builder.finish(
      absl::StrFormat("the %d boundary faces of the tets equal the %d boundary triangles (%s)",
                      faces.triangles.size(), boundary.triangles.size(), how),
      absl::StrFormat("%d %s between the tets' %d boundary faces and the %d boundary triangles "
                      "(%s)",
                      builder.count(), plural(builder.count(), "difference", "differences"),
                      faces.triangles.size(), boundary.triangles.size(), how));
}

}  // namespace afmesh
