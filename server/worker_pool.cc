#include "server/worker_pool.h"

#include <utility>

namespace afmesh::server {

WorkerPool::Slot::Slot(Slot&& other) noexcept : pool_(std::exchange(other.pool_, nullptr)) {}

WorkerPool::Slot& WorkerPool::Slot::operator=(Slot&& other) noexcept {
  if (this != &other) {
    if (pool_ != nullptr) pool_->release_slot();
    pool_ = std::exchange(other.pool_, nullptr);
  }
  return *this;
}

WorkerPool::Slot::~Slot() {
  if (pool_ != nullptr) pool_->release_slot();
}

WorkerPool::WorkerPool(int workers, int max_queue) : max_queue_(max_queue < 0 ? 0 : max_queue) {
  const int count = workers < 1 ? 1 : workers;
  threads_.reserve(count);
  for (int i = 0; i < count; ++i) threads_.emplace_back([this] { work(); });
}

WorkerPool::~WorkerPool() {
  {
    std::lock_guard<std::mutex> lock(mu_);
    stopping_ = true;
  }
  ready_.notify_all();
  for (std::thread& thread : threads_) thread.join();
}

std::optional<WorkerPool::Slot> WorkerPool::try_reserve() {
  std::lock_guard<std::mutex> lock(mu_);
  if (stopping_ || reserved_ >= workers() + max_queue_) return std::nullopt;
  ++reserved_;
  return Slot(this);
}

void WorkerPool::run(Slot slot, absl::AnyInvocable<void() &&> task) {
  slot.pool_ = nullptr;  // the worker releases the place once the task has run
  {
    std::lock_guard<std::mutex> lock(mu_);
    tasks_.push_back(std::move(task));
  }
  ready_.notify_one();
}

WorkerPool::Load WorkerPool::load() const {
  std::lock_guard<std::mutex> lock(mu_);
  return Load{
      .reserved = reserved_, .queued = static_cast<int>(tasks_.size()), .running = running_};
}

void WorkerPool::release_slot() {
  std::lock_guard<std::mutex> lock(mu_);
  --reserved_;
}

// A task has returned: its worker is free and its slot released.
void WorkerPool::task_done() {
  std::lock_guard<std::mutex> lock(mu_);
  --running_;
  --reserved_;
}

// Worker loop: takes tasks in arrival order until the pool stops and the queue is empty.
void WorkerPool::work() {
  for (;;) {
    absl::AnyInvocable<void() &&> task;
    {
      std::unique_lock<std::mutex> lock(mu_);
      ready_.wait(lock, [this] { return stopping_ || !tasks_.empty(); });
      if (tasks_.empty()) return;
      task = std::move(tasks_.front());
      tasks_.pop_front();
      ++running_;
    }
    std::move(task)();
    task_done();
  }
}

}  // namespace afmesh::server
