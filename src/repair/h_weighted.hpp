// Internal: the H-weighted nearest semidefinite matrix with fixed entries (NAG g02aj's problem, with
// a fixed set), by an augmented Lagrangian method (the engine of nearest_structured with
// elementwise weights).
#pragma once

#include <Eigen/Core>

#include "repair/fixed_entries.hpp"

namespace spdfit::detail {

/// What h_weighted_alm returns.
struct HWeightedResult {
  Eigen::MatrixXd X;       ///< positive semidefinite, with the fixed entries then set to their targets exactly
  int iterations = 0;      ///< semismooth Newton steps, in all
  int outer = 0;           ///< multiplier updates
  double kkt_residual = 0; ///< the largest relative KKT residual at the end (primal, dual)
  double residual = 0;     ///< how far the fixed entries of the semidefinite iterate were from their targets
  bool converged = false;
  Eigen::Index clipped = 0;  ///< zero eigenvalues of X (the rank of the multiplier Z)
  /// A lower bound on ||H o (X - G)||_F^2 / 2 over every admissible X (the dual function at the
  /// final multiplier, made dual-feasible); NaN where none could be formed.
  double dual_value = 0.0;
};

/// min ||H o (X - G)||_F^2 / 2 over symmetric X >= 0 with X_ij = B_ij on the pattern. The augmented
/// Lagrangian L_s(X, Z) = ||H o (X - G)||^2 / 2 + (||(Z - s X)_+||^2 - ||Z||^2) / (2 s) on the
/// constraint X >= 0 (multiplier Z >= 0): each subproblem min_X L_s over the free entries is
/// smooth with a semismooth gradient H o H o (X - G) - (Z - s X)_+, and is solved by Newton steps
/// with the generalized Hessian H o H o D + s J(D) (J the derivative of the projection at
/// Z - s X; conjugate gradients preconditioned by the same operator with H o H replaced by its
/// mean, which the eigenvectors invert exactly) and an Armijo search; then Z := (Z - s X)_+.
/// The iterate returned is the semidefinite -(Z - s X)_- / s, within the primal residual of X.
///
/// H, G, B symmetric; H >= 0 with max 1 (the caller scales it). Stops when both relative KKT
/// residuals (||X - its semidefinite part|| / (1 + ||X||), ||free part of H o H o (X - G) - Z|| /
/// (1 + ||H o H o G||)) are at most `tolerance`, or after `max_iterations` Newton steps. Throws
/// std::runtime_error when an eigendecomposition fails. Cost per Newton step: one
/// eigendecomposition and, per conjugate-gradient iteration, products of n x n by n x r matrices
/// (r = the rank of Z - s X's positive part, the number of eigenvalues the repair clips).
///
/// `X0` and `Z0` (both or neither), when given, start the iteration: a semidefinite X with the
/// fixed entries and a semidefinite multiplier, such as the solution of the problem with H
/// replaced by a rank-one h h^T (the diagonal weights' problem, which pattern_newton solves fast):
/// exact when H is of rank one on the free entries, and close when it nearly is, as overlap counts
/// of data missing at random are.
HWeightedResult h_weighted_alm(const Eigen::MatrixXd& G, const Eigen::MatrixXd& H, const FixedPattern& pattern,
                               const Eigen::MatrixXd& B, int max_iterations, double tolerance,
                               const Eigen::MatrixXd* X0 = nullptr, const Eigen::MatrixXd* Z0 = nullptr);

}  // namespace spdfit::detail
