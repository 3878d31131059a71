#include "proto/size_spec_convert.h"

#include <string>

#include "absl/strings/str_cat.h"
#include "google/protobuf/util/json_util.h"

namespace afmesh {
namespace {

Point point_from_proto(const v1::Point3& p) { return {p.x(), p.y(), p.z()}; }

void point_to_proto(const Point& p, v1::Point3& out) {
  out.set_x(p[0]);
  out.set_y(p[1]);
  out.set_z(p[2]);
}

DecayLaw law_from_proto(const v1::SizeSource& source) {
  switch (source.law_case()) {
    case v1::SizeSource::kPower:
      return PowerLaw{.gamma = source.power().gamma()};
    case v1::SizeSource::kExponential:
      return ExponentialLaw{.gamma = source.exponential().gamma()};
    case v1::SizeSource::kPolynomial: {
      const auto& coefficients = source.polynomial().coefficients();
      return PolynomialLaw{.coefficients = {coefficients.begin(), coefficients.end()}};
    }
    case v1::SizeSource::LAW_NOT_SET:
      break;
  }
  return NoLaw{};
}

SizeSource source_from_proto(const v1::SizeSource& source) {
  SizeSource out{.points = {},
                 .delta0 = source.delta0(),
                 .r0 = source.r0(),
                 .r1 = source.r1(),
                 .law = law_from_proto(source)};
  for (const v1::Point3& p : source.points()) out.points.push_back(point_from_proto(p));
  return out;
}

absl::StatusOr<BackgroundGridSpec> background_from_proto(const v1::BackgroundGrid& grid) {
  if (!grid.file().empty()) {
    return absl::InvalidArgumentError(absl::StrCat(
        "background.file (\"", grid.file(),
        "\"): servers never open client paths; the client must read the grid file and send the "
        "grid itself, in MeshVolume's background_grid slices (or inline as background.points, "
        "background.tets, background.sizes), as the afmesh CLI does"));
  }
  if (grid.tets_size() % 4 != 0) {
    return absl::InvalidArgumentError(
        absl::StrCat("background.tets holds ", grid.tets_size(),
                     " indices, not four per tet (a0, b0, c0, d0, a1, ...)"));
  }
  BackgroundGridSpec out;
  for (const v1::Point3& p : grid.points()) out.points.push_back(point_from_proto(p));
  for (int i = 0; i < grid.tets_size(); i += 4) {
    out.tets.push_back({grid.tets(i), grid.tets(i + 1), grid.tets(i + 2), grid.tets(i + 3)});
  }
  out.sizes.assign(grid.sizes().begin(), grid.sizes().end());
  return out;
}

void law_to_proto(const DecayLaw& law, v1::SizeSource& out) {
  if (const auto* power = std::get_if<PowerLaw>(&law)) {
    out.mutable_power()->set_gamma(power->gamma);
  } else if (const auto* exponential = std::get_if<ExponentialLaw>(&law)) {
    out.mutable_exponential()->set_gamma(exponential->gamma);
  } else if (const auto* polynomial = std::get_if<PolynomialLaw>(&law)) {
    // Set even when empty: no coefficients is the constant law delta0.
    v1::PolynomialLaw& message = *out.mutable_polynomial();
    for (const double a : polynomial->coefficients) message.add_coefficients(a);
  }
}

}  // namespace

absl::StatusOr<SizeSpec> size_spec_from_proto(const v1::SizeSpec& message) {
  SizeSpec spec;
  spec.max_size = message.max_size();
  spec.growth = message.growth() == 0.0 ? 1.0 : message.growth();
  for (const v1::SizeSource& source : message.sources()) {
    spec.sources.push_back(source_from_proto(source));
  }
  if (message.has_background()) {
    absl::StatusOr<BackgroundGridSpec> grid = background_from_proto(message.background());
    if (!grid.ok()) return grid.status();
    spec.background = *std::move(grid);
  }
  return spec;
}

v1::SizeSpec size_spec_to_proto(const SizeSpec& spec) {
  v1::SizeSpec out;
  out.set_max_size(spec.max_size);
  out.set_growth(spec.growth);
  for (const SizeSource& source : spec.sources) {
    v1::SizeSource& s = *out.add_sources();
    for (const Point& p : source.points) point_to_proto(p, *s.add_points());
    s.set_delta0(source.delta0);
    s.set_r0(source.r0);
    s.set_r1(source.r1);
    law_to_proto(source.law, s);
  }
  if (spec.background) {
    v1::BackgroundGrid& grid = *out.mutable_background();
    for (const Point& p : spec.background->points) point_to_proto(p, *grid.add_points());
    for (const Tet& tet : spec.background->tets) {
      for (const Index i : tet) grid.add_tets(i);
    }
    for (const double size : spec.background->sizes) grid.add_sizes(size);
  }
  return out;
}

absl::StatusOr<v1::SizeSpec> size_spec_proto_from_json(std::string_view json) {
  v1::SizeSpec message;
  const google::protobuf::util::Status status = google::protobuf::util::JsonStringToMessage(
      google::protobuf::StringPiece(json.data(), json.size()), &message);
  if (!status.ok()) {
    return absl::InvalidArgumentError(
        std::string(status.message().data(), status.message().size()));
  }
  return message;
}

}  // namespace afmesh
