// Compensated (Kahan–Babuška–Neumaier) summation of doubles.
//
// Keeps a running correction term so that the error of a sum of n terms is bounded by about
// one ulp of the result plus n·eps² times the sum of magnitudes, instead of n·eps times it
// (Neumaier 1974). Used wherever a mesh-wide total is compared against a tolerance (volumes) or
// reported (means), so that the figure does not drift with the element count.
#pragma once

#include <cmath>

namespace afmesh {

class CompensatedSum {
 public:
  void add(double x) {
    const double t = sum_ + x;
    if (std::abs(sum_) >= std::abs(x)) {
      correction_ += (sum_ - t) + x;
    } else {
      correction_ += (x - t) + sum_;
    }
    sum_ = t;
  }
  double value() const { return sum_ + correction_; }

 private:
  double sum_ = 0.0;
  double correction_ = 0.0;
};

}  // namespace afmesh
