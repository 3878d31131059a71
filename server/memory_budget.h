// The server's memory budget across concurrent jobs: a job is admitted by the bytes it is
// expected to need (core/volume/estimate_elements.h), not only by a free worker, so that two
// large jobs that would each fit do not run out of memory together (issue 12, part 1).
#pragma once

#include <cstdint>
#include <mutex>
#include <optional>

#include "absl/base/thread_annotations.h"

namespace afmesh::server {

class MemoryBudget {
 public:
  // Bytes reserved by one job; given back when destroyed. Move-only.
  class Reservation {
   public:
    Reservation(Reservation&& other) noexcept
        : budget_(other.budget_), bytes_(other.bytes_) {
      other.budget_ = nullptr;
    }
    Reservation& operator=(Reservation&& other) noexcept {
      if (this != &other) {
        if (budget_ != nullptr) budget_->give_back(bytes_);
        budget_ = other.budget_;
        bytes_ = other.bytes_;
        other.budget_ = nullptr;
      }
      return *this;
    }
    Reservation(const Reservation&) = delete;
    Reservation& operator=(const Reservation&) = delete;
    ~Reservation();

   private:
    friend class MemoryBudget;
    Reservation(MemoryBudget* budget, std::int64_t bytes) : budget_(budget), bytes_(bytes) {}
    MemoryBudget* budget_;  // null once moved from
    std::int64_t bytes_;
  };

  // `capacity` bytes (> 0) shared by every job.
  explicit MemoryBudget(std::int64_t capacity) : capacity_(capacity) {}
  MemoryBudget(const MemoryBudget&) = delete;
  MemoryBudget& operator=(const MemoryBudget&) = delete;

  // `bytes` (>= 0, at most capacity()) taken from the budget, or nullopt when the jobs holding
  // reservations leave less than that free.
  std::optional<Reservation> try_reserve(std::int64_t bytes);

  std::int64_t capacity() const { return capacity_; }
  std::int64_t in_use() const;

 private:
  void give_back(std::int64_t bytes);

  const std::int64_t capacity_;
  mutable std::mutex mu_;
  std::int64_t in_use_ ABSL_GUARDED_BY(mu_) = 0;
};

// 3/4 of the machine's physical memory: the default of afmesh-server's --memory-budget-mb.
std::int64_t default_memory_budget();

}  // namespace afmesh::server
