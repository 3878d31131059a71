// A bounded pool of worker threads for meshing jobs, with admission control.
//
// Capacity is `workers + max_queue` slots. A call reserves a slot when it arrives (before its
// input is uploaded) and holds it until its job has run, so a server that is full says so at
// once (RESOURCE_EXHAUSTED) instead of accepting input it cannot mesh soon. At most `workers`
// jobs run at a time; the others wait in arrival order.
#pragma once

#include <condition_variable>
#include <cstddef>
#include <deque>
#include <mutex>
#include <optional>
#include <thread>
#include <vector>

#include "absl/base/thread_annotations.h"
#include "absl/functional/any_invocable.h"

namespace afmesh::server {

class WorkerPool {
 public:
  // One reserved place in the pool. Move-only; releases the place when destroyed unless it was
  // handed to run().
  class Slot {
   public:
    Slot(Slot&& other) noexcept;
    Slot& operator=(Slot&& other) noexcept;
    Slot(const Slot&) = delete;
    Slot& operator=(const Slot&) = delete;
    ~Slot();

   private:
    friend class WorkerPool;
    explicit Slot(WorkerPool* pool) : pool_(pool) {}
    WorkerPool* pool_;  // null once released or consumed
  };

  // Starts `workers` (>= 1) threads; `max_queue` (>= 0) is the number of reserved slots beyond
  // the workers.
  WorkerPool(int workers, int max_queue);
  // Runs every queued task, then joins the threads. Every Slot must be gone by then.
  ~WorkerPool();
  WorkerPool(const WorkerPool&) = delete;
  WorkerPool& operator=(const WorkerPool&) = delete;

  // A slot, or nullopt when all workers + max_queue slots are reserved.
  std::optional<Slot> try_reserve();

  // Queues `task` to run on a worker; its slot is released when the task returns.
  void run(Slot slot, absl::AnyInvocable<void() &&> task);

  int workers() const { return static_cast<int>(threads_.size()); }
  int max_queue() const { return max_queue_; }

  // How full the pool is, read at one instant (for the metrics' gauges).
  struct Load {
    // Slots held by calls uploading, queued or running (at most workers + max_queue).
    int reserved = 0;
    int queued = 0;   // jobs waiting for a worker
    int running = 0;  // jobs on a worker
  };
  Load load() const;

 private:
  void release_slot();
  void work();
  void task_done();

  const int max_queue_;
  std::vector<std::thread> threads_;
  mutable std::mutex mu_;
  std::condition_variable ready_;
  std::deque<absl::AnyInvocable<void() &&>> tasks_ ABSL_GUARDED_BY(mu_);
  int reserved_ ABSL_GUARDED_BY(mu_) = 0;
  int running_ ABSL_GUARDED_BY(mu_) = 0;
  bool stopping_ ABSL_GUARDED_BY(mu_) = false;
};

}  // namespace afmesh::server
