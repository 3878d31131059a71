// Progress reporting and cancellation for long core operations.
//
// The core never owns threads or I/O: a caller (the server, a test, the CLI) passes a Progress
// and the operation calls `cancelled()` often (every few thousand elements at most), returning
// absl::CancelledError as soon as it is true, and `report()` now and then.
#pragma once

#include <string_view>

namespace afmesh {

class Progress {
 public:
  virtual ~Progress() = default;
  // `stage` names the step (e.g. "front"), `fraction` is in [0, 1] or negative when unknown.
  virtual void report(std::string_view stage, double fraction) { (void)stage; (void)fraction; }
  // True once the caller wants the operation to stop.
  virtual bool cancelled() const { return false; }
};

// A Progress that reports nothing and never cancels.
inline Progress& no_progress() {
  static Progress none;  // stateless: safe to share between threads
  return none;
}

}  // namespace afmesh
