#include "core/io/exact_point_merger.h"

#include <bit>

namespace afmesh {

ExactPointMerger::ExactPointMerger(std::vector<Point>& points, std::size_t expected_points)
    : points_(points) {
  index_of_.reserve(expected_points);
  points_.reserve(points_.size() + expected_points);
}

Index ExactPointMerger::insert(double x, double y, double z) {
  // Adding +0.0 turns -0.0 into +0.0 and leaves every other value unchanged.
  x += 0.0;
  y += 0.0;
  z += 0.0;
  const Key key = {std::bit_cast<std::uint64_t>(x), std::bit_cast<std::uint64_t>(y),
                   std::bit_cast<std::uint64_t>(z)};
  const auto [it, inserted] = index_of_.try_emplace(key, static_cast<Index>(points_.size()));
  if (inserted) points_.push_back({x, y, z});
  return it->second;
}

}  // namespace afmesh
