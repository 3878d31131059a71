// The slice codec (proto/slice_codec.h): mesh arrays through point, triangle, tet and background
// grid slices and back, bit for bit, cut at 32768 items; tags present and absent; malformed
// slices refused with the messages MeshVolume's clients read.
#include "proto/slice_codec.h"

#include <limits>
#include <string>
#include <vector>

#include "gmock/gmock.h"
#include "gtest/gtest.h"
#include "tests/server/request_support.h"

namespace afmesh::wire {
namespace {

using afmesh::testing::same_bits;

constexpr std::size_t kMessageCap = 1 << 20;  // bytes of payload per message

// One more than a slice of each kind, with values that only survive a bit-exact transfer and
// negative tags (the longest varints).
Mesh two_slice_mesh() {
  const int n = static_cast<int>(kMaxSliceItems) + 1;
  Mesh mesh;
  for (int i = 0; i < n; ++i) {
    mesh.points.push_back({i / 3.0, i % 2 == 0 ? -0.0 : 4.9e-320, -1.7e308});
    mesh.triangles.push_back({i, i + 1, i + 2});
    mesh.triangle_tags.push_back(i % 3 == 0 ? -1 : i);
    mesh.tets.push_back({i, i + 1, i + 2, i + 3});
    mesh.tet_tags.push_back(std::numeric_limits<Index>::min());
  }
  return mesh;
}

TEST(SliceCodec, SliceEndCutsAtTheLimit) {
  EXPECT_EQ(slice_end(0, 10), 10u);
  EXPECT_EQ(slice_end(0, kMaxSliceItems), kMaxSliceItems);
  EXPECT_EQ(slice_end(0, kMaxSliceItems + 1), kMaxSliceItems);
  EXPECT_EQ(slice_end(kMaxSliceItems, kMaxSliceItems + 1), kMaxSliceItems + 1);
  EXPECT_EQ(slice_end(4, 10, 4), 8u);
}

TEST(SliceCodec, MeshRoundTripsBitExactInSlicesUnderOneMebibyte) {
  const Mesh mesh = two_slice_mesh();
  Mesh received;
  int slices = 0;
  for (std::size_t begin = 0; begin < mesh.points.size(); begin += kMaxSliceItems, ++slices) {
    const std::size_t end = slice_end(begin, mesh.points.size());
    v1::PointSlice points;
    encode_points(mesh.points, begin, end, points);
    v1::TriangleSlice triangles;
    encode_triangles(mesh.triangles, mesh.triangle_tags, begin, end, triangles);
    v1::TetSlice tets;
    encode_tets(mesh.tets, mesh.tet_tags, begin, end, tets);
    EXPECT_LE(points.ByteSizeLong(), kMessageCap);
    EXPECT_LE(triangles.ByteSizeLong(), kMessageCap);
    EXPECT_LE(tets.ByteSizeLong(), kMessageCap);
    EXPECT_EQ(*point_count(points, "m"), end - begin);
    EXPECT_EQ(*triangle_count(triangles, "m"), end - begin);
    EXPECT_EQ(*tet_count(tets, "m"), end - begin);
    ASSERT_TRUE(append_points(points, "m", received.points).ok());
    ASSERT_TRUE(append_triangles(triangles, "m", received.triangles, received.triangle_tags).ok());
    ASSERT_TRUE(append_tets(tets, "m", received.tets, received.tet_tags).ok());
  }
  EXPECT_EQ(slices, 2);
  EXPECT_TRUE(same_bits(received.points, mesh.points));
  EXPECT_EQ(received.triangles, mesh.triangles);
  EXPECT_EQ(received.triangle_tags, mesh.triangle_tags);
  EXPECT_EQ(received.tets, mesh.tets);
  EXPECT_EQ(received.tet_tags, mesh.tet_tags);
}

TEST(SliceCodec, EncodingAlwaysSendsOneTagPerElementZeroWhenUntagged) {
  const std::vector<Triangle> triangles = {{0, 1, 2}, {1, 2, 3}, {2, 3, 4}};
  v1::TriangleSlice slice;
  encode_triangles(triangles, {5}, 0, 3, slice);
  EXPECT_THAT(slice.tags(), ::testing::ElementsAre(5, 0, 0));
  v1::TetSlice tets;
  encode_tets({{0, 1, 2, 3}}, {}, 0, 1, tets);
  EXPECT_THAT(tets.tags(), ::testing::ElementsAre(0));
}

TEST(SliceCodec, SlicesWithoutTagsDecodeAsTagZero) {
  v1::TriangleSlice triangles;
  for (const int i : {0, 1, 2, 1, 2, 3}) triangles.add_indices(i);
  std::vector<Triangle> rows = {{7, 8, 9}};
  std::vector<Index> tags = {4};
  ASSERT_TRUE(append_triangles(triangles, "m", rows, tags).ok());
  EXPECT_EQ(rows, (std::vector<Triangle>{{7, 8, 9}, {0, 1, 2}, {1, 2, 3}}));
  EXPECT_EQ(tags, (std::vector<Index>{4, 0, 0}));

  v1::TetSlice tets;
  for (const int i : {0, 1, 2, 3}) tets.add_indices(i);
  std::vector<Tet> tet_rows;
  std::vector<Index> tet_tags;
  ASSERT_TRUE(append_tets(tets, "m", tet_rows, tet_tags).ok());
  EXPECT_EQ(tet_tags, std::vector<Index>{0});
}

TEST(SliceCodec, BackgroundGridListsRoundTripEachContinuingItsOwnArray) {
  const std::vector<Point> points = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {-0.0, 1, 1}};
  const std::vector<Tet> tets = {{0, 1, 2, 3}, {1, 2, 3, 4}};
  const std::vector<double> sizes = {0.1, 0.2, 0.3, 0.4, 0.5};
  v1::BackgroundGridSlice first;
  encode_grid_points(points, 0, 3, first);
  encode_grid_tets(tets, 0, 1, first);
  v1::BackgroundGridSlice second;
  encode_grid_points(points, 3, 5, second);
  encode_grid_sizes(sizes, 0, 5, second);
  encode_grid_tets(tets, 1, 2, second);

  std::vector<Point> got_points;
  std::vector<Tet> got_tets;
  std::vector<double> got_sizes;
  for (const v1::BackgroundGridSlice* slice : {&first, &second}) {
    ASSERT_TRUE(append_grid_points(*slice, "m", got_points).ok());
    ASSERT_TRUE(append_grid_sizes(*slice, got_sizes).ok());
    ASSERT_TRUE(append_grid_tets(*slice, "m", got_tets).ok());
  }
  EXPECT_EQ(*grid_point_count(second, "m"), 2u);
  EXPECT_EQ(*grid_tet_count(second, "m"), 1u);
  EXPECT_TRUE(same_bits(got_points, points));
  EXPECT_EQ(got_tets, tets);
  EXPECT_EQ(got_sizes, sizes);
}

// The messages MeshVolume has always answered malformed slices with (tests/server/
// mesher_service_test.cc checks them through the service).
TEST(SliceCodec, MalformedSlicesAreRefusedNamingTheMessageOrTheElement) {
  std::vector<Point> points(7);
  v1::PointSlice four_coordinates;
  for (const double c : {1.0, 2.0, 3.0, 4.0}) four_coordinates.add_xyz(c);
  EXPECT_EQ(point_count(four_coordinates, "message 3").status().message(),
            "message 3: points slice has 4 coordinates, not a multiple of 3");
  EXPECT_EQ(append_points(four_coordinates, "message 3", points).message(),
            "message 3: points slice has 4 coordinates, not a multiple of 3");
  v1::PointSlice not_finite;
  for (const double c : {1.0, 2.0, 3.0, 4.0, std::numeric_limits<double>::quiet_NaN(), 6.0}) {
    not_finite.add_xyz(c);
  }
  EXPECT_EQ(append_points(not_finite, "message 3", points).message(),
            "point 8 has a non-finite coordinate y = nan");

  std::vector<Triangle> triangles(5);
  std::vector<Index> tags(5);
  v1::TriangleSlice four_indices;
  for (const int i : {0, 1, 2, 3}) four_indices.add_indices(i);
  EXPECT_EQ(triangle_count(four_indices, "message 2").status().message(),
            "message 2: triangles slice has 4 indices, not a multiple of 3");
  v1::TriangleSlice one_tag;
  for (const int i : {0, 1, 2, 1, 2, 3}) one_tag.add_indices(i);
  one_tag.add_tags(1);
  EXPECT_EQ(append_triangles(one_tag, "message 2", triangles, tags).message(),
            "message 2: triangles slice has 1 tags for 2 triangles (send none or one per "
            "triangle)");
  v1::TriangleSlice negative;
  for (const int i : {0, 1, 2, 1, 2, -1}) negative.add_indices(i);
  EXPECT_EQ(append_triangles(negative, "message 2", triangles, tags).message(),
            "triangle 6 has a negative point index -1 (corner 2)");

  std::vector<Tet> tets;
  std::vector<Index> tet_tags;
  v1::TetSlice three_indices;
  for (const int i : {0, 1, 2}) three_indices.add_indices(i);
  EXPECT_EQ(tet_count(three_indices, "message 9").status().message(),
            "message 9: tets slice has 3 indices, not a multiple of 4");
  v1::TetSlice tet_tags_off;
  for (const int i : {0, 1, 2, 3}) tet_tags_off.add_indices(i);
  tet_tags_off.add_tags(1);
  tet_tags_off.add_tags(2);
  EXPECT_EQ(append_tets(tet_tags_off, "message 9", tets, tet_tags).message(),
            "message 9: tets slice has 2 tags for 1 tets (send none or one per tet)");

  for (const absl::Status& status :
       {append_points(four_coordinates, "m", points),
        append_triangles(negative, "m", triangles, tags),
        append_tets(three_indices, "m", tets, tet_tags)}) {
    EXPECT_EQ(status.code(), absl::StatusCode::kInvalidArgument);
  }
}

TEST(SliceCodec, MalformedGridSlicesAreRefusedNamingTheGridElement) {
  std::vector<Point> points(2);
  std::vector<double> sizes(4);
  std::vector<Tet> tets(1);
  v1::BackgroundGridSlice slice;
  for (const double c : {1.0, 2.0, 3.0, 4.0}) slice.add_xyz(c);
  EXPECT_EQ(append_grid_points(slice, "message 5", points).message(),
            "message 5: background_grid slice has 4 coordinates, not a multiple of 3");
  slice.Clear();
  for (const double c : {1.0, 2.0, 3.0, 4.0, 5.0, std::numeric_limits<double>::infinity()}) {
    slice.add_xyz(c);
  }
  EXPECT_EQ(append_grid_points(slice, "message 5", points).message(),
            "background_grid.points[3].z must be finite, got inf");
  slice.Clear();
  slice.add_sizes(1.0);
  slice.add_sizes(0.0);
  EXPECT_EQ(append_grid_sizes(slice, sizes).message(),
            "background_grid.sizes[5] must be finite and > 0, got 0");
  slice.Clear();
  for (const int i : {0, 1, 2, 3, 4, 5}) slice.add_tets(i);
  EXPECT_EQ(grid_tet_count(slice, "message 5").status().message(),
            "message 5: background_grid slice has 6 tet indices, not a multiple of 4");
  slice.Clear();
  for (const int i : {0, 1, 2, 3, 4, -5, 6, 7}) slice.add_tets(i);
  EXPECT_EQ(append_grid_tets(slice, "message 5", tets).message(),
            "background_grid.tets[2][1] = -5 is a negative point index");
}

TEST(SliceCodec, ARefusedSliceLeavesTheArraysAsTheyWere) {
  Mesh mesh;
  mesh.points = {{1, 2, 3}};
  mesh.triangles = {{0, 0, 0}};
  mesh.triangle_tags = {9};
  v1::PointSlice points;
  for (const double c : {4.0, 5.0, 6.0, std::numeric_limits<double>::infinity(), 0.0, 0.0}) {
    points.add_xyz(c);
  }
  EXPECT_FALSE(append_points(points, "m", mesh.points).ok());
  v1::TriangleSlice triangles;
  for (const int i : {0, 1, 2, 0, -1, 2}) triangles.add_indices(i);
  EXPECT_FALSE(append_triangles(triangles, "m", mesh.triangles, mesh.triangle_tags).ok());
  EXPECT_EQ(mesh.points, (std::vector<Point>{{1, 2, 3}}));
  EXPECT_EQ(mesh.triangles, (std::vector<Triangle>{{0, 0, 0}}));
  EXPECT_EQ(mesh.triangle_tags, std::vector<Index>{9});
}

}  // namespace
}  // namespace afmesh::wire
