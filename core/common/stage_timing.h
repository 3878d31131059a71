// The wall time of one stage of a meshing job (validate, front, optimise, ...), as the core
// reports it in every result and the server streams it in the Summary.
#pragma once

#include <chrono>
#include <string>
#include <vector>

namespace afmesh {

struct StageTiming {
  std::string stage;   // e.g. "validate", "front", "optimise"
  double seconds = 0;  // wall time
};

// Appends one StageTiming per lap: the wall time since the previous lap (or construction).
class StageClock {
 public:
  explicit StageClock(std::vector<StageTiming>& out) : out_(out) {}
  void lap(const char* stage) {
    const auto now = std::chrono::steady_clock::now();
    out_.push_back({stage, std::chrono::duration<double>(now - start_).count()});
    start_ = now;
  }

 private:
  std::vector<StageTiming>& out_;
  std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();
};

}  // namespace afmesh
