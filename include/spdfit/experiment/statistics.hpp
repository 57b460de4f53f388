// Summaries of Monte Carlo results: per-method error statistics, per-entry statistics, and
// paired comparisons of two methods on the same trials.
#pragma once

#include <cstddef>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "spdfit/method.hpp"

namespace spdfit::experiment {

/// Statistics of a sample of errors. NaN values (trials on which the method failed) are left
/// out and counted in `failures`.
struct Summary {
  std::size_t count = 0;     ///< values summarized (finite ones)
  std::size_t failures = 0;  ///< NaN values left out
  double mean = 0.0;
  double std = 0.0;  ///< sample standard deviation (n - 1); 0 for one value
  double median = 0.0;
  double min = 0.0;
  double max = 0.0;
  /// std / sqrt(count): the standard error of the mean.
  double standard_error() const;
};

/// Summarizes `values` (copied: the median needs a partial sort). Empty or all-NaN input gives
/// count 0 and NaN statistics. Cost O(n).
Summary summarize(std::vector<double> values);

/// Two methods compared on the same trials: the differences d_k = a_k - b_k over the trials
/// where both are finite. Pairing removes the trial-to-trial variation both share, so the
/// standard error of the mean difference is far smaller than either method's own.
struct PairedComparison {
  std::size_t count = 0;
  double mean_difference = 0.0;  ///< mean of a - b
  double standard_error = 0.0;   ///< of mean_difference: std(d) / sqrt(count)
  double fraction_lower = 0.0;   ///< fraction of trials with a < b
};

/// Compares a and b (same length) trial by trial. Cost O(n).
PairedComparison compare_paired(const std::vector<double>& a, const std::vector<double>& b);

/// How many standard errors of the paired mean difference make a difference between two methods
/// real: under a normal mean difference, a tie passes for a difference with probability 0.3%.
inline constexpr double kSignificance = 3.0;

/// Whether a's values are significantly below b's, within the noise of each other, or above.
enum class Order { Lower, Tie, Higher };

/// "lower", "tie", "higher".
const char* to_string(Order order);

/// Lower when mean_difference + significance * standard_error < 0, Higher when
/// mean_difference - significance * standard_error > 0, Tie otherwise (also for no trials).
Order order_of(const PairedComparison& comparison, double significance = kSignificance);

/// The independent entries (i, j), i <= j, of a symmetric n x n matrix, row by row:
/// (0,0), (0,1), ..., (0,n-1), (1,1), ...: n (n + 1) / 2 of them (21 for n = 6).
std::vector<std::pair<Eigen::Index, Eigen::Index>> upper_triangle_entries(Eigen::Index n);

/// Per-entry error statistics of one method over the trials (Chen & McInroy, Figures 2-3).
/// `errors` holds the signed errors X_hat(i, j) - X(i, j) of the entries, one row per trial;
/// rows of NaN (trials where the method failed) are left out and counted.
struct EntryStatistics {
  Method method = Method::Spde;
  std::size_t count = 0;     ///< trials summarized
  std::size_t failures = 0;  ///< trials left out
  Eigen::VectorXd mae;       ///< mean absolute error, mean |e|
  /// Standard deviation of the signed error e (n - 1): the spread of the estimate, the paper's
  /// STD{}.
  Eigen::VectorXd std;
  Eigen::VectorXd bias;    ///< mean signed error, mean e (|bias| is the paper's "absolute mean")
  Eigen::MatrixXd errors;  ///< the per-trial signed errors (trials x entries), kept for tests
};

/// Summarizes a trials x entries matrix of signed errors. Cost O(trials x entries).
EntryStatistics summarize_entries(Method method, Eigen::MatrixXd errors);

}  // namespace spdfit::experiment
