#include "spdfit/experiment/monte_carlo.hpp"

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <exception>
#include <mutex>
#include <stdexcept>
#include <thread>

#include "estimators/small_problem.hpp"
#include "spdfit/fit.hpp"
#include "spdfit/reduction.hpp"
#include "spdfit/triangular_factor.hpp"

namespace spdfit::experiment {

namespace {

constexpr std::chrono::milliseconds kProgressInterval{100};

}  // namespace

bool MonteCarloOptions::is_valid(std::string* error) const {
  if (trials < 1) {
    if (error) *error = "the number of trials must be at least 1";
    return false;
  }
  return true;
}

void check_methods(const std::vector<Method>& methods, const std::string& what) {
  if (methods.empty()) throw std::invalid_argument(what + ": no methods to compare");
  for (std::size_t i = 0; i < methods.size(); ++i) {
    for (std::size_t j = 0; j < i; ++j) {
      if (methods[i] == methods[j]) {
        throw std::invalid_argument(what + ": method " + std::string(to_string(methods[i])) + " is listed twice");
      }
    }
  }
}

void run_trials(const MonteCarloOptions& options, const std::function<void(std::size_t, Random&)>& trial) {
  std::string error;
  if (!options.is_valid(&error)) throw std::invalid_argument("run_trials: " + error);
  const std::size_t total = options.trials;
  const std::size_t threads = std::min<std::size_t>(resolve_threads(options.threads), total);

  std::atomic<std::size_t> next{0};
  std::atomic<std::size_t> done{0};
  std::atomic<bool> stop{false};
  std::exception_ptr first_error;
  std::mutex mutex;  // guards first_error and running
  std::condition_variable finished;
  std::size_t running = threads;

  auto worker = [&]() {
    while (!stop.load(std::memory_order_relaxed)) {
      const std::size_t k = next.fetch_add(1, std::memory_order_relaxed);
      if (k >= total) break;
      try {
        Random random(trial_seed(options.seed, k));
        trial(k, random);
      } catch (...) {
        std::lock_guard<std::mutex> lock(mutex);
        if (!first_error) first_error = std::current_exception();
        stop = true;
      }
      done.fetch_add(1, std::memory_order_relaxed);
    }
    std::lock_guard<std::mutex> lock(mutex);
    --running;
    finished.notify_one();
  };

  if (threads == 1 && !options.progress) {
    worker();
  } else {
    std::vector<std::thread> pool;
    pool.reserve(threads);
    for (std::size_t t = 0; t < threads; ++t) pool.emplace_back(worker);
    {
      std::unique_lock<std::mutex> lock(mutex);
      while (!finished.wait_for(lock, kProgressInterval, [&running] { return running == 0; })) {
        if (options.progress) {
          lock.unlock();
          options.progress(done.load(std::memory_order_relaxed), total);
          lock.lock();
        }
      }
    }
    for (std::thread& thread : pool) thread.join();
  }
  if (first_error) std::rethrow_exception(first_error);
  if (options.progress) options.progress(done.load(), total);
}

void estimate(const Eigen::Ref<const Eigen::MatrixXd>& A, const Eigen::Ref<const Eigen::MatrixXd>& B,
              const std::vector<Method>& methods, std::vector<Eigen::MatrixXd>& X) {
  if (detail::estimate_small(A, B, methods, X)) return;
  FitOptions options;
  options.diagnostics = false;
  const Reduction data = reduce(TriangularFactor::from_data(A, B), options);
  X.resize(methods.size());
  for (std::size_t i = 0; i < methods.size(); ++i) {
    FitResult result = fit(data, methods[i]);
    X[i] = result.ok() ? std::move(result.X) : Eigen::MatrixXd();
  }
}

}  // namespace spdfit::experiment
