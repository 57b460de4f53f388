// detail::TaskPool (src/numerics/parallel.hpp), the streaming pipeline's worker threads: every
// task runs once, its result or exception reaches its future, and tasks still queued when the
// pool goes run before its threads are joined.
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <future>
#include <stdexcept>
#include <thread>
#include <vector>

#include "numerics/parallel.hpp"

namespace {

TEST(TaskPool, RunsEveryTaskOnceAndReturnsItsResult) {
  spdfit::detail::TaskPool pool(3);
  std::atomic<int> runs{0};
  std::vector<std::future<int>> results;
  for (int k = 0; k < 200; ++k) {
    results.push_back(pool.submit([k, &runs] {
      ++runs;
      return k * k;
    }));
  }
  for (int k = 0; k < 200; ++k) EXPECT_EQ(results[static_cast<std::size_t>(k)].get(), k * k);
  EXPECT_EQ(runs.load(), 200);
}

TEST(TaskPool, AnExceptionReachesItsFutureAndTheOthersStillRun) {
  spdfit::detail::TaskPool pool(2);
  auto bad = pool.submit([]() -> int { throw std::runtime_error("block 7 is bad"); });
  auto good = pool.submit([] { return 5; });
  EXPECT_THROW(
      {
        try {
          bad.get();
        } catch (const std::runtime_error& e) {
          EXPECT_STREQ(e.what(), "block 7 is bad");
          throw;
        }
      },
      std::runtime_error);
  EXPECT_EQ(good.get(), 5);
}

TEST(TaskPool, TasksQueuedAtDestructionStillRun) {
  std::atomic<int> runs{0};
  {
    spdfit::detail::TaskPool pool(1);
    for (int k = 0; k < 20; ++k) {
      // The futures are dropped: the pool alone keeps the tasks.
      (void)pool.submit([&runs] {
        std::this_thread::sleep_for(std::chrono::milliseconds(1));
        ++runs;
      });
    }
  }
  EXPECT_EQ(runs.load(), 20);
}

}  // namespace
