#include "repair/repair.hpp"

#include <cmath>
#include <limits>
#include <stdexcept>

#include "estimators/diagnostics.hpp"
#include "factor/data_checks.hpp"

namespace spdfit {

bool EigenvalueFloor::is_valid(std::string* error) const {
  auto fail = [error](std::string why) {
    if (error) *error = std::move(why);
    return false;
  };
  if (!std::isfinite(value) || value < 0.0) {
    return fail(std::string(relative ? "`min_eig_rel`" : "`min_eig`") + " must be a finite number >= 0");
  }
  if (relative && value >= 1.0) return fail("`min_eig_rel` (a relative eigenvalue floor) must be below 1");
  return true;
}

EigenvalueFloor EigenvalueFloor::chosen(std::optional<double> min_eig, std::optional<double> min_eig_rel,
                                        bool alpha_given) {
  if (min_eig && min_eig_rel) throw std::invalid_argument("give min_eig or min_eig_rel, not both");
  if (alpha_given && (min_eig || min_eig_rel)) {
    throw std::invalid_argument("alpha is the unit diagonal's floor: give it or min_eig/min_eig_rel, not both");
  }
  if (min_eig) return absolute(*min_eig);
  if (alpha_given) return {};
  return relative_to_largest(min_eig_rel.value_or(kRepairDefault));
}

namespace detail {

void check_repair_input(const Eigen::Ref<const Eigen::MatrixXd>& C, EigenvalueFloor floor) {
  if (C.rows() == 0 || C.rows() != C.cols()) {
    throw std::invalid_argument("the matrix to repair must be square and non-empty, not " + std::to_string(C.rows()) +
                                "x" + std::to_string(C.cols()));
  }
  if (const std::optional<NonfiniteEntry> e = first_nonfinite(C)) {
    throw std::invalid_argument("the matrix to repair has " + std::string(e->what) + " at row " +
                                std::to_string(e->row + 1) + ", column " + std::to_string(e->column + 1) +
                                " (counting from 1; [" + std::to_string(e->row) + ", " + std::to_string(e->column) +
                                "] in NumPy)" + kNonfiniteCause);
  }
  std::string error;
  if (!floor.is_valid(&error)) throw std::invalid_argument(error);
}

const char* floor_option(EigenvalueFloor floor) { return floor.relative ? "`min_eig_rel`" : "`min_eig`"; }

std::optional<Warning> asymmetry_warning(const Eigen::Ref<const Eigen::MatrixXd>& C) {
  const double norm = C.norm();
  const double asymmetry = (C - C.transpose()).norm();
  if (!(asymmetry > 1e-10 * norm)) return std::nullopt;
  return Warning(Code::NotSymmetric,
                 "the matrix is not symmetric (||X - X^T||_F / ||X||_F = " + format_number(asymmetry / norm) +
                     ", more than rounding): its symmetric part (X + X^T) / 2 was used; is it the right file?");
}

double resolve_floor(EigenvalueFloor floor, double lambda_max) {
  if (!floor.relative || floor.value == 0.0) return floor.value;
  if (!(lambda_max > 0.0)) {
    throw std::invalid_argument("the matrix has no positive eigenvalue (the largest is " + format_number(lambda_max) +
                                "), so a floor relative to it (`min_eig_rel`) is undefined (the nearest semidefinite "
                                "matrix is 0): give an absolute floor (`min_eig`)");
  }
  return floor.value * lambda_max;
}

void check_variances(const Eigen::VectorXd& d, bool zero_allowed, const char* why) {
  std::string listed;
  int count = 0;
  bool zero = false, negative = false;
  for (Eigen::Index i = 0; i < d.size(); ++i) {
    if (d(i) < 0.0 || (!zero_allowed && d(i) == 0.0)) {
      if (count < 10) listed += (count == 0 ? "" : ", ") + std::to_string(i + 1) + " (" + format_number(d(i)) + ")";
      ++count;
      zero = zero || d(i) == 0.0;
      negative = negative || d(i) < 0.0;
    }
  }
  if (count == 0) return;
  if (count > 10) listed += ", ... (" + std::to_string(count) + " in all)";
  const std::string what = negative && !zero ? "negative" : zero_allowed ? "negative" : "not positive";
  throw InputError(std::string(count == 1 ? "diagonal entry " : "diagonal entries ") + listed + " " +
                       (count == 1 ? "is " : "are ") + what + ": a covariance's variances must be " +
                       (zero_allowed ? ">= 0" : std::string("> 0 here (") + why + ")") +
                       "; raise them with `min_diag` (for example 1e-8 times the largest variance), or drop "
                       "those variables",
                   Code::DataValue);
}

std::optional<Warning> unit_diagonal_warning(const Eigen::Ref<const Eigen::MatrixXd>& S) {
  const double off = (S.diagonal().array() - 1.0).abs().maxCoeff();
  if (!(off > 1e-6)) return std::nullopt;
  return Warning(Code::DiagonalChanged,
                 "the diagonal is not 1 (it ranges from " + format_number(S.diagonal().minCoeff()) + " to " +
                     format_number(S.diagonal().maxCoeff()) +
                     "): it was repaired to a correlation matrix (unit diagonal); to keep a covariance's variances "
                     "instead, repair it with its diagonal kept (`keep_diag` or `via_corr`)");
}

std::optional<Warning> floor_warning(double floor, double floor_change, double repair, double scale,
                                         double lambda_max, bool of_correlation) {
  if (!(floor_change > repair) || !(floor_change > 1e-6 * scale)) return std::nullopt;
  return Warning(Code::EigenvaluesRaised,
                 std::string("the eigenvalue floor ") + format_number(floor) +
                     (of_correlation ? " of the correlation matrix D^-1/2 X D^-1/2" : "") + " moved the matrix by " +
                     format_number(floor_change) + ", more than the repair itself (" + format_number(repair) +
                     "); the " + (of_correlation ? "correlation matrix" : "matrix") +
                     " repaired has largest eigenvalue " + format_number(lambda_max) +
                     ": a floor meant for another scale does this (a relative floor follows the scale)",
                 "min_eig");
}

}  // namespace detail
}  // namespace spdfit
