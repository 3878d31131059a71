// Mesh arrays to and from the wire's slices (PointSlice, TriangleSlice, TetSlice and the
// BackgroundGridSlice lists of mesher.proto): the one place the client and the server flatten
// rows into repeated fields and read them back (house style, "One idea, one place").
//
// Encoding appends rows [begin, end) of an array to a slice; callers cut arrays into slices of
// at most kMaxSliceItems rows with slice_end. Decoding appends a slice's rows to an array after
// checking the whole slice, so an array is left as it was when a slice is refused. Each kind
// is decoded in two steps a receiver may separate, to check its limits in between: *_count
// checks the slice's shape and says how many rows it carries; append_* checks again, then its
// values, and appends. Errors are INVALID_ARGUMENT, shape errors prefixed with `where` (the
// message, e.g. "message 3"), value errors naming the row by its index in the whole array.
#pragma once

#include <algorithm>
#include <cstddef>
#include <string_view>
#include <vector>

#include "absl/status/status.h"
#include "absl/status/statusor.h"
#include "afmesh/v1/mesher.pb.h"
#include "core/mesh/mesh.h"

namespace afmesh::wire {

// Most points, triangles or tets per slice: 32768 points are 768 KiB of doubles; 32768 tets are
// at most 640 KiB of indices plus 320 KiB of tags (int32 varints take up to 5 bytes, 10 when
// negative), so every message stays under 1 MiB of payload, well under gRPC's 4 MiB default.
inline constexpr std::size_t kMaxSliceItems = 32768;

// The end of the slice that starts at row `begin` of `count` rows.
inline std::size_t slice_end(std::size_t begin, std::size_t count,
                             std::size_t max_items = kMaxSliceItems) {
  return std::min(count, begin + max_items);
}

// Encoding: rows [begin, end) appended to the slice. Triangles and tets always carry one tag
// each: tags[i], or 0 where `tags` is shorter (an untagged mesh).
void encode_points(const std::vector<Point>& points, std::size_t begin, std::size_t end,
                   v1::PointSlice& slice);
void encode_triangles(const std::vector<Triangle>& triangles, const std::vector<Index>& tags,
                      std::size_t begin, std::size_t end, v1::TriangleSlice& slice);
void encode_tets(const std::vector<Tet>& tets, const std::vector<Index>& tags, std::size_t begin,
                 std::size_t end, v1::TetSlice& slice);
void encode_grid_points(const std::vector<Point>& points, std::size_t begin, std::size_t end,
                        v1::BackgroundGridSlice& slice);
void encode_grid_sizes(const std::vector<double>& sizes, std::size_t begin, std::size_t end,
                       v1::BackgroundGridSlice& slice);
void encode_grid_tets(const std::vector<Tet>& tets, std::size_t begin, std::size_t end,
                      v1::BackgroundGridSlice& slice);

// Decoding a PointSlice: "<where>: points slice has 4 coordinates, not a multiple of 3";
// "point 7 has a non-finite coordinate y = nan".
absl::StatusOr<std::size_t> point_count(const v1::PointSlice& slice, std::string_view where);
absl::Status append_points(const v1::PointSlice& slice, std::string_view where,
                           std::vector<Point>& points);

// Decoding a TriangleSlice (a slice without tags gives tag 0 to its triangles): "<where>:
// triangles slice has 4 indices, not a multiple of 3", "<where>: triangles slice has 1 tags for
// 2 triangles (send none or one per triangle)"; "triangle 5 has a negative point index -1
// (corner 2)". Indices are not checked against a point count: points may still be coming.
absl::StatusOr<std::size_t> triangle_count(const v1::TriangleSlice& slice, std::string_view where);
absl::Status append_triangles(const v1::TriangleSlice& slice, std::string_view where,
                              std::vector<Triangle>& triangles, std::vector<Index>& tags);

// Decoding a TetSlice, likewise (tets slice, tet k).
absl::StatusOr<std::size_t> tet_count(const v1::TetSlice& slice, std::string_view where);
absl::Status append_tets(const v1::TetSlice& slice, std::string_view where, std::vector<Tet>& tets,
                         std::vector<Index>& tags);

// Decoding the three lists of a BackgroundGridSlice, each continuing its own array: "<where>:
// background_grid slice has 4 coordinates, not a multiple of 3" (likewise "tet indices, not a
// multiple of 4"); values named as the header's grid is: "background_grid.points[i].x must be
// finite, got inf", "background_grid.sizes[i] must be finite and > 0, got 0",
// "background_grid.tets[k][j] = -1 is a negative point index".
absl::StatusOr<std::size_t> grid_point_count(const v1::BackgroundGridSlice& slice,
                                             std::string_view where);
absl::Status append_grid_points(const v1::BackgroundGridSlice& slice, std::string_view where,
                                std::vector<Point>& points);
absl::Status append_grid_sizes(const v1::BackgroundGridSlice& slice, std::vector<double>& sizes);
absl::StatusOr<std::size_t> grid_tet_count(const v1::BackgroundGridSlice& slice,
                                           std::string_view where);
absl::Status append_grid_tets(const v1::BackgroundGridSlice& slice, std::string_view where,
                              std::vector<Tet>& tets);

}  // namespace afmesh::wire
