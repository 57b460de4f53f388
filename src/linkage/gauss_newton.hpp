// Gauss-Newton with step halving for the small nonlinear least-squares problems of linkage
// synthesis (internal): the structural error (notes 002 eq. 3.18) and the dial zeros (eq. 3.7).
#pragma once

#include <functional>
#include <string>

#include <Eigen/Core>

namespace spdfit::linkage::detail {

/// Evaluates the weighted residual r(x) and, when J is not null, its Jacobian dr/dx. Returns
/// false when x is infeasible (e.g. the linkage cannot be assembled, or has no real lengths).
using ResidualModel = std::function<bool(const Eigen::VectorXd& x, Eigen::VectorXd& r, Eigen::MatrixXd* J)>;

struct GaussNewtonSettings {
  double tolerance = 1e-10;  ///< stop when ||Delta x|| < tolerance
  int max_iterations = 100;
  double threshold = -1.0;   ///< singular-value cut-off of each step (small_least_squares)
};

struct GaussNewtonOutcome {
  bool converged = false;
  std::string message;       ///< why not, in words
  Eigen::VectorXd x;
  int iterations = 0;        ///< steps taken
  double step_norm = 0.0;    ///< ||Delta x|| of the last step computed
  /// Converged with ||Delta x|| >= tolerance: in the tail the steps stopped shrinking (an
  /// ill-conditioned J amplifies rounding into steps larger than the tolerance).
  bool rounding_limited = false;
};

/// Minimizes 1/2 ||r(x)||^2 from the feasible start x0: each step solves J Delta x = -r in the
/// least-squares sense (small_least_squares) and takes the longest of Delta x, Delta x / 2, ...,
/// Delta x / 2^30 that is feasible and lowers the objective; once the step promises a decrease
/// below 1e-10 of the objective (the tail, where the objective's rounding hides the decrease) it
/// takes the full feasible step. It stops when ||Delta x|| < tolerance, or when the steps in the
/// tail stop shrinking (rounding_limited).
/// Fails (converged = false) when the iteration limit is reached, when no halving helps while
/// ||Delta x|| >= tolerance (unless the residual is already at rounding level), or when the
/// step is not finite. Preconditions: model(x0) feasible (else std::invalid_argument).
GaussNewtonOutcome gauss_newton(const ResidualModel& model, const Eigen::VectorXd& x0, const GaussNewtonSettings& settings);

}  // namespace spdfit::linkage::detail
