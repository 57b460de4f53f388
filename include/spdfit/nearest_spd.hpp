// Higham's nearest symmetric positive (semi)definite matrix, and what every repair reports.
#pragma once

#include <Eigen/Core>
#include <optional>
#include <string>
#include <vector>

#include "spdfit/outcome.hpp"

namespace spdfit {

/// The smallest eigenvalue a repair allows: `value` itself, or with `relative` set, value times
/// the largest eigenvalue of the input's symmetric part (so that repairing s C gives s X); the
/// diagonal-keeping repairs apply a relative floor to the correlation matrix instead (see
/// NearestCorrelationOptions::floor).
struct EigenvalueFloor {
  double value = 0.0;
  bool relative = false;

  /// The relative floor that spdfit's `nearest` command and Python's nearest_spd and
  /// nearest_correlation use when none is given (as R's nearPD's posd.tol): the result is then
  /// positive definite, so that its Cholesky factorization succeeds.
  static constexpr double kRepairDefault = 1e-8;
  static EigenvalueFloor absolute(double value) { return {value, false}; }
  static EigenvalueFloor relative_to_largest(double value) { return {value, true}; }
  /// The floor of a repair from what its user gave (the `nearest` command and Python share this
  /// rule): `min_eig` absolute, `min_eig_rel` relative, neither the relative kRepairDefault; with
  /// `alpha_given` (NAG's alpha is the floor itself) the floor 0. std::invalid_argument when more
  /// than one is given.
  static EigenvalueFloor chosen(std::optional<double> min_eig, std::optional<double> min_eig_rel, bool alpha_given);

  /// True when value is finite and >= 0 (and < 1 when relative); otherwise `error` says why.
  bool is_valid(std::string* error = nullptr) const;
};

/// What a repair returns: the nearest matrix and how it was reached.
struct NearestResult {
  Eigen::MatrixXd X;                   ///< the nearest matrix; exactly symmetric
  double distance = 0.0;               ///< from the input: ||X_in - X||_F (weighted where weights are given)
  Eigen::Index clipped = 0;            ///< eigenvalues raised to the floor (the Newton methods: those at it)
  double min_eigenvalue_before = 0.0;  ///< of the symmetric part of the input
  double min_eig = 0.0;                ///< the floor applied, in the input's units (a relative floor resolved); of the correlation matrix for via_corr, and for keep_diag with a relative floor
  int iterations = 0;                  ///< Newton iterations (0: the direct eigenvalue clip)
  double gradient_norm = 0.0;          ///< the Newton methods' final ||diag(X) - d||_2 before the rescaling
  bool converged = true;               ///< the Newton methods: gradient_norm met the stopping test (NearestCorrelationOptions::tolerance)
  bool cholesky_ok = false;            ///< whether X has a Cholesky factorization (positive definite)
  std::vector<Warning> warnings;   ///< asymmetric input, a floor that moved X more than the repair, ...
};
using NearestSpdResult = NearestResult;

/// The nearest symmetric matrix to X (n x n) in the Frobenius norm whose eigenvalues are all
/// >= the floor (Higham, "Computing a nearest symmetric positive semidefinite matrix", 1988;
/// thesis 000 section 3.3 and eq. 4.39). With S = (X + X^T)/2 = W diag(lambda) W^T, the answer is
/// W diag(max(lambda_i, floor)) W^T. With floor 0 this is Higham's X_F = (S + H)/2, H the
/// symmetric polar factor of S: positive semidefinite. With a floor > 0 it is strictly
/// positive definite, which is what covariance repair needs.
///
/// Computed in units where the largest entry is of order one (an exact power-of-two scaling), so
/// that entries anywhere from denormal to near the largest double work. Warns (in `warnings`)
/// when X is not symmetric to rounding, when the floor moves X by more than the repair itself
/// (a floor too large for the matrix's scale), and when it raised eigenvalues to the floor (how
/// many, and the floor).
///
/// Preconditions: X square, non-empty, finite; min_eig finite and >= 0; a relative floor < 1 and
/// a largest eigenvalue > 0 (else std::invalid_argument). Failure: std::runtime_error when the
/// eigensolver does not converge or the answer does not fit in a double (entries or min_eig
/// within a factor n of the largest double). Cost: one symmetric eigendecomposition, O(n^3).
NearestResult nearest_spd(const Eigen::Ref<const Eigen::MatrixXd>& X, EigenvalueFloor floor);
/// nearest_spd with the absolute floor min_eig (the default 0: the nearest semidefinite matrix).
NearestResult nearest_spd(const Eigen::Ref<const Eigen::MatrixXd>& X, double min_eig = 0.0);

}  // namespace spdfit
