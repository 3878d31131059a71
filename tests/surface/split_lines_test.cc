// Tests of the sides along a discrete line (F3): counts, spacing under uniform and graded sizes,
// points on the polyline, fixed ends, and errors.
#include "core/surface/split_lines.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "core/geometry/closest_points.h"
#include "core/geometry/vec.h"
#include "core/shapes/shapes.h"
#include "core/surface/features.h"

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
  params.max_sides = 100;
  EXPECT_EQ(split_line(std::vector<Point>{{0, 0, 0}, {1, 0, 0}}, UniformSize(1e-3), params)
                .status()
                .code(),
            absl::StatusCode::kResourceExhausted);
}

// The lines of a cube's features, in the surface's local frame, split for h = 0.3: three sides
// each, ends at the corners.
TEST(SplitLine, CubeLinesFromFeatures) {
  absl::StatusOr<DiscreteSurface> s =
      DiscreteSurface::build(box_surface({4, 4, 4}, {5, 5, 5}, 0.25));
  ASSERT_TRUE(s.ok());
  absl::StatusOr<SurfaceFeatures> f = find_surface_features(*s);
  ASSERT_TRUE(f.ok());
  SplitLineParams params;
  params.field_origin = s->origin();
  for (const DiscreteLine& line : f->lines) {
    std::vector<Point> polyline;
    for (Index v : line.vertices) polyline.push_back(s->local_points()[v]);
    const LineSplit split = split_or_die(polyline, UniformSize(0.3), params);
    expect_ends_and_shape(split, polyline);
    EXPECT_EQ(split.points.size(), 4u);
  }
}

}  // namespace
}  // namespace afmesh
