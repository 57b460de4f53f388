// Higham's nearest symmetric positive (semi)definite matrix.
#pragma once

#include <Eigen/Core>

namespace spdfit {

/// The result of nearest_spd.
struct NearestSpdResult {
  Eigen::MatrixXd X;                   ///< the nearest matrix; exactly symmetric
  double distance = 0.0;               ///< ||X_in - X||_F
  Eigen::Index clipped = 0;            ///< eigenvalues of the symmetric part raised to min_eig
  double min_eigenvalue_before = 0.0;  ///< of the symmetric part of the input
};

/// The nearest symmetric matrix to X (n x n) in the Frobenius norm whose eigenvalues are all
/// >= min_eig (Higham, "Computing a nearest symmetric positive semidefinite matrix", 1988;
/// thesis 000 section 3.3 and eq. 4.39). With S = (X + X^T)/2 = W diag(lambda) W^T, the answer is
/// W diag(max(lambda_i, min_eig)) W^T. With min_eig = 0 this is Higham's X_F = (S + H)/2, H the
/// symmetric polar factor of S: positive semidefinite. With min_eig > 0 it is strictly
/// positive definite, which is what covariance repair needs.
///
/// Computed in units where the largest entry is of order one (an exact power-of-two scaling), so
/// that entries anywhere from denormal to near the largest double work.
///
/// Preconditions: X square, non-empty, finite; min_eig finite and >= 0 (else
/// std::invalid_argument). Failure: std::runtime_error when the eigensolver does not converge or
/// the answer does not fit in a double (entries or min_eig within a factor n of the largest
/// double). Cost: one symmetric eigendecomposition, O(n^3).
NearestSpdResult nearest_spd(const Eigen::Ref<const Eigen::MatrixXd>& X, double min_eig = 0.0);

}  // namespace spdfit
