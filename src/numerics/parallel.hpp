// Internal: the worker threads behind the Monte Carlo experiments, the bootstrap (parallel_for)
// and streaming (TaskPool).
#pragma once

#include <condition_variable>
#include <cstddef>
#include <deque>
#include <functional>
#include <future>
#include <memory>
#include <mutex>
#include <thread>
#include <type_traits>
#include <utility>
#include <vector>

namespace spdfit::detail {

/// Runs fn(i) for every i in [0, count) on up to `threads` threads (0: one per core), handing out
/// indices in order. With `progress`, the calling thread reports progress(done, count) about every
/// 100 ms while the workers run, and once at the end; without it, the calling thread works too.
/// The first exception thrown by fn stops the hand-out and is rethrown here once every thread has
/// stopped.
void parallel_for(std::size_t count, unsigned threads, const std::function<void(std::size_t)>& fn,
                  const std::function<void(std::size_t, std::size_t)>& progress = {});

/// A fixed set of threads that run submitted tasks in submission order, for a pipeline that hands
/// out one task per block: starting a thread per task (std::async) cost streaming about a tenth of
/// its time in thread creation and scheduling. The destructor runs the tasks still queued, then
/// joins the threads, so a task may own what it works on but must not refer to the submitter's
/// locals unless the submitter waits for it.
class TaskPool {
 public:
  explicit TaskPool(unsigned threads);
  ~TaskPool();
  TaskPool(const TaskPool&) = delete;
  TaskPool& operator=(const TaskPool&) = delete;

  /// Queues fn; its result (or exception) arrives through the future.
  template <typename Fn>
  std::future<std::invoke_result_t<Fn>> submit(Fn&& fn) {
    using Result = std::invoke_result_t<Fn>;
    auto task = std::make_shared<std::packaged_task<Result()>>(std::forward<Fn>(fn));
    std::future<Result> result = task->get_future();
    enqueue([task] { (*task)(); });
    return result;
  }

 private:
  void enqueue(std::function<void()> job);
  void work();

  std::mutex mutex_;
  std::condition_variable ready_;
  std::deque<std::function<void()>> jobs_;
  bool stopping_ = false;
  std::vector<std::thread> threads_;
};

}  // namespace spdfit::detail
