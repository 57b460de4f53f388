#include "spdfit/auto.hpp"

#include <algorithm>
#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <cmath>
#include <limits>
#include <string>

#include "estimators/auto_settle.hpp"
#include "estimators/diagnostics.hpp"
#include "factor/reduce.hpp"
#include "estimators/kernels.hpp"
#include "estimators/psd_ls_kernel.hpp"
#include "numerics/linalg.hpp"
#include "spdfit/spd_total_least_squares.hpp"
#include "spdfit/spde.hpp"

namespace spdfit {

using Eigen::Index;
using Eigen::MatrixXd;

namespace detail {

namespace {
// spd-tls needs enough rows beyond n for its scatter to fall below spde's bias: at least
// kMinExtraRowsPerColumn n of them, and (m - n) snr >= kMinEvidence (docs/guide.md's table).
constexpr double kMinExtraRowsPerColumn = 4.0;
constexpr double kMinEvidence = 30.0;
constexpr double kFloorRatio = 1e-8;
// Positive definite beyond rounding: lambda_min > kDefiniteMargin n eps lambda_max (a matrix on
// the boundary, from spd-tls, has lambda_min at rounding level of either sign).
constexpr double kDefiniteMargin = 64.0;
// Above this signal-to-noise ratio the data are consistent to rounding: spde, exact there to
// cond(A) eps (spd-tls is not, on ill-conditioned A; spd_total_least_squares.hpp).
constexpr double kNoiseFreeSnr = 1e10;
}  // namespace

template <int MaxN>
AutoChoice auto_choice(const BasicReduction<MaxN>& data, std::optional<double> noise_var) {
  AutoChoice choice;
  const Index n = data.n, m = data.dof_rows();  // centred data: one degree of freedom fewer
  choice.snr = std::numeric_limits<double>::quiet_NaN();
  if (data.rank_a < n) {
    choice.method = Method::SpdTotalLeastSquares;
    choice.code = "rank_deficient_a";
    return choice;
  }
  const double extra = static_cast<double>(m - n);
  if (noise_var && *noise_var > 0.0) {
    const double s_min = std::ldexp(data.s_a(n - 1), data.exponent_a);
    choice.snr = std::max(s_min * s_min / (static_cast<double>(m) * *noise_var) - 1.0, 0.0);
  } else if (noise_var) {
    choice.snr = std::numeric_limits<double>::infinity();  // noise-free: every method agrees
  }
  if (choice.snr >= kNoiseFreeSnr) {
    choice.method = Method::Spde;
    choice.code = "noise_free";
    return choice;
  }
  // An unknown snr (NaN: m <= n) fails the comparison: spde.
  const bool enough =
      extra >= kMinExtraRowsPerColumn * static_cast<double>(n) && extra * choice.snr >= kMinEvidence;
  choice.method = enough ? Method::SpdTotalLeastSquares : Method::Spde;
  choice.code = enough ? "many_samples" : "few_samples";
  return choice;
}

template <typename Matrix>
bool clearly_positive_definite(const Matrix& X) {
  if (X.size() == 0 || !X.allFinite()) return false;
  Eigen::Matrix<double, Eigen::Dynamic, 1, Eigen::ColMajor, Matrix::MaxRowsAtCompileTime, 1> w;
  if (!symmetric_eigen(X, w)) return false;
  return w(0) > kDefiniteMargin * static_cast<double>(X.rows()) * std::numeric_limits<double>::epsilon() *
                    w(w.size() - 1);
}

template <int MaxN>
double auto_floor(const BasicReduction<MaxN>& data) {
  SquareMatrix<MaxN> X;
  least_squares_kernel(data, X);
  const double norm = X.norm();
  return std::isfinite(norm) && norm > 0.0 ? kFloorRatio * norm : std::numeric_limits<double>::min();
}

AutoChoice auto_noise_choice(const DynamicReduction& data, const ScaledNoise& noise) {
  AutoChoice choice;
  const Index n = data.n, m = data.dof_rows();  // centred data: one degree of freedom fewer
  choice.snr = std::numeric_limits<double>::quiet_NaN();
  if (data.rank_a < n) {
    choice.method = Method::SpdTotalLeastSquares;
    choice.code = "rank_deficient_a";
    return choice;
  }
  // In the factor's units throughout (A_s = A 2^-ea with noise covariance Sigma_A 2^-2ea), and in
  // forms that a change of units A -> A D, B -> B D^-1 (X -> D^-1 X D^-1) leaves alone.
  // A's noise against its signal in its worst direction: max_v m v^T Sigma_A v / ||A v||^2, the
  // largest eigenvalue of m R11^-T Sigma_A R11^-1; snr is one over it, minus 1.
  const auto R = data.R11.triangularView<Eigen::Upper>();
  const Eigen::MatrixXd R_inv = R.solve(Eigen::MatrixXd::Identity(n, n));
  const Eigen::MatrixXd Z = symmetric_part(Eigen::MatrixXd(R_inv.transpose() * noise.cov_a * R_inv));
  const double noise_to_signal =
      static_cast<double>(m) * Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(Z, Eigen::EigenvaluesOnly).eigenvalues().maxCoeff();
  choice.snr = noise_to_signal > 0.0 ? std::max(1.0 / noise_to_signal - 1.0, 0.0)
                                     : std::numeric_limits<double>::infinity();
  bool negligible = noise.a_zero;
  if (!negligible && noise.b_definite) {
    const std::optional<double> bias = noise_in_a_bias(data, noise);
    negligible = bias && *bias <= kNegligibleNoiseBias;
  }
  if (negligible && noise.b_definite) {
    choice.method = Method::PsdLeastSquares;
    choice.code = "noise_in_b";
    return choice;
  }
  const double extra = static_cast<double>(m - n);
  const bool enough =
      extra >= kMinExtraRowsPerColumn * static_cast<double>(n) && extra * choice.snr >= kMinEvidence;
  choice.method = enough ? Method::SpdTotalLeastSquares : Method::Spde;
  choice.code = enough ? "many_samples" : "few_samples";
  return choice;
}

FitResult auto_settle(FitResult first, FitResult fallback, AutoReason& reason, double floor) {
  if (first.ok() && clearly_positive_definite(first.X)) return first;
  const std::string chosen(to_string(first.method));
  if (fallback.ok() && clearly_positive_definite(fallback.X)) {
    // The boundary (or no estimate): the least-squares fit over X >= floor I, positive definite.
    const std::string why = first.ok() ? chosen +
                                             " returned a matrix that is not positive definite (the infimum is "
                                             "on the boundary)"
                                       : chosen + " failed (" + first.message + ")";
    reason = AutoReason{"boundary", why + ": psd-ls with the floor " + format_number(floor) +
                                        " (1e-8 times the least-squares estimate's norm) instead"};
    fallback.warnings.insert(fallback.warnings.begin(), Warning(Code::Boundary, "auto: " + reason.text));
    return fallback;
  }
  const std::string fallback_failure =
      fallback.status == Status::NotComputed ? std::string("it cannot run here")
                                             : fallback.ok() ? std::string("its estimate is not positive definite either")
                                                             : fallback.message;
  if (!first.ok()) {
    first.message += "; psd-ls, auto's fallback, did not give an estimate either: " + fallback_failure;
    return first;
  }
  first.warnings.push_back(Warning(Code::NotPositiveDefinite, "auto: the estimate is not positive definite (smallest eigenvalue " +
                           format_number(first.diagnostics.min_eigenvalue.value_or(0.0)) + "): " + chosen +
                           " ended on the boundary, and psd-ls, auto's fallback, did not give a positive definite "
                           "estimate (" + fallback_failure + ")"));
  return first;
}

FitResult auto_settle_on_boundary(FitResult ml, AutoReason& reason) {
  const Eigen::Index rank = ml.diagnostics.boundary_certificate->rank;
  reason = AutoReason{
      "boundary",
      std::string(to_string(ml.method)) +
          " ended on the boundary (the likelihood's infimum over the positive definite matrices is at a singular "
          "matrix): its estimate, of rank " + std::to_string(rank) + " < n = " + std::to_string(ml.X.rows()) +
          ", is the constrained maximum-likelihood estimate over the positive semidefinite matrices, with the noise "
          "model's Sigma_A and Sigma_B (`certificate` holds its optimality conditions)"};
  ml.warnings.insert(ml.warnings.begin(), Warning(Code::Boundary, "auto: " + reason.text));
  return ml;
}

#define SPDFIT_INSTANTIATE(MaxN)                                                                          \
  template AutoChoice auto_choice<MaxN>(const BasicReduction<MaxN>&, std::optional<double>);           \
  template double auto_floor<MaxN>(const BasicReduction<MaxN>&);                                       \
  template bool clearly_positive_definite<SquareMatrix<MaxN>>(const SquareMatrix<MaxN>&);
SPDFIT_FOR_EACH_MAX_N(SPDFIT_INSTANTIATE)
#undef SPDFIT_INSTANTIATE

}  // namespace detail

namespace {

std::string reason_text(const detail::AutoChoice& choice, Index m, Index n) {
  const std::string snr = detail::format_number(choice.snr);
  const std::string rows = "m = " + std::to_string(m) + " rows for n = " + std::to_string(n);
  if (std::string(choice.code) == "rank_deficient_a") {
    return "A is rank-deficient, so spde is undefined: spd-tls, started from tls-sym";
  }
  if (std::string(choice.code) == "noise_free") {
    return "the data are consistent to rounding (signal-to-noise ratio " + snr +
           " in A's weakest direction): spde, exact on such data";
  }
  if (choice.method == Method::SpdTotalLeastSquares) {
    return rows + " and a signal-to-noise ratio of " + snr +
           " in A's weakest direction: enough data for total least squares, whose error keeps falling "
           "with m (spde's bias does not)";
  }
  return rows + " and a signal-to-noise ratio of " + snr +
         " in A's weakest direction: too few rows for total least squares to settle, so spde, whose "
         "scatter is smaller here";
}

// What auto assumed without a noise model, and how to give one.
std::string assumed_equal_text(const FitOptions& options) {
  const std::string assumed =
      options.noise_ratio == 1.0
          ? std::string("equal noise in every column of A and B")
          : "equal noise in every column of A, and `noise_ratio` = " + detail::format_number(options.noise_ratio) +
                " times it in every column of B";
  return "; it assumed " + assumed +
         ", in the units given: where sensors differ, give a noise model (`rest_a` and `rest_b`, rows recorded "
         "at rest; or `noise_std_a` and `noise_std_b`; or `noise_cov_a` and `noise_cov_b`)";
}

// Where the noise model came from, for auto's reason.
std::string noise_source_text(const NoiseModel& model) {
  switch (model.source()) {
    case NoiseSource::Rest:
      return "the noise model from the rest segment (" + std::to_string(model.rest_rows().value_or(0)) +
             " rows of `rest_a` and `rest_b`)";
    case NoiseSource::Std:
      return "the noise model from the standard deviations given (`noise_std_a`, `noise_std_b`)";
    case NoiseSource::Cov:
      return "the noise model from the covariances given (`noise_cov_a`, `noise_cov_b`)";
  }
  return "the noise model";
}

std::string noise_reason_text(const detail::AutoChoice& choice, const detail::DynamicReduction& data,
                              const NoiseModel& model) {
  const std::string source = noise_source_text(model);
  const std::string rows = "m = " + std::to_string(data.m) + " rows for n = " + std::to_string(data.n);
  const std::string snr = detail::format_number(choice.snr);
  if (std::string(choice.code) == "rank_deficient_a") {
    return "A is rank-deficient, so spde is undefined: spd-tls, the maximum-likelihood estimate with " + source +
           ", started from generalized tls-sym";
  }
  if (std::string(choice.code) == "noise_in_b") {
    return source + (model.a_is_zero() ? " has no noise in A" :
                     " has noise in A too small to matter against A's signal (the bias it gives least squares "
                     "is below a third of the standard error)") +
           ": psd-ls weighted by B's noise covariance, the maximum-likelihood estimate over the positive "
           "definite matrices when A is exact";
  }
  if (choice.method == Method::SpdTotalLeastSquares) {
    return rows + " and a signal-to-noise ratio of " + snr + " in A's weakest direction, with " + source +
           ": spd-tls, the maximum-likelihood estimate, whose error keeps falling with m";
  }
  return rows + " and a signal-to-noise ratio of " + snr + " in A's weakest direction: too few rows for a stable "
         "maximum-likelihood fit with " + source + ", so spde, whose scatter is smaller here; spde has no noise "
         "model: it assumes equal noise in every column of A and B, in the units given";
}

}  // namespace

FitResult auto_fit(const Reduction& reduction) {
  const detail::DynamicReduction& data = detail::data_of(reduction, Method::Auto);
  const Index n = data.n, m = data.m;
  const std::optional<detail::ScaledNoise> noise = detail::scaled_noise(data);
  detail::AutoChoice choice;
  AutoReason reason;
  if (noise) {
    choice = detail::auto_noise_choice(data, *noise);
    reason = AutoReason{choice.code, noise_reason_text(choice, data, *data.options.noise)};
  } else {
    const std::optional<double> noise_var = detail::data_noise_variance(data);
    choice = detail::auto_choice(data, noise_var);
    reason = AutoReason{choice.code, reason_text(choice, m, n) + assumed_equal_text(data.options)};
  }

  const double floor_s = detail::auto_floor(data);
  const double floor = std::ldexp(floor_s, data.exponent_b - data.exponent_a);
  FitResult result;
  switch (choice.method) {
    case Method::Spde:
      if (noise) {
        // spde has no noise model: it runs without, and says so.
        result = spde(detail::without_noise(reduction));
        result.warnings.push_back(Warning(Code::NoiseModelNotice, "auto: spde ran without the noise model (it has none): it assumes equal noise "
                                  "in every column of A and B, in the units given"));
        // The model auto chose by, and what its factory found, are still the result's.
        result.diagnostics.noise_model = data.options.noise;
        const std::vector<Warning>& found = data.options.noise->warnings();
        result.warnings.insert(result.warnings.begin(), found.begin(), found.end());
      } else {
        result = spde(reduction);
      }
      break;
    case Method::PsdLeastSquares:
      result = detail::psd_least_squares_scaled(data, floor_s);
      break;
    default:
      result = spd_total_least_squares(reduction);
  }
  const bool settled = result.ok() && detail::clearly_positive_definite(result.X);
  if (!settled && noise && result.ok() && result.diagnostics.boundary_certificate &&
      result.diagnostics.converged.value_or(false)) {
    // The likelihood's infimum on the boundary: spd-tls's constrained maximum-likelihood estimate,
    // where its first-order conditions hold (converged); otherwise the psd-ls fallback below.
    result = detail::auto_settle_on_boundary(std::move(result), reason);
  } else {
    // psd-ls with the floor, weighted by Sigma_B with a noise model (which needs Sigma_B > 0).
    FitResult fallback;
    if (!settled && (!noise || noise->b_definite)) fallback = detail::psd_least_squares_scaled(data, floor_s);
    result = detail::auto_settle(std::move(result), std::move(fallback), reason, floor);
  }
  result.diagnostics.chosen_method = result.method;
  result.diagnostics.reason = std::move(reason);
  return result;
}

FitResult auto_fit(const Eigen::Ref<const MatrixXd>& A, const Eigen::Ref<const MatrixXd>& B, const FitOptions& options) {
  return auto_fit(reduce(TriangularFactor::from_data(A, B), options));
}

}  // namespace spdfit
