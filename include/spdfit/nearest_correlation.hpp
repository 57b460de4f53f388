// The nearest correlation matrix (positive semidefinite, unit diagonal) and the nearest
// covariance with a fixed diagonal.
#pragma once

#include <Eigen/Core>
#include <string>

#include "spdfit/nearest_spd.hpp"

namespace spdfit {

/// Options of nearest_correlation, nearest_keep_diagonal and nearest_via_correlation.
struct NearestCorrelationOptions {
  /// Diagonal weights w (n positive finite numbers): the distance is ||W^1/2 (X - C) W^1/2||_F with
  /// W = diag(w). Empty (the default): all ones, the Frobenius norm.
  Eigen::VectorXd weights;
  /// The smallest eigenvalue allowed, an exact constraint of the problem (not a clip afterwards).
  /// Absolute: X >= floor I, below every diagonal entry of the result. Relative: nearest_correlation
  /// X >= floor lambda_max I, lambda_max the largest eigenvalue of C's symmetric part; for the
  /// diagonal-keeping repairs it is a floor of the correlation matrix, D^-1/2 X D^-1/2 >= floor
  /// lambda_max I with D = diag(C) and lambda_max the largest eigenvalue of D^-1/2 C D^-1/2
  /// (nearest_keep_diagonal: X >= floor lambda_max D), below every variance whatever their
  /// units. Default 0: semidefinite.
  EigenvalueFloor floor;
  /// NAG g02ab's name for a unit diagonal's floor: the result is (1 - alpha) X~ + alpha I with
  /// X~ the nearest correlation matrix to (C - alpha I) / (1 - alpha), so every eigenvalue is
  /// >= alpha. That is exactly the absolute floor alpha (the same minimizer). In [0, 1); not
  /// together with a floor, and not for nearest_keep_diagonal.
  double alpha = 0.0;
  /// Newton iterations at most (each one symmetric eigendecomposition plus a conjugate-gradient
  /// solve); then the best iterate with converged = false and a warning. >= 1.
  int max_iterations = 200;
  /// Stop when the dual gradient ||diag(X) - d||_2 (in the weighted problem) is at most
  /// tolerance * sqrt(n) * max(d), or at most the rounding of its own evaluation when that is
  /// larger: 2 sqrt(n) eps ||G + diag(y)||_2 for the dual matrix G + diag(y) (C's entries far
  /// larger than d, as a covariance given for a correlation, can put it there). > 0.
  double tolerance = 1e-10;

  /// True when the options are usable for an n x n matrix; otherwise `error` says why.
  bool is_valid(Eigen::Index n, std::string* error = nullptr) const;
};

using NearestCorrelationResult = NearestResult;

/// The nearest correlation matrix to C: minimizes ||W^1/2 (X - C) W^1/2||_F over symmetric X with
/// unit diagonal and eigenvalues >= the floor (Higham 2002), by the quadratically convergent
/// Newton method on the dual of Qi & Sun (2006), with Borsdorf & Higham's (2010) improvements:
/// the Newton equation solved by preconditioned conjugate gradients (Jacobi preconditioner) and
/// a line search on the dual function. A final diagonal scaling makes the diagonal exactly 1.
/// C's symmetric part is used, with a warning when C is not symmetric to rounding (more often a
/// wrong file than noise).
///
/// Preconditions (else std::invalid_argument): C square, non-empty, finite; options as
/// documented; the floor below 1. Cost: O(n^3) per Newton iteration; typically under ten
/// iterations.
NearestResult nearest_correlation(const Eigen::Ref<const Eigen::MatrixXd>& C,
                                  const NearestCorrelationOptions& options = {});

/// The nearest symmetric matrix to C with C's diagonal and eigenvalues >= the floor (the same
/// Newton method): a covariance repair that keeps the variances. A relative floor is of the
/// correlation matrix (X >= floor lambda_max D, see NearestCorrelationOptions::floor; `min_eig` in
/// the result is that floor, in correlation units), so EigenvalueFloor::kRepairDefault is always
/// feasible and X factors by Cholesky. Preconditions as nearest_correlation, and C's diagonal
/// entries >= 0 and above an absolute floor, > 0 with a relative one; alpha 0.
NearestResult nearest_keep_diagonal(const Eigen::Ref<const Eigen::MatrixXd>& C,
                                    const NearestCorrelationOptions& options = {});

/// statsmodels' cov_nearest route: with D = diag(C)^1/2, repair the correlation D^-1 C D^-1 by
/// nearest_correlation (options, floor and weights apply to it) and return D X D. It keeps C's
/// diagonal, and is the nearest such matrix in the norm ||D^-1 (X - C) D^-1||_F (nearest_keep_diagonal
/// with weights 1 / diag(C)), not in C's Frobenius norm. `distance` is ||X - C||_F in C's units all
/// the same (with W^1/2 on both sides when weights are given), comparable with the other repairs'.
/// Preconditions as nearest_correlation, and C's diagonal entries > 0.
NearestResult nearest_via_correlation(const Eigen::Ref<const Eigen::MatrixXd>& C,
                                      const NearestCorrelationOptions& options = {});

}  // namespace spdfit
