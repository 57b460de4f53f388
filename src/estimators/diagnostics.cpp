#include "estimators/diagnostics.hpp"

#include <Eigen/Eigenvalues>
#include <cmath>
#include <limits>

#include "factor/basic_reduction.hpp"
#include "factor/reduce.hpp"
#include "numerics/linalg.hpp"

namespace spdfit::detail {

using Eigen::Index;
using Eigen::MatrixXd;
using Eigen::VectorXd;

namespace {

// Eigenvalues above -kSemidefiniteSlack * n * eps * max|lambda| count as nonnegative: the
// rounding error of a symmetric eigensolver.
constexpr double kSemidefiniteSlack = 4.0;

// The data's size and ranks: reported with or without the other diagnostics.
void fill_shape_and_ranks(const DynamicReduction& data, Diagnostics& d) {
  d.m = data.m;
  d.n = data.n;
  d.d = data.d;
  d.rank_a = data.rank_a;
  d.rank_b = data.rank_b;
}

// The data's diagnostics. The noise estimate's relative standard error is about sqrt(2 / dof),
// dof = d (m - n) (a chi-squared sum); below n rows beyond the n the fit uses (m - n < n) it is
// worth a warning, unless the estimate failed anyway.
void fill_data_diagnostics(const DynamicReduction& data, Diagnostics& d, std::vector<Warning>& warnings,
                           bool warn_thin_noise_estimate = true) {
  fill_shape_and_ranks(data, d);
  // The noise model used, and what its factory found (a short or moving rest segment), first.
  if (data.options.noise) {
    d.noise_model = data.options.noise;
    warnings.insert(warnings.begin(), data.options.noise->warnings().begin(), data.options.noise->warnings().end());
  }
  d.singular_values_a = times_power_of_two(data.s_a, data.exponent_a);
  d.singular_values_b = times_power_of_two(data.s_b, data.exponent_b);
  d.cond_a = condition_number(data.s_a);
  d.cond_b = condition_number(data.s_b);
  // The column-scaled condition numbers: an SVD each where the rank did not need one, so deferred
  // to their first read when every diagnostic is reported; else cond(A D) only where the warning
  // may need it, as reduce_into left it.
  const bool reported = data.options.diagnostics && data.options.reported_diagnostics;
  d.cond_a_scaled = reported ? scaled_condition_of(data, false) : LazyDouble(data.cond_a_scaled);
  d.cond_b_scaled = reported ? scaled_condition_of(data, true) : LazyDouble(0.0);
  // Judged on the column-scaled A, as the rank is: columns in different units are not
  // ill-conditioning. reduce_into computed cond(A D) wherever it may exceed the threshold.
  const double cond_a_scaled = data.cond_a_scaled;
  if (data.rank_a == data.n && cond_a_scaled * kIllConditionedRcond > 1.0) {
    warnings.push_back(Warning(Code::IllConditioned, "A is ill-conditioned (cond(A) = " + format_number(cond_a_scaled) +
                       " with its columns scaled to unit norm): the estimate may have lost about " +
                       format_number(std::floor(std::log10(cond_a_scaled))) + " significant digits"));
  }
  // The noise estimate is deferred to its first read (it costs an SVD of the whole factor); the
  // TLS family's own, from their SVD, is kept. Its warning depends on the sizes alone.
  if (data.options.diagnostics && data.options.reported_diagnostics && data.dof_rows() > data.n) {
    if (!d.noise_sigma.pending() && !d.noise_sigma.has_value()) d.noise_sigma = noise_sigma_of(data);
    // With a noise model nothing rests on noise_sigma (the equal-noise model's estimate): no warning.
    if (warn_thin_noise_estimate && !data.options.noise && data.dof_rows() - data.n < data.n) {
      const double dof = static_cast<double>(data.d) * static_cast<double>(data.dof_rows() - data.n);
      warnings.push_back(Warning(Code::NoiseEstimate, "the noise estimate (noise_sigma) rests on " +
                         std::string(data.square() ? "n" : "d") + " (m - n) = " + format_number(dof) +
                         " degrees of freedom (m - n < n), so its relative standard error is about " +
                         format_number(100.0 * std::sqrt(2.0 / dof)) + "%: more samples make it reliable"));
    }
  }
}

// The result with the estimate in the data's units, or a failure when it overflowed.
FitResult checked(Method method, MatrixXd X, Diagnostics d, std::vector<Warning> warnings) {
  FitResult result;
  result.method = method;
  result.status = Status::Success;
  result.X = std::move(X);
  result.diagnostics = std::move(d);
  result.warnings = std::move(warnings);
  if (!result.X.allFinite()) {
    result.status = Status::NumericalFailure;
    result.message =
        std::string(to_string(method)) + ": the estimate overflows the range of double precision numbers";
    result.X.resize(0, 0);
  }
  return result;
}

// A B, on the BLAS for large products (multiply).
MatrixXd product(const MatrixXd& A, const MatrixXd& B) {
  MatrixXd C;
  multiply(A, false, B, false, C);
  return C;
}

}  // namespace

std::optional<double> scaled_area_criterion(const DynamicReduction& data, const MatrixXd& X_s) {
  VectorXd lambda;
  MatrixXd W;
  if (!symmetric_eigen(X_s, lambda, &W)) return std::nullopt;
  return scaled_area_criterion(data, lambda, W);
}

std::optional<double> scaled_area_criterion(const DynamicReduction& data, const VectorXd& lambda,
                                            const MatrixXd& vectors) {
  const Index n = data.n;
  const double scale = lambda.cwiseAbs().maxCoeff();
  const double eps = std::numeric_limits<double>::epsilon();
  if (!(scale > 0.0)) return std::nullopt;
  if (lambda(0) < -kSemidefiniteSlack * n * eps * scale) return std::nullopt;
  const double zero = n * eps * scale;  // eigenvalues at or below this are zero: rank of X
  Index first = 0;
  while (first < n && lambda(first) <= zero) ++first;
  const Index r = n - first;
  const auto W = vectors.rightCols(r);
  const VectorXd root = lambda.tail(r).cwiseSqrt();
  const MatrixXd Y = W * root.asDiagonal();                 // X = Y Y^T
  const MatrixXd Z = W * root.cwiseInverse().asDiagonal();  // Y^-T when r = n
  if (r == n) {
    // ||A Y - B Y^-T||^2 = ||R11 Y - R12 Y^-T||^2 + ||R22 Y^-T||^2: a sum of squares, no
    // cancellation (Chen & McInroy, Definition II.1).
    const double top = (product(data.R11, Y) - product(data.R12, Z)).squaredNorm();
    return top + product(data.R22, Z).squaredNorm();
  }
  // Semidefinite X of rank r (Corollary III.7): tr(P X) + tr(X^+ Q) - 2 tr(A^T B) with
  // P = R11^T R11, Q = R_b^T R_b and X^+ = Z Z^T.
  const double cross = data.R11.cwiseProduct(data.R12).sum();  // tr(R11^T R12)
  return product(data.R11, Y).squaredNorm() + product(data.R_b, Z).squaredNorm() - 2.0 * cross;
}

FitResult finish(Method method, const DynamicReduction& data, const MatrixXd& X_s, Diagnostics d,
                 std::vector<Warning> warnings) {
  const int ea = data.exponent_a;
  const int eb = data.exponent_b;
  if (!data.options.diagnostics) {
    fill_shape_and_ranks(data, d);
    return checked(method, times_power_of_two(X_s, eb - ea), std::move(d), std::move(warnings));
  }
  fill_data_diagnostics(data, d, warnings);
  // An estimate beyond the double range even in the scaled units (a column of A 1e300 times
  // smaller than another, independent of it) is a failure checked() reports; nothing below is
  // defined for it.
  if (!X_s.allFinite()) return checked(method, X_s, std::move(d), std::move(warnings));

  const bool reported = data.options.reported_diagnostics;
  // ||A X - B||_F^2 = ||R11 X - R12||_F^2 + ||R22||_F^2, in B's units.
  if (reported) {
    const double fit_part = (product(data.R11, X_s) - data.R12).norm();
    d.residual_norm = std::ldexp(std::hypot(fit_part, data.R22.norm()), eb);
  }

  // A non-square X (ls, tls) is never symmetric: no eigenvalues, no area criterion.
  d.symmetric = data.square() && X_s == X_s.transpose();
  if (d.symmetric) {
    // One eigendecomposition for the definiteness and the area criterion.
    VectorXd lambda;
    MatrixXd vectors;
    const bool solved = symmetric_eigen(X_s, lambda, &vectors);
    if (solved) {
      const double scale = lambda.cwiseAbs().maxCoeff();
      const double eps = std::numeric_limits<double>::epsilon();
      d.min_eigenvalue = std::ldexp(lambda(0), eb - ea);
      d.max_eigenvalue = std::ldexp(lambda(lambda.size() - 1), eb - ea);
      d.positive_definite = lambda(0) > 0.0;
      d.positive_semidefinite = lambda(0) >= -kSemidefiniteSlack * data.n * eps * scale;
    }
    if (d.positive_semidefinite && reported) {
      if (auto f = scaled_area_criterion(data, lambda, vectors)) d.area_criterion = std::ldexp(*f, ea + eb);
    }
  }

  return checked(method, times_power_of_two(X_s, eb - ea), std::move(d), std::move(warnings));
}

FitResult failure(Method method, const DynamicReduction& data, std::string message,
                  std::vector<Warning> warnings) {
  FitResult result;
  result.method = method;
  result.status = Status::NumericalFailure;
  result.message = std::move(message);
  fill_data_diagnostics(data, result.diagnostics, warnings, false);
  result.warnings = std::move(warnings);
  return result;
}

}  // namespace spdfit::detail
