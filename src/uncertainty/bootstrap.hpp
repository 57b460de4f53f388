// Internal: the bootstrap behind FitOptions::bootstrap. Replicates are drawn from generators
// keyed by (seed, replicate) and stored by replicate index, so the numbers are the same for any
// number of threads.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "spdfit/fit_options.hpp"
#include "spdfit/fit_result.hpp"
#include "spdfit/reduction.hpp"
#include "spdfit/triangular_factor.hpp"

namespace spdfit::detail {

/// Rows per group of the streaming (Poisson) bootstrap, fixed so that the replicates do not
/// depend on the block size, the threads or the processes.
constexpr Eigen::Index kBootstrapGroupRows = 4096;
/// Below this many groups the Poisson bootstrap is too coarse (with one group every replicate is
/// the estimate or nothing): fit_files resamples rows in memory instead, or refuses.
constexpr Eigen::Index kBootstrapMinGroups = 100;
/// Replicates closer than this (relative, Frobenius) to the first agree to rounding: solves of
/// rescaled copies of the same rows differ by a few hundred eps at moderate condition numbers,
/// while any sampling spread of real data is orders of magnitude larger.
constexpr double kSameReplicateRelative = 1e-12;

/// Why the streaming bootstrap cannot give standard errors for `rows` rows of `columns` values
/// (A's and B's): it needs kBootstrapMinGroups groups of kBootstrapGroupRows rows; `instead` says
/// what the caller cannot do and what the user can.
std::string too_few_groups(std::uint64_t rows, const std::string& instead);

/// Replicate r's multinomial resample of m rows: how often each row was drawn, m draws with
/// replacement by a generator keyed by (seed, r). resample_weights: the same counts as weights.
std::vector<std::uint32_t> resample_counts(Eigen::Index m, std::uint64_t seed, std::size_t replicate);
Eigen::VectorXd resample_weights(Eigen::Index m, std::uint64_t seed, std::size_t replicate);

/// The factor of replicate r's multinomial resample of the rows of A, B: m rows drawn with
/// replacement by a generator keyed by (seed, r), each row counted as often as it was drawn
/// (TriangularFactor::append with counts); with `intercept`, of [1 A B] (FitOptions::offsets
/// Estimate: each resample centred by its own means).
TriangularFactor resample_rows(const Eigen::Ref<const Eigen::MatrixXd>& A, const Eigen::Ref<const Eigen::MatrixXd>& B,
                               std::uint64_t seed, std::size_t replicate, bool intercept = false);

/// Replicate r's Poisson(1) count for the group with global index `group`.
std::uint32_t poisson_count(std::uint64_t seed, std::size_t replicate, std::uint64_t group);

/// The options of a replicate's fit: `options` without the diagnostics and the bootstrap.
FitOptions replicate_options(const FitOptions& options);

/// What one replicate gave: the estimate (empty when it failed) and the failure's message.
struct Replicate {
  Eigen::MatrixXd X;
  std::string message;
};

/// A replicate's fit as a Replicate: X when it succeeded with a finite estimate, else the message.
Replicate replicate_of(FitResult&& fitted);

/// The method the replicates of `full` run, as `fit` runs it on each replicate's reduction:
/// `full.method`, and for auto's boundary fallback psd-ls with auto's floor of the replicate's
/// own data. X only (the reduction's options should turn the diagnostics off).
FitResult fit_replicate(const Reduction& data, const FitResult& full);

/// One replicate: fit_replicate on the reduction of its factor (replicate_options); a failure, or
/// a factor with fewer rows than columns, is the message.
Replicate refit(const TriangularFactor& factor, const FitOptions& options, const FitResult& full);

/// Replicates 0 .. count - 1, made by make(r) on options.threads threads, telling
/// options.progress the fraction made as they finish.
std::vector<Replicate> run_replicates(std::size_t count, const FitOptions& options,
                                      const std::function<Replicate(std::size_t)>& make);

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
