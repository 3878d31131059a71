// Tests of the sides along a discrete line (F3): counts, spacing under uniform and graded sizes,
// points on the polyline, fixed ends, and errors.
#include "core/surface/split_lines.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <vector>

#include "core/geometry/closest_points.h"
#include "core/geometry/vec.h"
#include "core/shapes/shapes.h"
#include "core/surface/features.h"
#include "tests/surface/surface_test_shapes.h"

namespace afmesh {
namespace {

LineSplit split_or_die(const std::vector<Point>& polyline, const SizeField& sizes,
                       const SplitLineParams& params = {}) {
  absl::StatusOr<LineSplit> split = split_line(polyline, sizes, params);
  EXPECT_TRUE(split.ok()) << split.status();
  return *std::move(split);
}

// h(x) = a + b x: grows along the x axis.
class LinearSize final : public SizeField {
 public:
  LinearSize(double a, double b) : a_(a), b_(b) {}
  double size_at(const Point& x) const override { return a_ + b_ * x[0]; }

 private:
  double a_, b_;
};

void expect_ends_and_shape(const LineSplit& split, const std::vector<Point>& polyline) {
  ASSERT_GE(split.points.size(), 2u);
  EXPECT_EQ(split.points.front(), polyline.front());
  EXPECT_EQ(split.points.back(), polyline.back());
  EXPECT_EQ(split.arc_length.size(), split.points.size());
  EXPECT_EQ(split.segment.size(), split.points.size());
  for (std::size_t j = 0; j < split.points.size(); ++j) {
    const Index i = split.segment[j];
    const Point on = closest_point_on_segment(split.points[j], polyline[i], polyline[i + 1]);
    EXPECT_LE(distance(on, split.points[j]), 1e-15 * (1.0 + norm(split.points[j])));
    if (j > 0) {
      EXPECT_GT(split.arc_length[j], split.arc_length[j - 1]);
    }
  }
}

// A straight line with unevenly spaced vertices and a uniform size: equal sides.
TEST(SplitLine, UniformSizeGivesEqualSides) {
  const std::vector<Point> line = {
      {0, 0, 0}, {0.07, 0.14, 0.21}, {0.5, 1, 1.5}, {0.51, 1.02, 1.53}, {1, 2, 3}};
  const double length = std::sqrt(14.0);
  const LineSplit split = split_or_die(line, UniformSize(0.1));
  expect_ends_and_shape(split, line);
  const auto n = static_cast<double>(split.points.size() - 1);
  EXPECT_EQ(n, std::round(length / 0.1));
  for (std::size_t j = 1; j < split.points.size(); ++j) {
    EXPECT_NEAR(distance(split.points[j - 1], split.points[j]) / (length / n), 1.0, 1e-12) << j;
  }
}

// A polygon approximating a circle, closed: equal steps of arc length.
TEST(SplitLine, UniformSizeOnAClosedPolygonGivesEqualArcSteps) {
  std::vector<Point> loop;
  for (int k = 0; k <= 37; ++k) {
    const double phi = 2 * std::numbers::pi * (k % 37) / 37 + 0.01 * (k % 3);
    loop.push_back({std::cos(phi), std::sin(phi), 0.0});
  }
  loop.back() = loop.front();
  const LineSplit split = split_or_die(loop, UniformSize(0.13));
  expect_ends_and_shape(split, loop);
  const double total = split.arc_length.back();
  const auto n = static_cast<double>(split.points.size() - 1);
  EXPECT_EQ(n, std::round(total / 0.13));
  for (std::size_t j = 1; j < split.points.size(); ++j) {
    EXPECT_NEAR((split.arc_length[j] - split.arc_length[j - 1]) / (total / n), 1.0, 1e-12);
  }
}

// h grows from 0.01 to 0.11 along the line: each side is within 10% of h at its middle.
TEST(SplitLine, GradedSizeIsFollowed) {
  const std::vector<Point> line = {{0, 0, 0}, {0.3, 0, 0}, {1, 0, 0}};
  const LinearSize sizes(0.01, 0.1);
  const LineSplit split = split_or_die(line, sizes);
  expect_ends_and_shape(split, line);
  // n = round(∫ dx / (0.01 + 0.1 x)) = round(10 ln 11) = 24.
  EXPECT_EQ(split.points.size(), 25u);
  for (std::size_t j = 1; j < split.points.size(); ++j) {
    const double side = distance(split.points[j - 1], split.points[j]);
    const double h = sizes.size_at(lerp(split.points[j - 1], split.points[j], 0.5));
    EXPECT_NEAR(side / h, 1.0, 0.1) << j;
  }
}

TEST(SplitLine, LineShorterThanTheSizeGetsOneSide) {
  const std::vector<Point> line = {{0, 0, 0}, {0.05, 0, 0}, {0.1, 0.02, 0}};
  const LineSplit split = split_or_die(line, UniformSize(1.0));
  ASSERT_EQ(split.points.size(), 2u);
  expect_ends_and_shape(split, line);
}

// A closed loop shorter than the size: one side would run from its corner to itself.
TEST(SplitLine, MinSidesSplitsALoopShorterThanTheSize) {
  const std::vector<Point> loop = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0, 0, 0}};
  EXPECT_EQ(split_or_die(loop, UniformSize(10.0)).points.size(), 2u);
  SplitLineParams params;
  params.min_sides = 3;
  const LineSplit split = split_or_die(loop, UniformSize(10.0), params);
  ASSERT_EQ(split.points.size(), 4u);
  expect_ends_and_shape(split, loop);
  for (std::size_t j = 1; j < split.points.size(); ++j) {
    EXPECT_NEAR(split.arc_length[j] - split.arc_length[j - 1], 4.0 / 3.0, 1e-12) << j;
  }
  // More sides than min_sides when the size asks for them.
  EXPECT_EQ(split_or_die(loop, UniformSize(0.5), params).points.size(), 9u);
}

TEST(SplitLine, FieldOriginShiftsWhereTheSizeIsAsked) {
  const std::vector<Point> line = {{-0.5, 0, 0}, {0.5, 0, 0}};
  SplitLineParams params;
  params.field_origin = {10.0, 0, 0};  // the line lies at x in [9.5, 10.5] for the field
  const LinearSize sizes(-0.9, 0.1);   // h = 0.05 ... 0.15 there
  const LineSplit split = split_or_die(line, sizes, params);
  EXPECT_EQ(split.points.size() - 1, static_cast<std::size_t>(std::round(10 * std::log(3.0))));
}

TEST(SplitLine, RefusesBadInput) {
  const UniformSize h(0.1);
  EXPECT_EQ(split_line(std::vector<Point>{{0, 0, 0}}, h).status().code(),
            absl::StatusCode::kInvalidArgument);
  EXPECT_EQ(split_line(std::vector<Point>{{1, 1, 1}, {1, 1, 1}}, h).status().code(),
            absl::StatusCode::kInvalidArgument);
  EXPECT_EQ(split_line(std::vector<Point>{{0, 0, 0}, {NAN, 0, 0}}, h).status().code(),
            absl::StatusCode::kInvalidArgument);
  EXPECT_EQ(split_line(std::vector<Point>{{0, 0, 0}, {1, 0, 0}}, UniformSize(0.0)).status().code(),
            absl::StatusCode::kInvalidArgument);
  SplitLineParams params;
  params.growth = 0.9;
  EXPECT_EQ(split_line(std::vector<Point>{{0, 0, 0}, {1, 0, 0}}, h, params).status().code(),
            absl::StatusCode::kInvalidArgument);
  params.growth = 1.0;
  params.start_size = 0.0;
  EXPECT_EQ(split_line(std::vector<Point>{{0, 0, 0}, {1, 0, 0}}, h, params).status().code(),
            absl::StatusCode::kInvalidArgument);
  params.start_size = std::numeric_limits<double>::infinity();
  params.min_sides = 0;
  EXPECT_EQ(split_line(std::vector<Point>{{0, 0, 0}, {1, 0, 0}}, h, params).status().code(),
            absl::StatusCode::kInvalidArgument);
  params.min_sides = 3;
  params.max_sides = 2;
  EXPECT_EQ(split_line(std::vector<Point>{{0, 0, 0}, {1, 0, 0}}, h, params).status().code(),
            absl::StatusCode::kInvalidArgument);
  params.min_sides = 1;
  params.max_sides = 100;
  EXPECT_EQ(split_line(std::vector<Point>{{0, 0, 0}, {1, 0, 0}}, UniformSize(1e-3), params)
                .status()
                .code(),
            absl::StatusCode::kResourceExhausted);
}

// §4.2 with eq. 15: a corner of size 0.02 on a line asking 0.5, sides growing by 1.2 from it.
TEST(SplitLine, EndSizeGrowsAlongTheLine) {
  const std::vector<Point> line = {{0, 0, 0}, {0.4, 0, 0}, {1, 0, 0}};
  SplitLineParams params;
  params.start_size = 0.02;
  params.growth = 1.2;
  const LineSplit split = split_or_die(line, UniformSize(0.5), params);
  expect_ends_and_shape(split, line);
  // h(s) = 0.02 + 0.2 s over the whole line: n = round(5 ln 11) = 12.
  ASSERT_EQ(split.points.size(), 13u);
  EXPECT_NEAR(distance(split.points[0], split.points[1]) / 0.02, 1.0, 0.15);
  for (std::size_t j = 2; j < split.points.size(); ++j) {
    const double ratio = distance(split.points[j - 1], split.points[j]) /
                         distance(split.points[j - 2], split.points[j - 1]);
    EXPECT_NEAR(ratio, 1.2, 0.05) << j;
  }
  // Growth 1 keeps the corner's size along the whole line (the paper's uniform case).
  params.growth = 1.0;
  params.start_size = 0.1;
  params.end_size = 0.25;
  EXPECT_EQ(split_or_die(line, UniformSize(0.5), params).points.size(), 11u);
}

// A thin plate: each corner has a line of length 0.1, the plate's thickness, so every line of
// the plate gets that size at both ends; a cylinder's rims are loops: their own length.
TEST(SplitLine, LineEndSizesAreTheShortestLineAtEachCorner) {
  const testing::SurfaceModel plate =
      testing::surface_model(box_surface({0, 0, 0}, {1, 1, 0.1}, 0.05));
  ASSERT_EQ(plate.features.lines.size(), 12u);
  for (const LineEndSizes& ends : line_end_sizes(plate.surface, plate.features)) {
    EXPECT_NEAR(ends.start, 0.1, 1e-15);
    EXPECT_NEAR(ends.end, 0.1, 1e-15);
  }
  const testing::SurfaceModel cylinder =
      testing::surface_model(testing::closed_cylinder(1.0, 2.0, 32, 4));
  ASSERT_EQ(cylinder.features.lines.size(), 2u);
  const double rim = 32 * 2 * std::sin(std::numbers::pi / 32);
  for (const LineEndSizes& ends : line_end_sizes(cylinder.surface, cylinder.features)) {
    EXPECT_NEAR(ends.start, rim, 1e-14);
    EXPECT_NEAR(ends.end, rim, 1e-14);
  }
}

// The lines of a cube's features, in the surface's local frame, split for h = 0.3: three sides
// each, ends at the corners.
TEST(SplitLine, CubeLinesFromFeatures) {
  const testing::SurfaceModel cube =
      testing::surface_model(box_surface({4, 4, 4}, {5, 5, 5}, 0.25));
  ASSERT_EQ(cube.features.lines.size(), 12u);
  SplitLineParams params;
  params.field_origin = cube.surface.origin();
  for (const DiscreteLine& line : cube.features.lines) {
    std::vector<Point> polyline;
    for (Index v : line.vertices) polyline.push_back(cube.surface.local_points()[v]);
    const LineSplit split = split_or_die(polyline, UniformSize(0.3), params);
    expect_ends_and_shape(split, polyline);
    EXPECT_EQ(split.points.size(), 4u);
  }
}

}  // namespace
}  // namespace afmesh
