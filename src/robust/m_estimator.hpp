// Internal: the robust fit (FitOptions::robust): an M-estimator of X by iteratively reweighted rows,
// each row weighed by its residual whitened by the noise model.
#pragma once

#include <Eigen/Core>
#include <optional>
#include <vector>

#include "spdfit/fit_options.hpp"
#include "spdfit/fit_result.hpp"
#include "spdfit/method.hpp"
#include "spdfit/triangular_factor.hpp"
#include "uncertainty/bootstrap.hpp"

namespace spdfit::detail {

/// Whether `method` takes row weights, and so `robust`: every method but spde (whose area
/// criterion is not a sum over rows).
constexpr bool robust_applies(Method method) { return method != Method::Spde; }

/// The loss's constant for d-dimensional whitened residuals (their norm u, in units of the noise's
/// standard deviation) at which the M-estimator keeps `efficiency` of least squares' at Gaussian
/// noise: for d = 1 Huber's 1.345 and Tukey's 4.685 at 0.95. A Gaussian row's residual norm is
/// chi-distributed with d degrees of freedom; a radial M-estimator with weight w(u) has efficiency
/// (E[w] + E[u w'] / d)^2 / (E[w^2 u^2] / d), computed by quadrature and solved for k by bisection.
double robust_tuning(RobustLoss loss, Eigen::Index d, double efficiency = 0.95);

/// The median of the chi distribution with d degrees of freedom: whitened residual norms' median
/// over it estimates the noise's scale.
double chi_median(Eigen::Index d);

/// The median of u over the rows of positive count (`counts` empty: all rows), NaN when there are
/// none: median()'s value, to the bit. Huber's reweighting moves it little from one iteration to
/// the next, so with `guess` (the last one; anything not positive: none) only the values within 10 %
/// of it are selected among when the middle ranks are there. `bracket` is its scratch buffer.
double median_near(const Eigen::VectorXd& u, const Eigen::VectorXd& counts, double guess, std::vector<double>& bracket);

/// A row's weight for its scaled residual norm u >= 0: Huber min(1, k / u), Tukey (1 - (u / k)^2)^2
/// below k and 0 beyond.
double robust_weight(RobustLoss loss, double u, double k);

/// robust_weight of every u(i) / scale (0 where scale is not positive), to the bit, in vectorized
/// passes instead of a call per row.
Eigen::VectorXd robust_weights(RobustLoss loss, const Eigen::VectorXd& u, double scale, double k);

/// robust_weights into `w` (its storage reused when it has as many rows as u).
void robust_weights_into(RobustLoss loss, const Eigen::VectorXd& u, double scale, double k, Eigen::VectorXd& w);

/// Least trimmed squares of B on [1 A] (with `intercept`) or A, whitened by `method`'s noise model:
/// the X and offsets c (empty without) whose h = (m + p + 1) / 2 smallest whitened residuals (p = n,
/// or n + 1 with an intercept) have the least sum of squares, approximately (FAST-LTS with a fixed
/// seed: the result depends on nothing else), and the robust scale of its residuals. Tukey's start.
struct TrimmedStart {
  Eigen::MatrixXd X;
  Eigen::VectorXd c;
  double scale = 0.0;
};
TrimmedStart least_trimmed_squares(const Eigen::Ref<const Eigen::MatrixXd>& A,
                                   const Eigen::Ref<const Eigen::MatrixXd>& B, bool intercept, Method method,
                                   const FitOptions& options);

/// What a robust fit did to the rows (FitResult::robust, PhysicalEstimate::robust), from its final
/// weights: the rows below 0.5 (1-based, at most 1000 listed, all counted) and the smallest.
RobustReport robust_report(RobustLoss loss, double k, const Eigen::VectorXd& weights, double scale, int iterations,
                           bool converged);

/// The robust fit of A, B (in the units fitted; options.offsets None or Estimate) by `method`
/// (robust_applies; auto chooses on the plain fit, spd-tls where it would choose spde), with
/// options.robust's loss: each iteration the method's own fit of the weighted rows (a Cholesky
/// factor of the weighted Gram matrix while the weights settle, the QR factor of the weighted
/// rows, TriangularFactor::append with weights, for the last), the residuals whitened by the noise
/// model and scaled by their robust scale (median over chi_median: re-estimated each iteration for
/// Huber, fixed at the start's for Tukey). Huber starts from the plain fit (from least trimmed
/// squares where the plain fit fails); Tukey from least
/// trimmed squares on the rows (FAST-LTS: elemental starts and concentration steps, a fixed seed),
/// so that rows whose A is wrong cannot capture the start. Stops when X moves by less than 1e-8 of
/// itself, or after options.max_iterations (converged false, a warning). With options.bootstrap,
/// each resample is refitted robustly from the estimate. `factor` is the last weighted fit's (for
/// the offsets c with an intercept).
struct RobustFit {
  FitResult result;
  std::optional<TriangularFactor> factor;
  /// With options.bootstrap: each replicate's estimate (result.bootstrap summarizes them), for
  /// what a caller derives from them (hexapod identify's modes).
  std::vector<Replicate> replicates;
};
RobustFit robust_fit(const Eigen::Ref<const Eigen::MatrixXd>& A, const Eigen::Ref<const Eigen::MatrixXd>& B,
                     Method method, const FitOptions& options);

}  // namespace spdfit::detail
