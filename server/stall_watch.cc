#include "server/stall_watch.h"

#include <algorithm>

#include "grpcpp/server_context.h"

namespace afmesh::server {

StallWatch::StallWatch(std::chrono::milliseconds timeout)
    : timeout_(timeout), thread_([this] { watch(); }) {}

StallWatch::~StallWatch() {
  {
    std::lock_guard<std::mutex> lock(mu_);
    stopping_ = true;
  }
  wake_.notify_all();
  thread_.join();
}

void StallWatch::started(grpc::ServerContextBase* context, Transfer transfer) {
  std::lock_guard<std::mutex> lock(mu_);
  pending_[{context, transfer}] = Clock::now();
}

void StallWatch::ended(grpc::ServerContextBase* context, Transfer transfer) {
  std::lock_guard<std::mutex> lock(mu_);
  pending_.erase({context, transfer});
}

std::int64_t StallWatch::stalled_reads() const {
  std::lock_guard<std::mutex> lock(mu_);
  return stalled_reads_;
}

std::int64_t StallWatch::stalled_writes() const {
  std::lock_guard<std::mutex> lock(mu_);
  return stalled_writes_;
}

// The calls looked at are the few in flight (bounded by the pool's slots): a scan of all of them
// a few times per timeout costs nothing.
void StallWatch::watch() {
  const auto tick = std::clamp<std::chrono::milliseconds>(
      timeout_ / 4, std::chrono::milliseconds(10), std::chrono::milliseconds(1000));
  std::unique_lock<std::mutex> lock(mu_);
  while (!wake_.wait_for(lock, tick, [this] { return stopping_; })) {
    const Clock::time_point now = Clock::now();
    for (auto it = pending_.begin(); it != pending_.end();) {
      if (now - it->second < timeout_) {
        ++it;
        continue;
      }
      // Still pending, so the call is alive: it ends the transfer (and so erases it here, under
      // this lock) before it can be deleted.
      it->first.first->TryCancel();
      ++(it->first.second == Transfer::kRead ? stalled_reads_ : stalled_writes_);
      it = pending_.erase(it);
    }
  }
}

}  // namespace afmesh::server
