// Reproducible parallel Monte Carlo: independent trials spread over threads, with numbers that
// do not depend on the number of threads.
#pragma once

#include <Eigen/Core>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "spdfit/fit_result.hpp"
#include "spdfit/random.hpp"
#include "spdfit/threads.hpp"

namespace spdfit::experiment {

/// How many trials to run, from which seed, on how many threads.
struct MonteCarloOptions {
  std::size_t trials = 1000;
  std::uint64_t seed = 1;
  /// Worker threads; 0 means std::thread::hardware_concurrency(). The results do not depend
  /// on it.
  unsigned threads = 0;
  /// Called on the calling thread about every 0.1 s while trials run, with (trials done,
  /// trials in all), and once at the end; may be empty. For progress display only.
  std::function<void(std::size_t, std::size_t)> progress;

  /// True when usable (trials >= 1); otherwise `error` says why.
  bool is_valid(std::string* error = nullptr) const;
};

/// spdfit::resolve_threads (spdfit/threads.hpp), also reachable by its earlier name here.
using spdfit::resolve_threads;

/// Throws std::invalid_argument ("<what>: ...") unless `methods` is non-empty and has no repeats.
void check_methods(const std::vector<Method>& methods, const std::string& what);

/// Runs trial(k, random) for k = 0, ..., trials - 1, where `random` is a fresh
/// Random(trial_seed(seed, k)) for each trial. Trials are handed out to the threads one at a
/// time; a trial must write its results only to storage indexed by k (no other shared mutable
/// state), which makes the results identical for any number of threads. The first exception
/// a trial throws stops the remaining trials and is rethrown here. Throws
/// std::invalid_argument when the options are invalid.
void run_trials(const MonteCarloOptions& options, const std::function<void(std::size_t, Random&)>& trial);

/// The estimates of `methods` (in that order) on one trial's data, X only: X[i] becomes method
/// i's estimate, or an empty (0 x 0) matrix where the method has none (a numerical failure,
/// e.g. SPDE with A rank-deficient). The methods share the QR of [A B] and the reduction, and
/// run without the estimates' diagnostics. For n <= 8 every matrix lives on the stack and X's
/// storage is reused, so a loop that keeps X allocates nothing per trial; larger n takes the
/// public estimators' path. The estimates equal spdfit::fit's to rounding. This is every
/// experiment's inner loop, kept in one function so that a faster one can be swapped in at one
/// place. Throws std::invalid_argument for data fit() rejects. Cost O(m n^2 + n^3).
void estimate(const Eigen::Ref<const Eigen::MatrixXd>& A, const Eigen::Ref<const Eigen::MatrixXd>& B,
              const std::vector<Method>& methods, std::vector<Eigen::MatrixXd>& X);

}  // namespace spdfit::experiment
