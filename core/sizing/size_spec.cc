#include "core/sizing/size_spec.h"

#include <cmath>
#include <string>

#include "absl/strings/str_cat.h"
#include "core/geometry/predicates.h"

namespace afmesh {
namespace {

absl::Status field_error(const std::string& field, const std::string& what) {
  return absl::InvalidArgumentError(absl::StrCat(field, " ", what));
}

absl::Status check_finite(const std::string& field, double value) {
  if (std::isfinite(value)) return absl::OkStatus();
  return field_error(field, absl::StrCat("must be a finite number, got ", value));
}

// `value` must be finite and > 0.
absl::Status check_positive(const std::string& field, double value) {
  if (absl::Status s = check_finite(field, value); !s.ok()) return s;
  if (value > 0.0) return absl::OkStatus();
  return field_error(field, absl::StrCat("must be > 0, got ", value));
}

// `value` must be finite and >= bound; `why`, when given, is added to the message.
absl::Status check_at_least(const std::string& field, double value, double bound,
                            const char* why = "") {
  if (absl::Status s = check_finite(field, value); !s.ok()) return s;
  if (value >= bound) return absl::OkStatus();
  return field_error(field, absl::StrCat("must be >= ", bound, why, ", got ", value));
}

absl::Status check_point(const std::string& field, const Point& p) {
  static constexpr const char* kAxis[3] = {"x", "y", "z"};
  for (int k = 0; k < 3; ++k) {
    if (!std::isfinite(p[k])) {
      return field_error(absl::StrCat(field, ".", kAxis[k]),
                         absl::StrCat("must be a finite number, got ", p[k]));
    }
  }
  return absl::OkStatus();
}

absl::Status check_law(const std::string& field, const DecayLaw& law) {
  static constexpr const char* kGrows = " (a size must not shrink away from its source)";
  if (std::holds_alternative<NoLaw>(law)) {
    return field_error(field, "has no decay law: give one of power, exponential or polynomial");
  }
  if (const auto* power = std::get_if<PowerLaw>(&law)) {
    return check_positive(field + ".power.gamma", power->gamma);
  }
  if (const auto* exponential = std::get_if<ExponentialLaw>(&law)) {
    return check_at_least(field + ".exponential.gamma", exponential->gamma, 0.0, kGrows);
  }
  const auto& polynomial = std::get<PolynomialLaw>(law);
  for (std::size_t i = 0; i < polynomial.coefficients.size(); ++i) {
    const std::string name = absl::StrCat(field, ".polynomial.coefficients[", i, "]");
    if (absl::Status s = check_at_least(name, polynomial.coefficients[i], 0.0, kGrows); !s.ok()) {
      return s;
    }
  }
  return absl::OkStatus();
}

absl::Status check_source(const std::string& field, const SizeSource& source) {
  const std::size_t n = source.points.size();
  if (n < 1 || n > 3) {
    return field_error(field + ".points",
                       absl::StrCat("must hold 1, 2 or 3 points (point, line or triangle "
                                    "source), got ", n));
  }
  for (std::size_t i = 0; i < n; ++i) {
    if (absl::Status s = check_point(absl::StrCat(field, ".points[", i, "]"), source.points[i]);
        !s.ok()) {
      return s;
    }
  }
  if (absl::Status s = check_positive(field + ".delta0", source.delta0); !s.ok()) return s;
  if (absl::Status s = check_at_least(field + ".r0", source.r0, 0.0); !s.ok()) return s;
  if (absl::Status s = check_positive(field + ".r1", source.r1); !s.ok()) return s;
  return check_law(field, source.law);
}

absl::Status check_tet(const std::string& field, const BackgroundGridSpec& grid, std::size_t t) {
  const Tet& tet = grid.tets[t];
  const Index n = static_cast<Index>(grid.points.size());
  for (int c = 0; c < 4; ++c) {
    if (tet[c] < 0 || tet[c] >= n) {
      return field_error(absl::StrCat(field, ".tets[", t, "][", c, "]"),
                         absl::StrCat("= ", tet[c], " is out of range [0, ", n, ")"));
    }
  }
  const int sign = orient3d(grid.points[tet[0]], grid.points[tet[1]], grid.points[tet[2]],
                            grid.points[tet[3]]);
  const std::string name = absl::StrCat(field, ".tets[", t, "]");
  if (sign < 0) {
    return field_error(name, "is inverted (negative volume): order its points so that "
                             "det[b-a, c-a, d-a] > 0, e.g. swap the last two");
  }
  if (sign == 0) return field_error(name, "is flat (zero volume)");
  return absl::OkStatus();
}

}  // namespace

absl::Status validate_background_grid(const BackgroundGridSpec& grid, const char* field) {
  const std::string f = field;
  if (grid.points.size() < 4) {
    return field_error(f + ".points", absl::StrCat("must hold at least 4 points, got ",
                                                   grid.points.size()));
  }
  if (grid.tets.empty()) return field_error(f + ".tets", "must hold at least 1 tetrahedron");
  if (grid.sizes.size() != grid.points.size()) {
    return field_error(f + ".sizes", absl::StrCat("must hold one size per point: got ",
                                                  grid.sizes.size(), " sizes for ",
                                                  grid.points.size(), " points"));
  }
  for (std::size_t i = 0; i < grid.points.size(); ++i) {
    if (absl::Status s = check_point(absl::StrCat(f, ".points[", i, "]"), grid.points[i]);
        !s.ok()) {
      return s;
    }
    if (absl::Status s = check_positive(absl::StrCat(f, ".sizes[", i, "]"), grid.sizes[i]);
        !s.ok()) {
      return s;
    }
  }
  for (std::size_t t = 0; t < grid.tets.size(); ++t) {
    if (absl::Status s = check_tet(f, grid, t); !s.ok()) return s;
  }
  return absl::OkStatus();
}

absl::Status validate_size_spec(const SizeSpec& spec) {
  if (absl::Status s = check_positive("maxSize", spec.max_size); !s.ok()) return s;
  if (absl::Status s = check_at_least("growth", spec.growth, 1.0); !s.ok()) return s;
  for (std::size_t i = 0; i < spec.sources.size(); ++i) {
    if (absl::Status s = check_source(absl::StrCat("sources[", i, "]"), spec.sources[i]); !s.ok()) {
      return s;
    }
  }
  if (spec.background) return validate_background_grid(*spec.background, "background");
  return absl::OkStatus();
}

}  // namespace afmesh
