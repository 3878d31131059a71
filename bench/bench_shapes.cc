#include "bench/bench_shapes.h"

#include <cmath>

#include "absl/status/status.h"
#include "absl/strings/str_cat.h"
#include "absl/strings/str_join.h"
#include "core/shapes/shapes.h"

namespace afmesh::bench {
namespace {

constexpr double kTorusMajorRadius = 1.0;
constexpr double kTorusMinorRadius = 0.35;
constexpr double kLBlockUnit = 0.5;

}  // namespace

std::vector<std::string> bench_shape_names() { return {"sphere", "torus", "box", "lblock"}; }

std::string bench_shape_description(std::string_view name) {
  if (name == "sphere") return "sphere, radius 1";
  if (name == "torus") return "torus, R = 1, r = 0.35";
  if (name == "box") return "unit cube";
  if (name == "lblock") return "L-block with hole, unit 0.5";
  return "";
}

absl::StatusOr<Mesh> bench_surface(std::string_view name, double h) {
  if (!(h > 0.0) || !std::isfinite(h))
    return absl::InvalidArgumentError(absl::StrCat("size h must be > 0, got ", h));
  if (name == "sphere") return sphere_surface({0.0, 0.0, 0.0}, 1.0, h);
  if (name == "torus") return torus_surface(kTorusMajorRadius, kTorusMinorRadius, h);
  if (name == "box") return box_surface({0.0, 0.0, 0.0}, {1.0, 1.0, 1.0}, h);
  if (name == "lblock") return l_block_with_hole_surface(kLBlockUnit, h);
  return absl::InvalidArgumentError(absl::StrCat("unknown shape '", std::string(name), "'; known shapes: ",
                                                 absl::StrJoin(bench_shape_names(), ", ")));
}

}  // namespace afmesh::bench
