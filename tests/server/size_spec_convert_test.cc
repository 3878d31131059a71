// The size specification's JSON / wire form (afmesh.v1.SizeSpec) against core's SizeSpec: the
// design's JSON converts to the spec built by hand, field by field, and back; what the
// conversion rejects is named by its JSON field.
#include <cmath>
#include <string>
#include <variant>

#include "gmock/gmock.h"
#include "google/protobuf/util/json_util.h"
#include "gtest/gtest.h"
#include "proto/size_spec_convert.h"

namespace afmesh {
namespace {

using ::testing::HasSubstr;

// design.md's example, with the background grid inline (one positive tet) instead of a file.
constexpr const char* kDesignSpec = R"({
  "maxSize": 0.8,
  "growth": 1.2,
  "sources": [
    {"points": [{"x": 0, "y": 0, "z": 0}],
     "delta0": 0.15, "r0": 1.0, "r1": 0.2, "polynomial": {"coefficients": [1.0, 0.0]}},
    {"points": [{"x": 0, "y": 0, "z": 0}, {"x": 1, "y": 0, "z": 0}],
     "delta0": 0.1, "r0": 0.0, "r1": 0.5, "power": {"gamma": 1.5}},
    {"points": [{"x": 0, "y": 0, "z": 1}, {"x": 1, "y": 0, "z": 1}, {"x": 0, "y": 1, "z": 1}],
     "delta0": 0.1, "r0": 0.1, "r1": 1.0, "exponential": {"gamma": 0.7}}
  ],
  "background": {"points": [{"x": 0, "y": 0, "z": 0}, {"x": 2, "y": 0, "z": 0},
                            {"x": 0, "y": 2, "z": 0}, {"x": 0, "y": 0, "z": 2}],
                 "tets": [0, 1, 2, 3],
                 "sizes": [0.5, 0.6, 0.7, 0.8]}
})";

SizeSpec design_spec_by_hand() {
  SizeSpec spec;
  spec.max_size = 0.8;
  spec.growth = 1.2;
  spec.sources.push_back({.points = {{0, 0, 0}},
                          .delta0 = 0.15,
                          .r0 = 1.0,
                          .r1 = 0.2,
                          .law = PolynomialLaw{.coefficients = {1.0, 0.0}}});
  spec.sources.push_back({.points = {{0, 0, 0}, {1, 0, 0}},
                          .delta0 = 0.1,
                          .r0 = 0.0,
                          .r1 = 0.5,
                          .law = PowerLaw{.gamma = 1.5}});
  spec.sources.push_back({.points = {{0, 0, 1}, {1, 0, 1}, {0, 1, 1}},
                          .delta0 = 0.1,
                          .r0 = 0.1,
                          .r1 = 1.0,
                          .law = ExponentialLaw{.gamma = 0.7}});
  spec.background = BackgroundGridSpec{.points = {{0, 0, 0}, {2, 0, 0}, {0, 2, 0}, {0, 0, 2}},
                                       .tets = {{0, 1, 2, 3}},
                                       .sizes = {0.5, 0.6, 0.7, 0.8}};
  return spec;
}

// Law kind and parameters, as comparable values.
std::vector<double> law_values(const DecayLaw& law) {
  if (const auto* power = std::get_if<PowerLaw>(&law)) return {1.0, power->gamma};
  if (const auto* exponential = std::get_if<ExponentialLaw>(&law)) return {2.0, exponential->gamma};
  if (const auto* polynomial = std::get_if<PolynomialLaw>(&law)) {
    std::vector<double> values = {3.0};
    values.insert(values.end(), polynomial->coefficients.begin(), polynomial->coefficients.end());
    return values;
  }
  return {0.0};
}

void expect_same_spec(const SizeSpec& actual, const SizeSpec& expected) {
  EXPECT_EQ(actual.max_size, expected.max_size);
  EXPECT_EQ(actual.growth, expected.growth);
  ASSERT_EQ(actual.sources.size(), expected.sources.size());
  for (std::size_t i = 0; i < expected.sources.size(); ++i) {
    SCOPED_TRACE(testing::Message() << "sources[" << i << "]");
    EXPECT_EQ(actual.sources[i].points, expected.sources[i].points);
    EXPECT_EQ(actual.sources[i].delta0, expected.sources[i].delta0);
    EXPECT_EQ(actual.sources[i].r0, expected.sources[i].r0);
    EXPECT_EQ(actual.sources[i].r1, expected.sources[i].r1);
    EXPECT_EQ(actual.sources[i].law.index(), expected.sources[i].law.index());
    EXPECT_EQ(law_values(actual.sources[i].law), law_values(expected.sources[i].law));
  }
  ASSERT_EQ(actual.background.has_value(), expected.background.has_value());
  if (expected.background) {
    EXPECT_EQ(actual.background->points, expected.background->points);
    EXPECT_EQ(actual.background->tets, expected.background->tets);
    EXPECT_EQ(actual.background->sizes, expected.background->sizes);
  }
}

absl::StatusOr<SizeSpec> spec_from_json(const std::string& json) {
  absl::StatusOr<v1::SizeSpec> message = size_spec_proto_from_json(json);
  if (!message.ok()) return message.status();
  return size_spec_from_proto(*message);
}

TEST(SizeSpecConvert, DesignJsonConvertsToTheHandBuiltSpec) {
  absl::StatusOr<SizeSpec> spec = spec_from_json(kDesignSpec);
  ASSERT_TRUE(spec.ok()) << spec.status();
  expect_same_spec(*spec, design_spec_by_hand());
  EXPECT_TRUE(validate_size_spec(*spec).ok()) << validate_size_spec(*spec);
}

TEST(SizeSpecConvert, SpecToJsonAndBackIsTheSameSpec) {
  std::string json;
  ASSERT_TRUE(
      google::protobuf::util::MessageToJsonString(size_spec_to_proto(design_spec_by_hand()), &json)
          .ok());
  for (const char* field : {"\"maxSize\"", "\"growth\"", "\"sources\"", "\"delta0\"", "\"r0\"",
                            "\"r1\"", "\"polynomial\"", "\"coefficients\"", "\"power\"",
                            "\"exponential\"", "\"gamma\"", "\"background\"", "\"tets\"",
                            "\"sizes\""}) {
    EXPECT_THAT(json, HasSubstr(field));
  }
  absl::StatusOr<SizeSpec> spec = spec_from_json(json);
  ASSERT_TRUE(spec.ok()) << spec.status();
  expect_same_spec(*spec, design_spec_by_hand());
}

TEST(SizeSpecConvert, UnsetGrowthIsOneAndEmptyPolynomialStaysAPolynomial) {
  absl::StatusOr<SizeSpec> spec = spec_from_json(
      R"({"maxSize": 1, "sources": [{"points": [{}], "delta0": 0.1, "r1": 1, "polynomial": {}}]})");
  ASSERT_TRUE(spec.ok()) << spec.status();
  EXPECT_EQ(spec->growth, 1.0);
  ASSERT_EQ(spec->sources.size(), 1u);
  EXPECT_TRUE(std::holds_alternative<PolynomialLaw>(spec->sources[0].law));
  EXPECT_EQ(spec->sources[0].points, (std::vector<Point>{{0, 0, 0}}));
  EXPECT_TRUE(std::holds_alternative<PolynomialLaw>(
      size_spec_from_proto(size_spec_to_proto(*spec))->sources[0].law));
}

TEST(SizeSpecConvert, MissingLawBecomesNoLawWhichValidationNames) {
  absl::StatusOr<SizeSpec> spec =
      spec_from_json(R"({"maxSize": 1, "sources": [{"points": [{}], "delta0": 0.1, "r1": 1}]})");
  ASSERT_TRUE(spec.ok()) << spec.status();
  EXPECT_TRUE(std::holds_alternative<NoLaw>(spec->sources[0].law));
  const absl::Status status = validate_size_spec(*spec);
  EXPECT_EQ(status.code(), absl::StatusCode::kInvalidArgument);
  EXPECT_THAT(status.message(), HasSubstr("sources[0]"));
}

TEST(SizeSpecConvert, UnknownLawInJsonIsRejectedNamingIt) {
  const absl::StatusOr<v1::SizeSpec> message = size_spec_proto_from_json(
      R"({"maxSize": 1, "sources": [{"points": [{}], "delta0": 0.1, "r1": 1, "cubic": {}}]})");
  EXPECT_EQ(message.status().code(), absl::StatusCode::kInvalidArgument);
  EXPECT_THAT(message.status().message(), HasSubstr("cubic"));
}

TEST(SizeSpecConvert, JsonNanParsesToNanAndValidationNamesTheField) {
  absl::StatusOr<SizeSpec> spec = spec_from_json(
      R"({"maxSize": 1, "sources": [{"points": [{}], "delta0": "NaN", "r1": 1, "power": {"gamma": 1}}]})");
  ASSERT_TRUE(spec.ok()) << spec.status();
  EXPECT_TRUE(std::isnan(spec->sources[0].delta0));
  EXPECT_THAT(validate_size_spec(*spec).message(), HasSubstr("sources[0].delta0"));
}

TEST(SizeSpecConvert, BackgroundFileIsRejectedSayingTheClientMustSendTheGrid) {
  const absl::StatusOr<SizeSpec> spec =
      spec_from_json(R"({"maxSize": 1, "background": {"file": "background.msh"}})");
  EXPECT_EQ(spec.status().code(), absl::StatusCode::kInvalidArgument);
  EXPECT_THAT(spec.status().message(), HasSubstr("background.file"));
  EXPECT_THAT(spec.status().message(), HasSubstr("servers never open client paths"));
  EXPECT_THAT(spec.status().message(),
              HasSubstr("the client must read the grid file and send the grid itself, in "
                        "MeshVolume's background_grid slices"));
}

TEST(SizeSpecConvert, BackgroundTetsNotFourPerTetAreRejected) {
  const absl::StatusOr<SizeSpec> spec =
      spec_from_json(R"({"maxSize": 1, "background": {"tets": [0, 1, 2, 3, 4]}})");
  EXPECT_EQ(spec.status().code(), absl::StatusCode::kInvalidArgument);
  EXPECT_THAT(spec.status().message(), HasSubstr("background.tets holds 5 indices"));
}

}  // namespace
}  // namespace afmesh
