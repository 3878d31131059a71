// The size field of a specification: minimum of sources, max_size and background (eq. 14);
// pruning and batch evaluation give exactly the same doubles as evaluating every source.
#include "core/sizing/spec_size_field.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "core/geometry/vec.h"
#include "tests/sizing/sizing_test_util.h"

namespace afmesh {
namespace {

using sizing_test::point_source;
using sizing_test::source_of;

const Box kUnitBox{{0, 0, 0}, {1, 1, 1}};

SpecSizeField make_field(const SizeSpec& spec, const Box& domain = kUnitBox,
                         const SpecSizeFieldParams& params = {}) {
  absl::StatusOr<SpecSizeField> field = SpecSizeField::create(spec, domain, params);
  EXPECT_TRUE(field.ok()) << field.status();
  return *std::move(field);
}

TEST(SpecSizeField, WithoutSourcesTheSizeIsMaxSizeEverywhere) {
  SizeSpec spec;
  spec.max_size = 0.8;
  const SpecSizeField field = make_field(spec);
  for (const Point& x : {Point{0.5, 0.5, 0.5}, Point{0, 0, 0}, Point{7, -3, 2}}) {
    EXPECT_EQ(field.size_at(x), 0.8);
  }
  EXPECT_EQ(field.background().tets().size(), 5u);
}

TEST(SpecSizeField, IsTheMinimumOfSeveralSourcesCappedByMaxSize) {
  SizeSpec spec;
  spec.max_size = 1.0;
  // delta 0.1 (1 + r / 0.5) around (0,0,0) and 0.2 (1 + r / 0.5) along x = 1, y = 0.
  spec.sources = {point_source({0, 0, 0}, 0.1, 0.0, 0.5, PolynomialLaw{{1.0}}),
                  source_of({{1, 0, 0}, {1, 0, 1}}, 0.2, 0.0, 0.5, PolynomialLaw{{1.0}})};
  const SpecSizeField field = make_field(spec);
  EXPECT_NEAR(field.size_at({0, 0, 0}), 0.1, 1e-15);                 // source 0
  EXPECT_NEAR(field.size_at({1, 0, 0.5}), 0.2, 1e-15);               // source 1: 0.1 * 3.24 > 0.2
  EXPECT_NEAR(field.size_at({0.5, 0, 0}), 0.2, 1e-15);               // source 0: 0.2 < 0.4
  EXPECT_NEAR(field.size_at({0.3, 0, 0}), 0.1 * (1 + 0.6), 1e-15);   // source 0 wins
  EXPECT_NEAR(field.size_at({0.9, 0.1, 0.5}), 0.2 * (1 + 2 * std::hypot(0.1, 0.1)), 1e-15);
  EXPECT_EQ(field.size_at({0, 5, 0}), 1.0);                          // both above max_size
}

TEST(SpecSizeField, BackgroundGridJoinsTheMinimum) {
  SizeSpec spec;
  spec.max_size = 2.0;
  spec.sources = {point_source({0, 0, 0}, 0.1, 0.0, 0.1, PowerLaw{1.0})};
  // One tet with size 0.5 at its origin corner and 1.5 elsewhere.
  spec.background = BackgroundGridSpec{{{0, 0, 0}, {3, 0, 0}, {0, 3, 0}, {0, 0, 3}},
                                       {{0, 1, 2, 3}},
                                       {0.5, 1.5, 1.5, 1.5}};
  const SpecSizeField field = make_field(spec);
  EXPECT_NEAR(field.size_at({0.05, 0, 0}), 0.15, 1e-15);               // the source
  EXPECT_NEAR(field.size_at({0.6, 0.6, 0}), 0.5 + 1.2 / 3.0, 1e-15);   // the grid: 0.9 < 1.3
  EXPECT_EQ(field.size_at({10, 10, 10}), 1.5);                         // nearest grid point
}

// A random valid source: 1, 2 or 3 points near the unit cube, a random law.
SizeSource random_source(std::mt19937& rng) {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const auto near_cube = [&] {
    return Point{1.4 * u(rng) - 0.2, 1.4 * u(rng) - 0.2, 1.4 * u(rng) - 0.2};
  };
  SizeSource s;
  const int points = 1 + static_cast<int>(3 * u(rng));
  s.points.push_back(near_cube());
  for (int i = 1; i < points; ++i) {
    s.points.push_back(add(s.points[0], scale(sub(near_cube(), s.points[0]), 0.2)));
  }
  s.delta0 = 0.005 + 0.05 * u(rng);
  s.r0 = 0.05 * u(rng);
  s.r1 = 0.02 + 0.1 * u(rng);
  switch (static_cast<int>(3 * u(rng))) {
    case 0: s.law = PowerLaw{1.0 + u(rng)}; break;
    case 1: s.law = ExponentialLaw{0.5 + u(rng)}; break;
    default: s.law = PolynomialLaw{{u(rng), u(rng)}}; break;
  }
  return s;
}

std::vector<Point> random_points(std::mt19937& rng, int n) {
  std::uniform_real_distribution<double> u(-0.1, 1.1);  // some outside the domain's cells
  std::vector<Point> points(n);
  for (Point& p : points) p = {u(rng), u(rng), u(rng)};
  return points;
}

TEST(SpecSizeField, PruningGivesBitIdenticalResults) {
  std::mt19937 rng(42);
  for (int sources : {1, 7, 60, 400}) {
    SizeSpec spec;
    spec.max_size = 0.3;
    for (int i = 0; i < sources; ++i) spec.sources.push_back(random_source(rng));
    const SpecSizeField pruned = make_field(spec);
    const SpecSizeField full = make_field(spec, kUnitBox, {.prune_sources = false});
    ASSERT_GT(pruned.cells().cell_count(), 0);
    ASSERT_EQ(full.cells().cell_count(), 0);
    const std::vector<Point> xs = random_points(rng, 3000);
    for (const Point& x : xs) {
      // Reference: every source, one at a time.
      double reference = 0.3;
      for (Index s = 0; s < full.sources().count(); ++s) {
        reference = std::min(reference, full.sources().size(s, x));
      }
      ASSERT_EQ(pruned.size_at(x), reference) << sources << " sources";
      ASSERT_EQ(full.size_at(x), reference) << sources << " sources";
    }
  }
}

TEST(SpecSizeField, PruningSkipsMostOfManySources) {
  std::mt19937 rng(9);
  SizeSpec spec;
  spec.max_size = 0.3;
  for (int i = 0; i < 400; ++i) spec.sources.push_back(random_source(rng));
  const SpecSizeField field = make_field(spec);
  std::int64_t kept = 0;
  for (Index c = 0; c < field.cells().cell_count(); ++c) kept += field.cells().sources(c).size();
  EXPECT_LT(kept, field.cells().cell_count() * 400 / 4);
}

TEST(SpecSizeField, BatchEqualsSinglePointsBitForBit) {
  std::mt19937 rng(17);
  SizeSpec spec;
  spec.max_size = 0.25;
  for (int i = 0; i < 150; ++i) spec.sources.push_back(random_source(rng));
  // A tight cluster of like sources: cells away from it keep nearly all of them.
  std::uniform_real_distribution<double> jitter(-0.01, 0.01);
  for (int i = 0; i < 100; ++i) {
    spec.sources.push_back(point_source({0.5 + jitter(rng), 0.5 + jitter(rng), 0.5 + jitter(rng)},
                                        0.02, 0.0, 0.1, PowerLaw{1.5}));
  }
  spec.background = BackgroundGridSpec{{{-1, -1, -1}, {3, -1, -1}, {-1, 3, -1}, {-1, -1, 3}},
                                       {{0, 1, 2, 3}},
                                       {0.05, 0.4, 0.3, 0.2}};
  for (const bool prune : {true, false}) {
    const SpecSizeField field = make_field(spec, kUnitBox, {.prune_sources = prune});
    if (prune) {  // some cells keep enough sources for the gathered block path
      std::size_t most = 0;
      for (Index c = 0; c < field.cells().cell_count(); ++c) {
        most = std::max(most, field.cells().sources(c).size());
      }
      ASSERT_GE(most, 4u * SourceSet::kBlock);
    }
    // Many points (several per cell: the gathered block path) and a few (point by point).
    for (int n : {20000, 5}) {
      const std::vector<Point> xs = random_points(rng, n);
      std::vector<double> batch(xs.size());
      field.sizes_at(xs, batch);
      for (std::size_t i = 0; i < xs.size(); ++i) ASSERT_EQ(batch[i], field.size_at(xs[i])) << i;
    }
  }
}

TEST(SpecSizeField, CopiesAndMovesAnswerTheSame) {
  std::mt19937 rng(5);
  SizeSpec spec;
  spec.max_size = 0.3;
  for (int i = 0; i < 30; ++i) spec.sources.push_back(random_source(rng));
  const SpecSizeField field = make_field(spec);
  SpecSizeField copy = field;
  SpecSizeField moved = std::move(copy);
  for (const Point& x : random_points(rng, 200)) EXPECT_EQ(moved.size_at(x), field.size_at(x));
}

TEST(SpecSizeField, CreateRejectsInvalidSpecsAndDomains) {
  SizeSpec spec;
  spec.max_size = 0.5;
  spec.sources = {point_source({0, 0, 0}, 0.1, 0.0, -1.0, PowerLaw{1.0})};
  EXPECT_EQ(SpecSizeField::create(spec, kUnitBox).status().message(),
            "sources[0].r1 must be > 0, got -1");
  spec.sources.clear();
  EXPECT_EQ(SpecSizeField::create(spec, empty_box()).status().code(),
            absl::StatusCode::kInvalidArgument);
  // A single-point domain still gets a default grid (grown by max_size).
  const SpecSizeField point = make_field(spec, Box{{1, 1, 1}, {1, 1, 1}});
  EXPECT_EQ(point.size_at({1, 1, 1}), 0.5);
}

}  // namespace
}  // namespace afmesh
