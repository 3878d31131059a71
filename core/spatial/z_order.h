// Z order (Morton order): a key per point whose order follows a space-filling curve, so that
// points sorted by it lie near their neighbours in the sequence (memory locality of a walk, the
// insertion order of an incremental Delaunay tetrahedralisation).
#pragma once

#include <algorithm>
#include <cstdint>

#include "core/mesh/mesh.h"
#include "core/spatial/box.h"

namespace afmesh {

// The Z-order key of x in `box`: each coordinate scaled to 21 bits over the box's extent on its
// axis (clamped into the box; an axis of no extent gives 0), the bits interleaved from the top,
// x's bit first.
inline std::uint64_t z_order(const Point& x, const Box& box) {
  std::uint32_t q[3];
  for (int a = 0; a < 3; ++a) {
    const double extent = box.hi[a] - box.lo[a];
    const double u = extent > 0.0 ? (x[a] - box.lo[a]) / extent : 0.0;
    q[a] = static_cast<std::uint32_t>(std::clamp(u, 0.0, 1.0) * 2097151.0);
  }
  std::uint64_t key = 0;
  for (int bit = 20; bit >= 0; --bit)
    for (int a = 0; a < 3; ++a) key = key << 1 | (q[a] >> bit & 1u);
  return key;
}

}  // namespace afmesh
