// Small builders shared by the sizing tests.
#pragma once

#include <vector>

#include "core/sizing/size_spec.h"

namespace afmesh::sizing_test {

inline SizeSource point_source(const Point& p, double delta0, double r0, double r1,
                               DecayLaw law) {
  return SizeSource{{p}, delta0, r0, r1, std::move(law)};
}

inline SizeSource source_of(std::vector<Point> points, double delta0, double r0, double r1,
                            DecayLaw law) {
  return SizeSource{std::move(points), delta0, r0, r1, std::move(law)};
}

}  // namespace afmesh::sizing_test
