#include "proto/slice_codec.h"

#include <array>
#include <cmath>
#include <string>

#include "absl/strings/str_format.h"

namespace afmesh::wire {
namespace {

template <class T>
using Flat = google::protobuf::RepeatedField<T>;

// Rows [begin, end) of `rows`, flattened onto the end of `flat`.
template <class T, std::size_t K>
void add_rows(const std::vector<std::array<T, K>>& rows, std::size_t begin, std::size_t end,
              Flat<T>& flat) {
  flat.Reserve(flat.size() + static_cast<int>(K * (end - begin)));
  for (std::size_t r = begin; r < end; ++r) {
    for (const T value : rows[r]) flat.Add(value);
  }
}

// One tag per row of [begin, end): tags[r], or 0 past the end of `tags`.
void add_tags(const std::vector<Index>& tags, std::size_t begin, std::size_t end,
              Flat<Index>& flat) {
  flat.Reserve(flat.size() + static_cast<int>(end - begin));
  for (std::size_t r = begin; r < end; ++r) flat.Add(r < tags.size() ? tags[r] : 0);
}

// The rows of K values `flat` carries; INVALID_ARGUMENT "<where>: <kind> has N <values>, not a
// multiple of K" when its length is not a multiple of K.
template <std::size_t K, class T>
absl::StatusOr<std::size_t> row_count(const Flat<T>& flat, std::string_view where,
                                      std::string_view kind, std::string_view values) {
  if (flat.size() % static_cast<int>(K) != 0) {
    return absl::InvalidArgumentError(absl::StrFormat("%s: %s has %d %s, not a multiple of %d",
                                                      where, kind, flat.size(), values, K));
  }
  return static_cast<std::size_t>(flat.size()) / K;
}

// The rows of `flat`, appended to `rows` (whose length is a multiple of K: checked).
template <class T, std::size_t K>
void append_rows(const Flat<T>& flat, std::vector<std::array<T, K>>& rows) {
  for (int i = 0; i < flat.size(); i += static_cast<int>(K)) {
    std::array<T, K>& row = rows.emplace_back();
    for (std::size_t j = 0; j < K; ++j) row[j] = flat.Get(i + static_cast<int>(j));
  }
}

// The position of the first non-finite value of `xyz`, or -1.
int first_non_finite(const Flat<double>& xyz) {
  for (int i = 0; i < xyz.size(); ++i) {
    if (!std::isfinite(xyz.Get(i))) return i;
  }
  return -1;
}

// The position of the first negative index of `indices`, or -1.
int first_negative(const Flat<Index>& indices) {
  for (int i = 0; i < indices.size(); ++i) {
    if (indices.Get(i) < 0) return i;
  }
  return -1;
}

// Appends the rows of `flat` once its shape (`count`) is right and it holds no bad value (`bad`:
// the position of the first, or -1); else INVALID_ARGUMENT, `describe(row, column, value)`
// naming the bad value by its row in the whole array.
template <class T, std::size_t K, class Describe>
absl::Status append_checked(const Flat<T>& flat, const absl::StatusOr<std::size_t>& count,
                            int bad, const Describe& describe,
                            std::vector<std::array<T, K>>& rows) {
  if (!count.ok()) return count.status();
  if (bad >= 0) {
    return absl::InvalidArgumentError(describe(rows.size() + static_cast<std::size_t>(bad) / K,
                                               bad % static_cast<int>(K), flat.Get(bad)));
  }
  append_rows(flat, rows);
  return absl::OkStatus();
}

// Triangle and tet slices: K indices per element and none or one tag each. `elements` is the
// kind's plural ("triangles", "tets"); without its last letter, one element.
template <std::size_t K>
absl::StatusOr<std::size_t> element_count(const Flat<Index>& indices, const Flat<Index>& tags,
                                          std::string_view where, std::string_view elements) {
  absl::StatusOr<std::size_t> count =
      row_count<K>(indices, where, absl::StrFormat("%s slice", elements), "indices");
  if (!count.ok()) return count;
  if (tags.size() != 0 && static_cast<std::size_t>(tags.size()) != *count) {
    return absl::InvalidArgumentError(absl::StrFormat(
        "%s: %s slice has %d tags for %d %s (send none or one per %s)", where, elements,
        tags.size(), *count, elements, elements.substr(0, elements.size() - 1)));
  }
  return count;
}

template <std::size_t K>
absl::Status append_elements(const Flat<Index>& indices, const Flat<Index>& tags,
                             std::string_view where, std::string_view elements,
                             std::vector<std::array<Index, K>>& rows,
                             std::vector<Index>& row_tags) {
  const absl::StatusOr<std::size_t> count = element_count<K>(indices, tags, where, elements);
  const auto describe = [elements](std::size_t element, int corner, Index index) {
    return absl::StrFormat("%s %d has a negative point index %d (corner %d)",
                           elements.substr(0, elements.size() - 1), element, index, corner);
  };
  if (absl::Status status = append_checked(indices, count, first_negative(indices), describe, rows);
      !status.ok()) {
    return status;
  }
  if (tags.size() == 0) {
    row_tags.insert(row_tags.end(), *count, 0);
  } else {
    row_tags.insert(row_tags.end(), tags.begin(), tags.end());
  }
  return absl::OkStatus();
}

}  // namespace

void encode_points(const std::vector<Point>& points, std::size_t begin, std::size_t end,
                   v1::PointSlice& slice) {
  add_rows(points, begin, end, *slice.mutable_xyz());
}

void encode_triangles(const std::vector<Triangle>& triangles, const std::vector<Index>& tags,
                      std::size_t begin, std::size_t end, v1::TriangleSlice& slice) {
  add_rows(triangles, begin, end, *slice.mutable_indices());
  add_tags(tags, begin, end, *slice.mutable_tags());
}

void encode_tets(const std::vector<Tet>& tets, const std::vector<Index>& tags, std::size_t begin,
                 std::size_t end, v1::TetSlice& slice) {
  add_rows(tets, begin, end, *slice.mutable_indices());
  add_tags(tags, begin, end, *slice.mutable_tags());
}

void encode_grid_points(const std::vector<Point>& points, std::size_t begin, std::size_t end,
                        v1::BackgroundGridSlice& slice) {
  add_rows(points, begin, end, *slice.mutable_xyz());
}

void encode_grid_sizes(const std::vector<double>& sizes, std::size_t begin, std::size_t end,
                       v1::BackgroundGridSlice& slice) {
  slice.mutable_sizes()->Add(sizes.begin() + static_cast<std::ptrdiff_t>(begin),
                             sizes.begin() + static_cast<std::ptrdiff_t>(end));
}

void encode_grid_tets(const std::vector<Tet>& tets, std::size_t begin, std::size_t end,
                      v1::BackgroundGridSlice& slice) {
  add_rows(tets, begin, end, *slice.mutable_tets());
}

absl::StatusOr<std::size_t> point_count(const v1::PointSlice& slice, std::string_view where) {
  return row_count<3>(slice.xyz(), where, "points slice", "coordinates");
}

absl::Status append_points(const v1::PointSlice& slice, std::string_view where,
                           std::vector<Point>& points) {
  const auto describe = [](std::size_t point, int axis, double value) {
    return absl::StrFormat("point %d has a non-finite coordinate %c = %g", point, "xyz"[axis],
                           value);
  };
  return append_checked(slice.xyz(), point_count(slice, where), first_non_finite(slice.xyz()),
                        describe, points);
}

absl::StatusOr<std::size_t> triangle_count(const v1::TriangleSlice& slice,
                                           std::string_view where) {
  return element_count<3>(slice.indices(), slice.tags(), where, "triangles");
}

absl::Status append_triangles(const v1::TriangleSlice& slice, std::string_view where,
                              std::vector<Triangle>& triangles, std::vector<Index>& tags) {
  return append_elements<3>(slice.indices(), slice.tags(), where, "triangles", triangles, tags);
}

absl::StatusOr<std::size_t> tet_count(const v1::TetSlice& slice, std::string_view where) {
  return element_count<4>(slice.indices(), slice.tags(), where, "tets");
}

absl::Status append_tets(const v1::TetSlice& slice, std::string_view where, std::vector<Tet>& tets,
                         std::vector<Index>& tags) {
  return append_elements<4>(slice.indices(), slice.tags(), where, "tets", tets, tags);
}

absl::StatusOr<std::size_t> grid_point_count(const v1::BackgroundGridSlice& slice,
                                             std::string_view where) {
  return row_count<3>(slice.xyz(), where, "background_grid slice", "coordinates");
}

absl::Status append_grid_points(const v1::BackgroundGridSlice& slice, std::string_view where,
                                std::vector<Point>& points) {
  const auto describe = [](std::size_t point, int axis, double value) {
    return absl::StrFormat("background_grid.points[%d].%c must be finite, got %g", point,
                           "xyz"[axis], value);
  };
  return append_checked(slice.xyz(), grid_point_count(slice, where),
                        first_non_finite(slice.xyz()), describe, points);
}

absl::Status append_grid_sizes(const v1::BackgroundGridSlice& slice, std::vector<double>& sizes) {
  for (int i = 0; i < slice.sizes_size(); ++i) {
    const double size = slice.sizes(i);
    if (!std::isfinite(size) || size <= 0.0) {
      return absl::InvalidArgumentError(absl::StrFormat(
          "background_grid.sizes[%d] must be finite and > 0, got %g", sizes.size() + i, size));
    }
  }
  sizes.insert(sizes.end(), slice.sizes().begin(), slice.sizes().end());
  return absl::OkStatus();
}

absl::StatusOr<std::size_t> grid_tet_count(const v1::BackgroundGridSlice& slice,
                                           std::string_view where) {
  return row_count<4>(slice.tets(), where, "background_grid slice", "tet indices");
}

absl::Status append_grid_tets(const v1::BackgroundGridSlice& slice, std::string_view where,
                              std::vector<Tet>& tets) {
  const auto describe = [](std::size_t tet, int corner, Index index) {
    return absl::StrFormat("background_grid.tets[%d][%d] = %d is a negative point index", tet,
                           corner, index);
  };
  return append_checked(slice.tets(), grid_tet_count(slice, where), first_negative(slice.tets()),
                        describe, tets);
}

}  // namespace afmesh::wire
