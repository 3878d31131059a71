// The element size wanted in space (paper §4), as one interface the fronts query.
//
// The volume and surface fronts ask a SizeField for delta_bg / delta_s at a point and combine it
// with the sizes attached to the front's points through the growth factor (eq. 15, see
// attached_sizes.h). Sources, background grids and their minimum (eq. 1–14) implement this
// interface in spec_size_field.h.
#pragma once

#include <algorithm>
#include <cstddef>
#include <span>

#include "core/mesh/mesh.h"

namespace afmesh {

class SizeField {
 public:
  virtual ~SizeField() = default;

  // The wanted edge length at x (> 0, in the units of the points). x must be finite.
  virtual double size_at(const Point& x) const = 0;

  // The sizes at many points: out[i] = size_at(xs[i]), bit for bit, for i < xs.size().
  // `out` must hold xs.size() values. Implementations may evaluate the points in any order or in
  // groups (to vectorise or to share work between nearby points); the default asks size_at.
  virtual void sizes_at(std::span<const Point> xs, std::span<double> out) const {
    for (std::size_t i = 0; i < xs.size(); ++i) out[i] = size_at(xs[i]);
  }
};

// The smaller of two fields' sizes at every point (eq. 14's minimum, of two fields). Both must
// outlive it.
class SmallerOfSizes final : public SizeField {
 public:
  SmallerOfSizes(const SizeField& a, const SizeField& b) : a_(a), b_(b) {}
  double size_at(const Point& x) const override {
    return std::min(a_.size_at(x), b_.size_at(x));
  }

 private:
  const SizeField& a_;
  const SizeField& b_;
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
