// Counts the calls in progress and closes the door on new ones when the server drains.
//
// A graceful stop (SIGTERM) closes the gate, so new calls are refused with UNAVAILABLE and a
// load balancer sends them elsewhere, waits until every admitted call has ended, and only then
// shuts the gRPC server down, so no call in flight is cut short. Calls still in flight when the
// grace period is over are told to stop (abort()): their jobs end, and they finish UNAVAILABLE.
#pragma once

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <mutex>

#include "absl/base/thread_annotations.h"

namespace afmesh::server {

class CallGate {
 public:
  // Admits a call; false once close() was called.
  bool try_enter();
  // An admitted call has ended.
  void leave();
  // Refuses every later try_enter().
  void close();
  // Blocks until no admitted call remains, or `timeout` has passed; true when none remains.
  bool wait_until_empty_for(std::chrono::steady_clock::duration timeout);
  // Asks every admitted call to stop (see aborting()).
  void abort();
  // True once abort() was called: calls stop their jobs and end UNAVAILABLE.
  bool aborting() const { return aborting_.load(std::memory_order_acquire); }
  // When the last admitted call ended (the steady clock's epoch if none has).
  std::chrono::steady_clock::time_point last_leave();
  // Admitted calls that have not ended yet.
  int active() const;
  // True once close() was called (the server is draining).
  bool closed() const;

 private:
  mutable std::mutex mu_;
  std::condition_variable empty_;
  int active_ ABSL_GUARDED_BY(mu_) = 0;
  bool closed_ ABSL_GUARDED_BY(mu_) = false;
  std::atomic<bool> aborting_{false};
  std::chrono::steady_clock::time_point last_leave_ ABSL_GUARDED_BY(mu_);
};

}  // namespace afmesh::server
