// Resident memory of the calling process, read from Linux's /proc/self/status, for the
// benchmarks' bytes-per-element figures.
//
//   VmRSS  resident set size now
//   VmHWM  peak resident set size ("high water mark") since the process started or since the
//          mark was last reset
//
// Figures are bytes. Outside Linux, or when /proc is not mounted, reads fail with NOT_FOUND.
#pragma once

#include <cstdint>

#include "absl/status/statusor.h"

namespace afmesh::bench {

struct ResidentMemory {
  std::int64_t current_bytes = 0;  // VmRSS
  std::int64_t peak_bytes = 0;     // VmHWM
};

// VmRSS and VmHWM of this process.
absl::StatusOr<ResidentMemory> read_resident_memory();

// Resets VmHWM to the current VmRSS (writes "5" to /proc/self/clear_refs, Linux >= 4.0), so that
// a later peak covers only what follows. FAILED_PRECONDITION when the kernel refuses.
absl::Status reset_peak_resident_memory();

// Measures the peak resident memory of one phase of the process:
//   PeakMemoryProbe probe;  probe.start();  ...work...  probe.finish();
// `growth_bytes()` is then peak during the phase minus resident memory at its start, the memory
// the phase needed beyond what the process already held. When VmHWM could not be reset,
// `peak_was_reset()` is false and the figure is an upper bound (an earlier peak may be in it).
class PeakMemoryProbe {
 public:
  // Resets VmHWM and reads the resident memory at the start of the phase.
  void start();
  // Reads the peak at the end of the phase.
  void finish();

  bool ok() const { return status_.ok(); }
  const absl::Status& status() const { return status_; }
  bool peak_was_reset() const { return peak_was_reset_; }
  std::int64_t start_bytes() const { return start_.current_bytes; }
  std::int64_t peak_bytes() const { return end_.peak_bytes; }
  std::int64_t growth_bytes() const { return end_.peak_bytes - start_.current_bytes; }

 private:
  absl::Status status_ = absl::FailedPreconditionError("the memory probe was not started");
  bool peak_was_reset_ = false;
  ResidentMemory start_;
  ResidentMemory end_;
};

}  // namespace afmesh::bench
