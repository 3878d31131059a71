#include "core/quality/ring_triangulation.h"

#include <algorithm>

namespace afmesh {

RingTriangulation best_ring_triangulation(int n,
                                          absl::FunctionRef<double(int, int, int)> quality) {
  constexpr double kNone = -std::numeric_limits<double>::infinity();
  RingTriangulation result;
  if (n < 3 || n > kMaxRingSize) return result;
  // best[i][j]: the best smallest quality over triangulations of the sub-polygon i, i+1, .., j
  // (j - i >= 2), and apex[i][j] the corner k of the triangle on its base (i, j) that achieves
  // it. A sub-polygon of two corners (an edge) has no triangle: quality +infinity.
  double best[kMaxRingSize][kMaxRingSize];
  int apex[kMaxRingSize][kMaxRingSize];
  for (int i = 0; i + 1 < n; ++i) best[i][i + 1] = std::numeric_limits<double>::infinity();
  for (int span = 2; span < n; ++span) {
    for (int i = 0; i + span < n; ++i) {
      const int j = i + span;
      best[i][j] = kNone;
      apex[i][j] = -1;
      for (int k = i + 1; k < j; ++k) {
        const double sides = std::min(best[i][k], best[k][j]);
        if (!(sides > best[i][j])) continue;  // cannot beat the best so far: skip quality()
        const double q = std::min(sides, quality(i, k, j));
        if (q > best[i][j]) {
          best[i][j] = q;
          apex[i][j] = k;
        }
      }
    }
  }
  if (!(best[0][n - 1] > kNone)) return result;
  result.quality = best[0][n - 1];
  // Unwind the recursion: the triangle on base (i, j), then its two sides.
  std::vector<std::array<int, 2>> bases = {{0, n - 1}};
  while (!bases.empty()) {
    const auto [i, j] = bases.back();
    bases.pop_back();
    if (j - i < 2) continue;
    const int k = apex[i][j];
    result.triangles.push_back({i, k, j});
    bases.push_back({k, j});
    bases.push_back({i, k});
  }
  return result;
}

}  // namespace afmesh
