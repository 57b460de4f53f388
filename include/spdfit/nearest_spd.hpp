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
/// Preconditions: X square, non-empty, finite; min_eig finite and >= 0 (else
/// std::invalid_argument). Cost: one symmetric eigendecomposition, O(n^3).
NearestSpdResult nearest_spd(const Eigen::Ref<const Eigen::MatrixXd>& X, double min_eig = 0.0);

}  // namespace spdfit
