#include "spdfit/threads.hpp"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <exception>
#include <mutex>
#include <thread>
#include <vector>

#include "numerics/parallel.hpp"

namespace spdfit {

unsigned resolve_threads(unsigned requested) {
  if (requested > 0) return requested;
  const unsigned hardware = std::thread::hardware_concurrency();
  return hardware > 0 ? hardware : 1;
}

namespace detail {

namespace {
constexpr std::chrono::milliseconds kProgressInterval{100};
}  // namespace

void parallel_for(std::size_t count, unsigned threads, const std::function<void(std::size_t)>& fn,
                  const std::function<void(std::size_t, std::size_t)>& progress) {
  const std::size_t workers = std::min<std::size_t>(resolve_threads(threads), std::max<std::size_t>(count, 1));
  std::atomic<std::size_t> next{0};
  std::atomic<std::size_t> done{0};
  std::atomic<bool> stop{false};
  std::exception_ptr first_error;
  std::mutex mutex;  // guards first_error and running
  std::condition_variable finished;
  std::size_t running = 0;

  auto work = [&]() {
    while (!stop.load(std::memory_order_relaxed)) {
      const std::size_t i = next.fetch_add(1, std::memory_order_relaxed);
      if (i >= count) break;
      try {
        fn(i);
      } catch (...) {
        std::lock_guard<std::mutex> lock(mutex);
        if (!first_error) first_error = std::current_exception();
        stop = true;
      }
      done.fetch_add(1, std::memory_order_relaxed);
    }
  };

  if (!progress) {
    // The calling thread is one of the workers.
    std::vector<std::thread> pool;
    pool.reserve(workers - 1);
    for (std::size_t t = 1; t < workers; ++t) pool.emplace_back(work);
    work();
    for (std::thread& thread : pool) thread.join();
  } else {
    // The calling thread reports progress while the workers run.
    running = workers;
    std::vector<std::thread> pool;
    pool.reserve(workers);
    for (std::size_t t = 0; t < workers; ++t) {
      pool.emplace_back([&] {
        work();
        std::lock_guard<std::mutex> lock(mutex);
        --running;
        finished.notify_one();
      });
    }
    {
      std::unique_lock<std::mutex> lock(mutex);
      while (!finished.wait_for(lock, kProgressInterval, [&running] { return running == 0; })) {
        lock.unlock();
        progress(done.load(std::memory_order_relaxed), count);
        lock.lock();
      }
    }
    for (std::thread& thread : pool) thread.join();
  }
  if (first_error) std::rethrow_exception(first_error);
  if (progress) progress(done.load(), count);
}

TaskPool::TaskPool(unsigned threads) {
  threads_.reserve(threads);
  for (unsigned k = 0; k < threads; ++k) threads_.emplace_back([this] { work(); });
}

TaskPool::~TaskPool() {
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    stopping_ = true;
  }
  ready_.notify_all();
  for (std::thread& thread : threads_) thread.join();
}

void TaskPool::enqueue(std::function<void()> job) {
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    jobs_.push_back(std::move(job));
  }
  ready_.notify_one();
}

void TaskPool::work() {
  for (;;) {
    std::function<void()> job;
    {
      std::unique_lock<std::mutex> lock(mutex_);
      ready_.wait(lock, [this] { return stopping_ || !jobs_.empty(); });
      if (jobs_.empty()) return;  // stopping, and nothing left to run
      job = std::move(jobs_.front());
      jobs_.pop_front();
    }
    job();  // a packaged_task: its exception goes to its future
  }
}

}  // namespace detail

}  // namespace spdfit
