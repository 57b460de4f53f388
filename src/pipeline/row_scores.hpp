// Internal: the rows that dominate a fit in memory: a row whose residual, whitened by the noise
// model and studentized by its leverage, is far out among all rows' (median and MAD), as a gross
// error or a wrong row of A (a leverage point the fit follows) makes it.
#pragma once

#include <Eigen/Core>
#include <optional>
#include <vector>

#include "pipeline/row_numbers.hpp"
#include "spdfit/fit_options.hpp"
#include "spdfit/fit_result.hpp"
#include "spdfit/method.hpp"
#include "spdfit/outcome.hpp"
#include "spdfit/triangular_factor.hpp"

namespace spdfit::detail {

/// A row is named when the robust z-score of its score exceeds this: (score - median) / (1.4826
/// MAD). For Gaussian noise a row's probability of it is far below 1e-10, whatever the design: a
/// row of high leverage that agrees with the others has an ordinary studentized residual.
inline constexpr double kDominantZScore = 10.0;

/// Each row's residual a_i X + c - b_i (c: FitResult::offsets' with Offsets::Estimate, else 0)
/// whitened by the covariance the result's method models it with (X^T Sigma_A X + Sigma_B with a
/// noise model; X^T X + r^2 I for the methods that model noise in A, r the noise ratio; I for ls,
/// procrustes and psd-ls), divided by sqrt(1 - h_i), h_i the row's leverage in A (of the centred
/// A plus 1/m with an intercept), from `factor` (the fit's, of [A B] or [1 A B]). Empty when the
/// fit failed or there are too few rows (m <= n + 1). Cost O(m n (n + d)).
Eigen::VectorXd row_scores(const Eigen::Ref<const Eigen::MatrixXd>& A, const Eigen::Ref<const Eigen::MatrixXd>& B,
                           const FitResult& result, const TriangularFactor& factor, const FitOptions& options);

/// The covariance of a row's residual a_i X - b_i as `method` models the noise: X^T Sigma_A X +
/// Sigma_B with the noise model of `options`; X^T X + r^2 I (r the noise ratio) for the methods that
/// model noise in A (the total least-squares methods, spde, auto); I for ls, procrustes and psd-ls.
Eigen::MatrixXd residual_covariance(const Eigen::MatrixXd& X, Method method, const FitOptions& options);

/// Each row's whitened residual norm ||L^-1 (a_i X + c - b_i)||, L L^T = `covariance` (floored at
/// 1e-12 of its largest diagonal entry where singular); c empty: no offsets. O(m n d + m d^2).
Eigen::VectorXd whitened_residuals(const Eigen::Ref<const Eigen::MatrixXd>& A, const Eigen::Ref<const Eigen::MatrixXd>& B,
                                   const Eigen::MatrixXd& X, const Eigen::VectorXd& c, const Eigen::MatrixXd& covariance);

/// whitened_residuals into `out` (its storage reused when it has m rows: an iteration's).
void whitened_residuals_into(const Eigen::Ref<const Eigen::MatrixXd>& A, const Eigen::Ref<const Eigen::MatrixXd>& B,
                             const Eigen::MatrixXd& X, const Eigen::VectorXd& c, const Eigen::MatrixXd& covariance,
                             Eigen::VectorXd& out);

/// The median of `values` (not empty).
double median(std::vector<double> values);

/// 1.4826 times the median absolute deviation of `values` (not empty) from their median, which
/// `center` receives: a robust standard deviation. `values` is reordered and overwritten.
double robust_spread(std::vector<double>& values, double* center = nullptr);

/// Robust z-scores (x - median) / (1.4826 MAD); all 0 when the MAD is 0 or there are fewer than 3.
Eigen::VectorXd robust_z_scores(const Eigen::VectorXd& x);

/// The warning (code outliers) naming up to five rows (numbered as in their files by `numbers`) whose row_scores'
/// robust z-score is above kDominantZScore, with their z-scores; rows holding a value of magnitude
/// 1e30 or more (the sentinel warning's) are not named again. Nothing when none is, or when
/// options.diagnostics is off or the check would cost more than the fit's factorization left
/// unread (options.reported_diagnostics off and m n (n + d) above 1e8).
std::optional<Warning> dominant_rows_warning(const Eigen::Ref<const Eigen::MatrixXd>& A,
                                             const Eigen::Ref<const Eigen::MatrixXd>& B, const FitResult& result,
                                             const TriangularFactor& factor, const FitOptions& options,
                                             const RowNumbers& numbers = {});

}  // namespace spdfit::detail
