// Back-off bookkeeping shared by the volume and surface fronts (not in the paper): how often a
// front had to re-open its elements in each region, so that each retry at the same place can
// re-open more. Counted by place, not by point, because re-meshing replaces the points: the
// region of an item of size d at x is its cell in a grid whose spacing is the power of two just
// above 2d.
#pragma once

#include <array>
#include <cmath>
#include <cstdint>

#include "absl/container/flat_hash_map.h"
#include "core/mesh/mesh.h"

namespace afmesh {

class RepairCounts {
 public:
  // The count of the region of an item of size d (> 0) at x, 0 at first.
  int& at(const Point& x, double d) {
    const int level = static_cast<int>(std::ceil(std::log2(2.0 * d)));
    const double cell = std::ldexp(1.0, level);
    std::array<std::int64_t, 4> key{level, 0, 0, 0};
    for (int a = 0; a < 3; ++a) key[a + 1] = static_cast<std::int64_t>(std::floor(x[a] / cell));
    return counts_[key];
  }

 private:
  absl::flat_hash_map<std::array<std::int64_t, 4>, int> counts_;
};

}  // namespace afmesh
