#include "server/worker_pool.h"

#include <atomic>
#include <chrono>
#include <future>
#include <optional>
#include <thread>
#include <vector>

#include "gtest/gtest.h"

namespace afmesh::server {
namespace {

TEST(WorkerPool, RunsEveryTaskBeforeDestruction) {
  std::atomic<int> done{0};
  {
    WorkerPool pool(2, 8);
    for (int i = 0; i < 10; ++i) {
      std::optional<WorkerPool::Slot> slot = pool.try_reserve();
      ASSERT_TRUE(slot.has_value()) << "slot " << i;
      pool.run(std::move(*slot), [&done] { done.fetch_add(1); });
    }
  }
  EXPECT_EQ(done.load(), 10);
}

TEST(WorkerPool, RefusesReservationsBeyondWorkersPlusQueue) {
  WorkerPool pool(1, 2);
  std::vector<WorkerPool::Slot> slots;
  for (int i = 0; i < 3; ++i) {
    std::optional<WorkerPool::Slot> slot = pool.try_reserve();
    ASSERT_TRUE(slot.has_value()) << "slot " << i;
    slots.push_back(std::move(*slot));
  }
  EXPECT_FALSE(pool.try_reserve().has_value());
}

TEST(WorkerPool, DroppedSlotFreesItsPlace) {
  WorkerPool pool(1, 0);
  std::optional<WorkerPool::Slot> first = pool.try_reserve();
  ASSERT_TRUE(first.has_value());
  EXPECT_FALSE(pool.try_reserve().has_value());
  first.reset();
  EXPECT_TRUE(pool.try_reserve().has_value());
}

TEST(WorkerPool, FinishedTaskFreesItsPlace) {
  WorkerPool pool(1, 0);
  std::optional<WorkerPool::Slot> slot = pool.try_reserve();
  ASSERT_TRUE(slot.has_value());
  std::promise<void> ran;
  pool.run(std::move(*slot), [&ran] { ran.set_value(); });
  ran.get_future().wait();
  std::optional<WorkerPool::Slot> next;
  const auto give_up = std::chrono::steady_clock::now() + std::chrono::seconds(5);
  while (!next && std::chrono::steady_clock::now() < give_up) next = pool.try_reserve();
  EXPECT_TRUE(next.has_value());
}

TEST(WorkerPool, RunsAtMostWorkersTasksAtOnce) {
  constexpr int kWorkers = 2;
  std::atomic<int> running{0};
  std::atomic<int> most{0};
  {
    WorkerPool pool(kWorkers, 6);
    for (int i = 0; i < 8; ++i) {
      std::optional<WorkerPool::Slot> slot = pool.try_reserve();
      ASSERT_TRUE(slot.has_value());
      pool.run(std::move(*slot), [&] {
        const int now = running.fetch_add(1) + 1;
        int seen = most.load();
        while (now > seen && !most.compare_exchange_weak(seen, now)) {
        }
        std::this_thread::sleep_for(std::chrono::milliseconds(5));
        running.fetch_sub(1);
      });
    }
  }
  EXPECT_LE(most.load(), kWorkers);
  EXPECT_GE(most.load(), 1);
}

TEST(WorkerPool, LoadCountsReservedQueuedAndRunning) {
  WorkerPool pool(1, 2);
  std::promise<void> started;
  std::promise<void> release;
  std::shared_future<void> released = release.get_future().share();
  std::optional<WorkerPool::Slot> first = pool.try_reserve();
  std::optional<WorkerPool::Slot> second = pool.try_reserve();
  std::optional<WorkerPool::Slot> third = pool.try_reserve();
  ASSERT_TRUE(first && second && third);
  pool.run(std::move(*first), [&started, released] {
    started.set_value();
    released.wait();
  });
  started.get_future().wait();
  pool.run(std::move(*second), [] {});  // waits: the only worker is busy
  const WorkerPool::Load busy = pool.load();
  EXPECT_EQ(busy.reserved, 3);  // the third slot is held, its task not yet queued
  EXPECT_EQ(busy.queued, 1);
  EXPECT_EQ(busy.running, 1);

  third.reset();
  release.set_value();
  WorkerPool::Load idle = pool.load();
  const auto give_up = std::chrono::steady_clock::now() + std::chrono::seconds(5);
  while (idle.reserved != 0 && std::chrono::steady_clock::now() < give_up) idle = pool.load();
  EXPECT_EQ(idle.reserved, 0);
  EXPECT_EQ(idle.queued, 0);
  EXPECT_EQ(idle.running, 0);
}

}  // namespace
}  // namespace afmesh::server
