// Progress reporting and cancellation for long core operations.
//
// The core never owns threads or I/O: a caller (the server, a test, the CLI) passes a Progress
// and the operation calls `cancelled()` often (every few thousand elements at most), returning
// absl::CancelledError as soon as it is true, and `report()` now and then.
#pragma once

#include <cstdint>
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

// For loops too tight to ask progress.cancelled() on every element: `due()` asks it once every
// `interval` calls and stays true once it was true. Loops over millions of elements use it so
// that a cancelled call stops within milliseconds (issue 12: a worker freed within 100 ms).
class CancelCheck {
 public:
  explicit CancelCheck(const Progress& progress, std::int64_t interval = 4096)
      : progress_(progress), interval_(interval) {}
  bool due() {
    if (stopped_) return true;
    if (++count_ < interval_) return false;
    count_ = 0;
    stopped_ = progress_.cancelled();
    return stopped_;
  }
  // Asks now (between the steps of a loop's caller), whatever the count.
  bool look() {
    count_ = 0;
    if (!stopped_) stopped_ = progress_.cancelled();
    return stopped_;
  }
  // True once a due() or look() found the caller cancelled.
  bool stopped() const { return stopped_; }

 private:
  const Progress& progress_;
  std::int64_t interval_;
  std::int64_t count_ = 0;
  bool stopped_ = false;
};

}  // namespace afmesh
