// Every estimator on the same data, and how far each estimate is from a known truth.
#pragma once

#include <cstddef>
#include <optional>
#include <vector>

#include <Eigen/Core>

#include "spdfit/fit_options.hpp"
#include "spdfit/fit_result.hpp"

namespace spdfit {

/// ||X - truth||_F, the error of a successful estimate against the true X (the error the thesis'
/// and the paper's experiments measure); nothing for a failed result. Throws
/// std::invalid_argument when truth does not have X's shape. Cost O(n d).
std::optional<double> error_vs_truth(const FitResult& result, const Eigen::MatrixXd& truth);

/// The index of the smallest of `errors` (the first of equal ones); nothing when none is given.
std::optional<std::size_t> closest_to_truth(const std::vector<std::optional<double>>& errors);

/// fit_all's results with their errors against a truth, when one is given.
struct Comparison {
  Eigen::Index m = 0, n = 0, d = 0;  ///< A is m x n, B m x d
  std::vector<FitResult> results;    ///< fit_all's, one per method
  std::optional<Eigen::MatrixXd> truth;
  /// error_vs_truth of each result (with a truth; nothing for a failed method or without one).
  std::vector<std::optional<double>> errors;
};

/// Every method on A X ~= B (fit_all, one factor for all) and, with a truth (n x d), each
/// estimate's error against it. Throws std::invalid_argument as fit_all does, and when truth is
/// not n x d. Cost: fit_all's.
Comparison compare(const Eigen::Ref<const Eigen::MatrixXd>& A, const Eigen::Ref<const Eigen::MatrixXd>& B,
                   const FitOptions& options = {}, const std::optional<Eigen::MatrixXd>& truth = std::nullopt);

}  // namespace spdfit
