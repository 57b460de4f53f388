// Every estimator on the same data, and how far each estimate is from a known truth.
#pragma once

#include <string_view>
#include <vector>

#include "spdfit/fit_request.hpp"
#include "spdfit/options.hpp"
#include "spdfit/output_request.hpp"

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

/// `spdfit compare` as one workflow: A and B (files or values), the options every method shares,
/// a truth, and how the result is printed.
struct CompareRequest {
  MatrixInput a;  ///< A (m x n)
  MatrixInput b;  ///< B (m x d); empty with fit.a_cols and fit.b_cols (both from a's file)
  /// The noise (ratio or model), the columns of one file, and how files are read (fit.read).
  FitRequest fit;
  std::optional<MatrixInput> truth;  ///< the true X (n x d)
  OutputRequest output;              ///< the command line's: JSON or the report, and where
};

/// The options of a CompareRequest: a, b (positional), truth, the fit's that every method shares
/// (the noise's, a_cols, b_cols), and the command line's json and output.
const std::vector<OptionSpec<CompareRequest>>& compare_option_table();

/// Checks the options given (library names): the table's rules, and B needed unless `a_cols` and
/// `b_cols` choose both from A's file. Throws OptionError.
void check_compare_request(const CompareRequest& request, const std::vector<std::string_view>& given);

/// What `spdfit compare` found: the comparison and every warning (the readers', then each
/// method's prefixed with its name).
struct CompareRun {
  Comparison comparison;
  std::vector<Warning> warnings;
};

/// Reads A and B (read_pair for files, with the fit's column selections) and the truth (n x d:
/// io::DataError naming its file, InputError otherwise), resolves the noise model, and compares
/// (compare). Cost: compare's.
CompareRun run_compare(const CompareRequest& request);

}  // namespace spdfit
