// Internal: the bootstrap behind FitOptions::bootstrap. Replicates are drawn from generators
// keyed by (seed, replicate) and stored by replicate index, so the numbers are the same for any
// number of threads.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <functional>
#include <optional>
#include <vector>

#include "spdfit/fit_options.hpp"
#include "spdfit/fit_result.hpp"
#include "spdfit/reduction.hpp"
#include "spdfit/triangular_factor.hpp"

namespace spdfit::detail {

/// Rows per group of the streaming (Poisson) bootstrap, fixed so that the replicates do not
/// depend on the block size, the threads or the processes.
constexpr Eigen::Index kBootstrapGroupRows = 4096;
/// Below this many groups the Poisson bootstrap is too coarse: a warning.
constexpr Eigen::Index kBootstrapMinGroups = 100;

/// Replicate r's multinomial resample of m rows: counts[i] is how often row i is drawn
/// (the counts sum to m).
void multinomial_counts(std::uint64_t seed, int replicate, Eigen::Index m, std::vector<std::uint32_t>& counts);

/// Replicate r's Poisson(1) count for the group with global index `group`.
std::uint32_t poisson_count(std::uint64_t seed, int replicate, std::uint64_t group);

/// Runs fn(i) for i in [0, count) on up to `threads` threads (0: one per core). The first
/// exception thrown by fn is rethrown here after every thread has stopped.
void parallel_for(int count, unsigned threads, const std::function<void(int)>& fn);

/// What one replicate gave: the estimate (empty when it failed) and the first failure's message.
struct Replicate {
  Eigen::MatrixXd X;
  std::string message;
};

/// The method the replicates of `full` run, as `fit` runs it on each replicate's reduction:
/// `full.method`, and for auto's boundary fallback psd-ls with auto's floor of the replicate's
/// own data. X only (the reduction's options should turn the diagnostics off).
FitResult fit_replicate(const Reduction& data, const FitResult& full);

/// One replicate: fit_replicate on the reduction of its factor (options without diagnostics);
/// a failure, or a factor with fewer rows than columns, is the message.
Replicate refit(const TriangularFactor& factor, const FitOptions& options, const FitResult& full);

/// The uncertainty of sorted values (SpectrumUncertainty): `replicates` holds each replicate's
/// values ascending, or nothing where it has none.
SpectrumUncertainty summarize_spectrum(const Eigen::VectorXd& estimate,
                                       const std::vector<std::optional<Eigen::VectorXd>>& replicates, double level);

/// Fills result.bootstrap (scheme "multinomial" unless set after) from the replicates' estimates,
/// with the warnings about failed replicates and about bias.
void attach_bootstrap(FitResult& result, const std::vector<Replicate>& replicates, const FitOptions& options,
                      const Reduction& full_data);

/// The bootstrap of fit(A, B, method, options) for its result `result` (successful).
void bootstrap_in_memory(FitResult& result, const Eigen::Ref<const Eigen::MatrixXd>& A,
                         const Eigen::Ref<const Eigen::MatrixXd>& B, const Reduction& full_data);

}  // namespace spdfit::detail
