#include "spdfit/compare.hpp"

#include <stdexcept>
#include <string>

#include "spdfit/fit.hpp"

namespace spdfit {

namespace {

std::string shape(Eigen::Index rows, Eigen::Index cols) { return std::to_string(rows) + "x" + std::to_string(cols); }

}  // namespace

std::optional<double> error_vs_truth(const FitResult& result, const Eigen::MatrixXd& truth) {
  if (!result.ok()) return std::nullopt;
  if (truth.rows() != result.X.rows() || truth.cols() != result.X.cols()) {
    throw std::invalid_argument("error_vs_truth: the truth is " + shape(truth.rows(), truth.cols()) +
                                " but the estimate X is " + shape(result.X.rows(), result.X.cols()));
  }
  return (result.X - truth).norm();
}

std::optional<std::size_t> closest_to_truth(const std::vector<std::optional<double>>& errors) {
  std::optional<std::size_t> best;
  for (std::size_t k = 0; k < errors.size(); ++k) {
    if (errors[k] && (!best || *errors[k] < *errors[*best])) best = k;
  }
  return best;
}

Comparison compare(const Eigen::Ref<const Eigen::MatrixXd>& A, const Eigen::Ref<const Eigen::MatrixXd>& B,
                   const FitOptions& options, const std::optional<Eigen::MatrixXd>& truth) {
  if (truth && (truth->rows() != A.cols() || truth->cols() != B.cols())) {
    throw std::invalid_argument("compare: the true X must be " + shape(A.cols(), B.cols()) + " (n x d), not " +
                                shape(truth->rows(), truth->cols()));
  }
  Comparison out;
  out.m = A.rows();
  out.n = A.cols();
  out.d = B.cols();
  out.truth = truth;
  out.results = fit_all(A, B, options);
  for (const FitResult& r : out.results) {
    out.errors.push_back(truth ? error_vs_truth(r, *truth) : std::nullopt);
  }
  return out;
}

}  // namespace spdfit
