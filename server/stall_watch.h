// Ends calls whose transfer has stalled: a client that stops reading the result stream (or stops
// sending its input) would otherwise keep its finished mesh, its share of the memory budget and
// its pool slot for as long as it likes (issue 12, slow clients). Not in the paper.
//
// A call tells the watch when each read or write starts and ends (OnReadDone/OnWriteDone come
// for every StartRead/StartWrite, even on a broken stream, so every started transfer ends).
// A thread of its own looks a few times per timeout and cancels (ServerContext::TryCancel) a
// call whose transfer has been pending longer than the timeout; gRPC then fails the transfer and
// the call cleans up as for a client cancel.
#pragma once

#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <map>
#include <mutex>
#include <thread>
#include <utility>

#include "absl/base/thread_annotations.h"

namespace grpc {
class ServerContextBase;
}

namespace afmesh::server {

class StallWatch {
 public:
  enum class Transfer { kRead, kWrite };

  // `timeout` > 0. The watch looks every timeout/4 (at least every second, at most every 10 ms).
  explicit StallWatch(std::chrono::milliseconds timeout);
  // Stops the thread; every started transfer must have ended.
  ~StallWatch();
  StallWatch(const StallWatch&) = delete;
  StallWatch& operator=(const StallWatch&) = delete;

  // A transfer of `context`'s call has started / ended.
  void started(grpc::ServerContextBase* context, Transfer transfer);
  void ended(grpc::ServerContextBase* context, Transfer transfer);

  // Calls cancelled for a stalled read / write so far.
  std::int64_t stalled_reads() const;
  std::int64_t stalled_writes() const;

  std::chrono::milliseconds timeout() const { return timeout_; }

 private:
  using Clock = std::chrono::steady_clock;
  using Key = std::pair<grpc::ServerContextBase*, Transfer>;

  void watch();

  const std::chrono::milliseconds timeout_;
  mutable std::mutex mu_;
  std::condition_variable wake_;
  std::map<Key, Clock::time_point> pending_ ABSL_GUARDED_BY(mu_);
  std::int64_t stalled_reads_ ABSL_GUARDED_BY(mu_) = 0;
  std::int64_t stalled_writes_ ABSL_GUARDED_BY(mu_) = 0;
  bool stopping_ ABSL_GUARDED_BY(mu_) = false;
  std::thread thread_;  // last: starts once the members above exist
};

}  // namespace afmesh::server
