#include "core/sizing/decay_law.h"

#include <variant>

namespace afmesh {

double decay_size(const SizeSource& source, double r) {
  const double rho = scaled_distance(r, source.r0, source.r1);
  if (const auto* power = std::get_if<PowerLaw>(&source.law)) {
    return law_size(LawKind::kPower, source.delta0, power->gamma, {}, rho);
  }
  if (const auto* exponential = std::get_if<ExponentialLaw>(&source.law)) {
    return law_size(LawKind::kExponential, source.delta0, exponential->gamma, {}, rho);
  }
  const auto& polynomial = std::get<PolynomialLaw>(source.law);
  return law_size(LawKind::kPolynomial, source.delta0, 0.0, polynomial.coefficients, rho);
}

}  // namespace afmesh
