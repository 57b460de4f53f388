#include "spdfit/auto.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "estimators/diagnostics.hpp"
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
  const Index n = data.n, m = data.m;
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

}  // namespace

FitResult auto_fit(const Reduction& reduction) {
  const detail::DynamicReduction& data = detail::data_of(reduction, Method::Auto);
  const Index n = data.n, m = data.m;
  const std::optional<double> noise_var = data.noise_var ? data.noise_var : detail::noise_variance(data);
  const detail::AutoChoice choice = detail::auto_choice(data, noise_var);
  AutoReason reason{choice.code, reason_text(choice, m, n)};

  FitResult result = choice.method == Method::Spde ? spde(reduction) : spd_total_least_squares(reduction);
  if (!result.ok() || !detail::clearly_positive_definite(result.X)) {
    // The boundary (or no estimate): the least-squares fit over X >= floor I, positive definite.
    const double floor_s = detail::auto_floor(data);
    const double floor = std::ldexp(floor_s, data.exponent_b - data.exponent_a);
    FitResult fallback = detail::psd_least_squares_scaled(data, floor_s);
    if (fallback.ok()) {
      const std::string why = result.ok() ? std::string(to_string(choice.method)) +
                                                " returned a matrix that is not positive definite (the infimum is "
                                                "on the boundary)"
                                          : std::string(to_string(choice.method)) + " failed (" + result.message + ")";
      reason = AutoReason{"boundary", why + ": psd-ls with the floor " + detail::format_number(floor) +
                                          " (1e-8 times the least-squares estimate's norm) instead"};
      fallback.warnings.insert(fallback.warnings.begin(), "auto: " + reason.text);
      result = std::move(fallback);
    }
  }
  result.diagnostics.chosen_method = result.method;
  result.diagnostics.reason = std::move(reason);
  return result;
}

FitResult auto_fit(const Eigen::Ref<const MatrixXd>& A, const Eigen::Ref<const MatrixXd>& B, const FitOptions& options) {
  return auto_fit(reduce(TriangularFactor::from_data(A, B), options));
}

}  // namespace spdfit
