#include "server/call_gate.h"

namespace afmesh::server {

bool CallGate::try_enter() {
  std::lock_guard<std::mutex> lock(mu_);
  if (closed_) return false;
  ++active_;
  return true;
}

void CallGate::leave() {
  std::lock_guard<std::mutex> lock(mu_);
  last_leave_ = std::chrono::steady_clock::now();
  if (--active_ == 0) empty_.notify_all();
}

void CallGate::close() {
  std::lock_guard<std::mutex> lock(mu_);
  closed_ = true;
}

bool CallGate::wait_until_empty_for(std::chrono::steady_clock::duration timeout) {
  std::unique_lock<std::mutex> lock(mu_);
  return empty_.wait_for(lock, timeout, [this] { return active_ == 0; });
}

void CallGate::abort() { aborting_.store(true, std::memory_order_release); }

std::chrono::steady_clock::time_point CallGate::last_leave() {
  std::lock_guard<std::mutex> lock(mu_);
  return last_leave_;
}

int CallGate::active() const {
  std::lock_guard<std::mutex> lock(mu_);
  return active_;
}

bool CallGate::closed() const {
  std::lock_guard<std::mutex> lock(mu_);
  return closed_;
}

}  // namespace afmesh::server
