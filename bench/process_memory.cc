#include "bench/process_memory.h"

#include <fstream>
#include <sstream>
#include <string>

#include "absl/status/status.h"
#include "absl/strings/str_cat.h"

namespace afmesh::bench {
namespace {

constexpr char kStatusPath[] = "/proc/self/status";
constexpr char kClearRefsPath[] = "/proc/self/clear_refs";

// Value in bytes of a "Key:   1234 kB" line of /proc/self/status; -1 when `line` is not `key`.
std::int64_t kilobyte_field(const std::string& line, const std::string& key) {
  if (line.compare(0, key.size(), key) != 0 || line.size() <= key.size() ||
      line[key.size()] != ':')
    return -1;
  std::istringstream fields(line.substr(key.size() + 1));
  std::int64_t kilobytes = -1;
  fields >> kilobytes;
  return kilobytes < 0 ? -1 : kilobytes * 1024;
}

}  // namespace

absl::StatusOr<ResidentMemory> read_resident_memory() {
  std::ifstream status(kStatusPath);
  if (!status) return absl::NotFoundError(absl::StrCat("cannot open ", kStatusPath));
  ResidentMemory m{-1, -1};
  for (std::string line; std::getline(status, line);) {
    if (const std::int64_t v = kilobyte_field(line, "VmRSS"); v >= 0) m.current_bytes = v;
    if (const std::int64_t v = kilobyte_field(line, "VmHWM"); v >= 0) m.peak_bytes = v;
  }
  if (m.current_bytes < 0 || m.peak_bytes < 0)
    return absl::NotFoundError(absl::StrCat(kStatusPath, " has no VmRSS/VmHWM lines"));
  return m;
}

absl::Status reset_peak_resident_memory() {
  std::ofstream clear_refs(kClearRefsPath);
  clear_refs << "5";
  clear_refs.flush();
  if (!clear_refs)
    return absl::FailedPreconditionError(
        absl::StrCat("cannot write 5 to ", kClearRefsPath, " to reset VmHWM"));
  return absl::OkStatus();
}

void PeakMemoryProbe::start() {
  peak_was_reset_ = reset_peak_resident_memory().ok();
  absl::StatusOr<ResidentMemory> start = read_resident_memory();
  if (!start.ok()) {
    status_ = start.status();
    return;
  }
  start_ = *start;
  status_ = absl::OkStatus();
}

void PeakMemoryProbe::finish() {
  if (!status_.ok()) return;
  absl::StatusOr<ResidentMemory> end = read_resident_memory();
  if (!end.ok()) {
    status_ = end.status();
    return;
  }
  end_ = *end;
}

}  // namespace afmesh::bench
