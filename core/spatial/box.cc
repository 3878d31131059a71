#include "core/spatial/box.h"

#include <limits>

namespace afmesh {

Box empty_box() {
  constexpr double kInf = std::numeric_limits<double>::infinity();
  return Box{{kInf, kInf, kInf}, {-kInf, -kInf, -kInf}};
}

Box triangle_box(const std::vector<Point>& points, const Triangle& t) {
  Box box = empty_box();
  for (Index v : t) enclose(box, points[v]);
  return box;
}

std::vector<Box> triangle_boxes(const std::vector<Point>& points,
                                const std::vector<Triangle>& triangles) {
  std::vector<Box> boxes;
  boxes.reserve(triangles.size());
  for (const Triangle& t : triangles) boxes.push_back(triangle_box(points, t));
  return boxes;
}

}  // namespace afmesh
