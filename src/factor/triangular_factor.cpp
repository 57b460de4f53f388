#include "spdfit/triangular_factor.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "estimators/kernels.hpp"
#include "numerics/linalg.hpp"

namespace spdfit {

using Eigen::Index;
using Eigen::MatrixXd;

namespace detail {

void check_data(const Eigen::Ref<const MatrixXd>& A, const Eigen::Ref<const MatrixXd>& B, Index n) {
  if (A.rows() != B.rows() || A.cols() != B.cols()) {
    throw std::invalid_argument("A is " + std::to_string(A.rows()) + "x" + std::to_string(A.cols()) +
                                " but B is " + std::to_string(B.rows()) + "x" + std::to_string(B.cols()) +
                                ": they must have the same shape");
  }
  if (A.cols() != n) {
    throw std::invalid_argument("data has " + std::to_string(A.cols()) + " columns, expected " +
                                std::to_string(n));
  }
  if (!A.allFinite()) throw std::invalid_argument("A contains NaN or Inf");
  if (!B.allFinite()) throw std::invalid_argument("B contains NaN or Inf");
}

std::string too_few_rows(Index m, Index n) {
  return "the data has " + std::to_string(m) + " rows but " + std::to_string(n) +
         " columns: at least as many rows as columns are needed";
}

}  // namespace detail

TriangularFactor::TriangularFactor(Index n) : n_(n) {
  if (n < 1) throw std::invalid_argument("the data must have at least one column");
  R_ = MatrixXd::Zero(2 * n, 2 * n);
}

TriangularFactor TriangularFactor::from_data(const Eigen::Ref<const MatrixXd>& A,
                                             const Eigen::Ref<const MatrixXd>& B) {
  TriangularFactor factor(A.cols());
  factor.append(A, B);
  return factor;
}

void TriangularFactor::raise_exponents(std::optional<int> ea, std::optional<int> eb) {
  // R = [R11 R12; 0 R22]: the first n columns come from A, the last n from B, so a column
  // block scales with its own exponent. Powers of two make this exact (bar underflow of
  // entries that are negligible next to the new data). A block whose data so far was all
  // zero has no exponent yet and its columns of R are zero, so the first nonzero data sets it.
  auto raise = [this](std::optional<int>& current, std::optional<int> wanted, Index first_col) {
    if (!wanted) return;
    if (!current) {
      current = wanted;
      return;
    }
    if (*wanted <= *current) return;
    R_.middleCols(first_col, n_) =
        detail::times_power_of_two(R_.middleCols(first_col, n_), *current - *wanted);
    current = wanted;
  };
  raise(exponent_a_, ea, 0);
  raise(exponent_b_, eb, n_);
}

void TriangularFactor::absorb(const Eigen::Ref<const MatrixXd>& scaled_rows) {
  if (rows_ == 0) {
    R_ = detail::triangular_factor(scaled_rows);
    return;
  }
  MatrixXd stacked(2 * n_ + scaled_rows.rows(), 2 * n_);
  stacked << R_, scaled_rows;
  R_ = detail::triangular_factor(stacked);
}

void TriangularFactor::append(const Eigen::Ref<const MatrixXd>& A, const Eigen::Ref<const MatrixXd>& B) {
  detail::check_data(A, B, n_);
  if (A.rows() == 0) return;
  raise_exponents(detail::scale_exponent(A), detail::scale_exponent(B));
  MatrixXd scaled(A.rows(), 2 * n_);
  auto scaled_a = scaled.leftCols(n_);
  auto scaled_b = scaled.rightCols(n_);
  scaled_a = A;
  scaled_b = B;
  detail::multiply_by_power_of_two(scaled_a, -exponent_a());
  detail::multiply_by_power_of_two(scaled_b, -exponent_b());
  absorb(scaled);
  rows_ += A.rows();
}

void TriangularFactor::merge(const TriangularFactor& other) {
  if (other.n_ != n_) {
    throw std::invalid_argument("cannot merge factors with " + std::to_string(n_) + " and " +
                                std::to_string(other.n_) + " columns");
  }
  if (other.rows_ == 0) return;
  raise_exponents(other.exponent_a_, other.exponent_b_);
  MatrixXd theirs = other.R_;
  theirs.leftCols(n_) = detail::times_power_of_two(theirs.leftCols(n_), other.exponent_a() - exponent_a());
  theirs.rightCols(n_) = detail::times_power_of_two(theirs.rightCols(n_), other.exponent_b() - exponent_b());
  absorb(theirs);
  rows_ += other.rows_;
}

}  // namespace spdfit
