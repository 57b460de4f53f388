// Internal: Qi and Sun's Newton method on the dual of the nearest semidefinite matrix with a set of
// entries fixed (the engine of nearest_structured without elementwise weights).
#pragma once

#include <Eigen/Core>
#include <limits>
#include <vector>

#include "repair/fixed_entries.hpp"

namespace spdfit::detail {

/// What pattern_newton returns.
struct PatternNewtonResult {
  Eigen::MatrixXd X;           ///< (G + A^* y)_+ with the fixed entries then set to their targets exactly
  int iterations = 0;          ///< Newton steps taken
  double residual = 0.0;       ///< ||A(X) - b||_2 in entry units, before the fixed entries were set
  bool converged = false;      ///< residual met the stopping test
  bool infeasible = false;     ///< the dual value passed `infeasible_above`: no admissible X exists
  Eigen::Index clipped = 0;    ///< eigenvalues of G + A^* y at or below 0
  double dual_value = 0.0;     ///< b^T y - ||(G + A^* y)_+||^2 / 2 + ||G||^2 / 2 <= ||X - G||^2 / 2 for every admissible X
  /// Not converged because the multipliers diverge (the kept entries seem to admit only singular
  /// completions): the rows where the direction every admissible X must annihilate is largest.
  std::vector<Eigen::Index> singular_rows;
};

/// min ||X - G||_F^2 / 2 over symmetric X >= 0 with X_ij = B_ij on the pattern (each lower-triangle
/// entry (i, j) also fixes (j, i)), by Newton's method on the dual theta(y) = ||(G + A^* y)_+||_F^2 / 2
/// - b^T y (Qi & Sun 2006 for the diagonal; Qi & Sun 2010 for a general fixed set), A^* y =
/// sum_p y_p E_p with E_p = e_i e_j^T + e_j e_i^T (e_i e_i^T on the diagonal). The Newton equation is
/// solved by conjugate gradients with the Jacobian's (approximate) diagonal as preconditioner, and
/// the step by an Armijo search on theta. Starts where G + A^* y has the targets.
///
/// Stops when ||A(X) - b|| (entry units) is at most `tolerance` or its own rounding level, after
/// `max_iterations` steps, or when the dual value exceeds `infeasible_above` (the problem then
/// has no solution: the dual is unbounded). With `multiplier`, it gets the multiplier of X >= 0,
/// Z = -(G + A^* y)_- (semidefinite, Z X = 0 at the solution). G and B symmetric. Throws std::runtime_error when an
/// eigendecomposition fails. Cost per step: one eigendecomposition and, per conjugate-gradient
/// iteration, products of n x n by n x r matrices (r positive eigenvalues) and O(m r) for the m
/// fixed entries.
PatternNewtonResult pattern_newton(Eigen::MatrixXd G, const FixedPattern& pattern, const Eigen::MatrixXd& B,
                                   int max_iterations, double tolerance,
                                   double infeasible_above = std::numeric_limits<double>::infinity(),
                                   Eigen::MatrixXd* multiplier = nullptr);

}  // namespace spdfit::detail
