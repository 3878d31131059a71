// Validation of size specifications: every error names the offending source or field.
#include "core/sizing/size_spec.h"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <limits>
#include <string>

#include "tests/sizing/sizing_test_util.h"

namespace afmesh {
namespace {

using sizing_test::source_of;

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// The example of design.md ("Size specification"), with an inline background grid.
SizeSpec example_spec() {
  SizeSpec spec;
  spec.max_size = 0.8;
  spec.growth = 1.2;
  spec.sources = {source_of({{0, 0, 0}}, 0.15, 1.0, 0.2, PolynomialLaw{{1.0, 0.0}}),
                  source_of({{0, 0, 0}, {1, 0, 0}}, 0.1, 0.0, 0.5, PowerLaw{1.5}),
                  source_of({{0, 0, 1}, {1, 0, 1}, {0, 1, 1}}, 0.1, 0.1, 1.0, ExponentialLaw{0.7}),
                  source_of({{2, 2, 2}}, 0.3, 0.0, 1.0, PowerLaw{1.0})};
  spec.background = BackgroundGridSpec{
      {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {1, 1, 1}}, {{0, 1, 2, 3}, {1, 2, 3, 4}},
      {0.5, 0.5, 0.5, 0.5, 0.7}};
  return spec;
}

// The message of validating the example after `edit`.
std::string error_after(const std::function<void(SizeSpec&)>& edit) {
  SizeSpec spec = example_spec();
  edit(spec);
  const absl::Status status = validate_size_spec(spec);
  EXPECT_EQ(status.code(), absl::StatusCode::kInvalidArgument);
  return std::string(status.message());
}

TEST(SizeSpec, TheDesignExampleIsValid) {
  EXPECT_TRUE(validate_size_spec(example_spec()).ok()) << validate_size_spec(example_spec());
}

TEST(SizeSpec, TopLevelErrorsNameTheField) {
  EXPECT_EQ(error_after([](SizeSpec& s) { s.max_size = 0; }), "maxSize must be > 0, got 0");
  EXPECT_EQ(error_after([](SizeSpec& s) { s.max_size = -2; }), "maxSize must be > 0, got -2");
  EXPECT_EQ(error_after([](SizeSpec& s) { s.max_size = kNaN; }),
            "maxSize must be a finite number, got nan");
  EXPECT_EQ(error_after([](SizeSpec& s) { s.growth = 0.5; }), "growth must be >= 1, got 0.5");
}

TEST(SizeSpec, SourceErrorsNameTheSourceAndField) {
  EXPECT_EQ(error_after([](SizeSpec& s) { s.sources[3].r1 = -1; }),
            "sources[3].r1 must be > 0, got -1");
  EXPECT_EQ(error_after([](SizeSpec& s) { s.sources[1].r1 = 0; }),
            "sources[1].r1 must be > 0, got 0");
  EXPECT_EQ(error_after([](SizeSpec& s) { s.sources[0].delta0 = -0.1; }),
            "sources[0].delta0 must be > 0, got -0.1");
  EXPECT_EQ(error_after([](SizeSpec& s) { s.sources[2].delta0 = 0; }),
            "sources[2].delta0 must be > 0, got 0");
  EXPECT_EQ(error_after([](SizeSpec& s) { s.sources[2].r0 = kNaN; }),
            "sources[2].r0 must be a finite number, got nan");
  EXPECT_EQ(error_after([](SizeSpec& s) { s.sources[2].r0 = -1; }),
            "sources[2].r0 must be >= 0, got -1");
  EXPECT_EQ(error_after([](SizeSpec& s) { s.sources[1].points[1][1] = kNaN; }),
            "sources[1].points[1].y must be a finite number, got nan");
  EXPECT_EQ(error_after([](SizeSpec& s) { s.sources[2].points.push_back({1, 1, 1}); }),
            "sources[2].points must hold 1, 2 or 3 points (point, line or triangle source), got 4");
  EXPECT_EQ(error_after([](SizeSpec& s) { s.sources[0].points.clear(); }),
            "sources[0].points must hold 1, 2 or 3 points (point, line or triangle source), got 0");
}

TEST(SizeSpec, LawErrorsNameTheLawAndParameter) {
  EXPECT_EQ(error_after([](SizeSpec& s) { s.sources[3].law = NoLaw{}; }),
            "sources[3] has no decay law: give one of power, exponential or polynomial");
  EXPECT_EQ(error_after([](SizeSpec& s) { s.sources[1].law = PowerLaw{0}; }),
            "sources[1].power.gamma must be > 0, got 0");
  EXPECT_EQ(error_after([](SizeSpec& s) { s.sources[2].law = ExponentialLaw{-1}; }),
            "sources[2].exponential.gamma must be >= 0 (a size must not shrink away from its "
            "source), got -1");
  EXPECT_EQ(error_after([](SizeSpec& s) { s.sources[0].law = PolynomialLaw{{1, -0.5}}; }),
            "sources[0].polynomial.coefficients[1] must be >= 0 (a size must not shrink away "
            "from its source), got -0.5");
  EXPECT_EQ(error_after([](SizeSpec& s) { s.sources[0].law = PolynomialLaw{{kNaN}}; }),
            "sources[0].polynomial.coefficients[0] must be a finite number, got nan");
}

TEST(SizeSpec, BackgroundErrorsNameTheField) {
  EXPECT_EQ(error_after([](SizeSpec& s) { s.background->tets[1][3] = 5; }),
            "background.tets[1][3] = 5 is out of range [0, 5)");
  EXPECT_EQ(error_after([](SizeSpec& s) { s.background->tets[0][0] = -1; }),
            "background.tets[0][0] = -1 is out of range [0, 5)");
  EXPECT_EQ(error_after([](SizeSpec& s) { std::swap(s.background->tets[0][0],
                                                    s.background->tets[0][1]); }),
            "background.tets[0] is inverted (negative volume): order its points so that "
            "det[b-a, c-a, d-a] > 0, e.g. swap the last two");
  EXPECT_EQ(error_after([](SizeSpec& s) { s.background->tets[0][3] = 0; }),
            "background.tets[0] is flat (zero volume)");
  EXPECT_EQ(error_after([](SizeSpec& s) { s.background->sizes.push_back(1.0); }),
            "background.sizes must hold one size per point: got 6 sizes for 5 points");
  EXPECT_EQ(error_after([](SizeSpec& s) { s.background->sizes[4] = -0.7; }),
            "background.sizes[4] must be > 0, got -0.7");
  EXPECT_EQ(error_after([](SizeSpec& s) { s.background->points[2][2] = kNaN; }),
            "background.points[2].z must be a finite number, got nan");
  EXPECT_EQ(error_after([](SizeSpec& s) { s.background->tets.clear(); }),
            "background.tets must hold at least 1 tetrahedron");
}

}  // namespace
}  // namespace afmesh
