#include "server/memory_budget.h"

#include <unistd.h>

namespace afmesh::server {

MemoryBudget::Reservation::~Reservation() {
  if (budget_ != nullptr) budget_->give_back(bytes_);
}

std::optional<MemoryBudget::Reservation> MemoryBudget::try_reserve(std::int64_t bytes) {
  std::lock_guard<std::mutex> lock(mu_);
  if (bytes > capacity_ - in_use_) return std::nullopt;
  in_use_ += bytes;
  return Reservation(this, bytes);
}

std::int64_t MemoryBudget::in_use() const {
  std::lock_guard<std::mutex> lock(mu_);
  return in_use_;
}

void MemoryBudget::give_back(std::int64_t bytes) {
  std::lock_guard<std::mutex> lock(mu_);
  in_use_ -= bytes;
}

std::int64_t default_memory_budget() {
  const long pages = sysconf(_SC_PHYS_PAGES);
  const long page_size = sysconf(_SC_PAGESIZE);
  if (pages <= 0 || page_size <= 0) return std::int64_t{4} << 30;  // unknown: 4 GiB
  return static_cast<std::int64_t>(pages) * page_size / 4 * 3;
}

}  // namespace afmesh::server
