// Not in the paper: the never-hang guard of the volume front's end game (issue 10 part 2).
#pragma once

#include <cstdint>
#include <limits>

namespace afmesh::volume {

// The end game must shrink the front. Once the elements hold all but kShare of the enclosed
// volume, the front may only get smaller; a front whose smallest size is not beaten for
// kSteps + kStepsPerFace × that size fills the last gaps with ever smaller elements and would
// never close (a cube of edges 0.15 at size 0.02, before coarse faces retried their later rules
// at once: the volume meshed after 1M steps, then 800k tets more without end).
class EndGameWatch {
 public:
  static constexpr double kShare = 1e-3;
  static constexpr std::int64_t kSteps = 20000;
  static constexpr std::int64_t kStepsPerFace = 20;

  // True when the end game has stopped making progress. Call once per step, with the volume the
  // elements hold, the enclosed volume and the number of front faces.
  bool stalled(double meshed_volume, double domain_volume, std::int64_t front_size,
               std::int64_t step) {
    if (meshed_volume < domain_volume * (1.0 - kShare)) return false;
    if (front_size < smallest_front_) {
      smallest_front_ = front_size;
      since_ = step;
    }
    return step - since_ > kSteps + kStepsPerFace * smallest_front_;
  }
  std::int64_t smallest_front() const { return smallest_front_; }

 private:
  std::int64_t smallest_front_ = std::numeric_limits<std::int64_t>::max();
  std::int64_t since_ = 0;
};

}  // namespace afmesh::volume
