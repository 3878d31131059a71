// The element size wanted in space (paper §4), as one interface the fronts query.
//
// The volume and surface fronts ask a SizeField for delta_bg / delta_s at a point and combine it
// with the sizes attached to the front's points through the growth factor (eq. 15). Sources,
// background grids and their minimum (eq. 1–14) implement this interface.
#pragma once

#include "core/mesh/mesh.h"

namespace afmesh {

class SizeField {
 public:
  virtual ~SizeField() = default;
  // The wanted edge length at x (> 0).
  virtual double size_at(const Point& x) const = 0;
};

// The same size everywhere.
class UniformSize final : public SizeField {
 public:
  explicit UniformSize(double h) : h_(h) {}
  double size_at(const Point&) const override { return h_; }

 private:
  double h_;
};

}  // namespace afmesh
