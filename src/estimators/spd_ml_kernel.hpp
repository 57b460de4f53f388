// Internal: the arithmetic of spd-tls with a noise model (FitOptions::noise), the maximum-likelihood
// estimate over the symmetric positive definite matrices: a Riemannian Newton method like
// spd_tls_kernel's, for a criterion whose weight does not commute with X.
#pragma once

#include <Eigen/Core>

#include "estimators/noise_weights.hpp"
#include "estimators/spd_tls_kernel.hpp"

namespace spdfit::detail {

/// The likelihood criterion of the errors-in-variables model (NoiseModel) for symmetric X_s, in
/// the factor's scaled units (where it has the same value as in the data's: it is dimensionless),
///
///     f(X) = sum_i r_i^T W^-1 r_i = tr(E W^-1),   W = X Sigma_A X + Sigma_B,
///     E = (R11 X - R12)^T (R11 X - R12) + R22^T R22 = (A X - B)^T (A X - B),
///
/// r_i the i-th row of A X - B: twice the negative log-likelihood, up to a constant, with the true
/// rows eliminated. With Sigma_A = I, Sigma_B = r^2 I it is spd_tls_criterion. NaN when W is not
/// positive definite. O(n^3).
double spd_ml_criterion(const DynamicReduction& data, const ScaledNoise& noise, const Eigen::MatrixXd& X_s);

/// Minimizes spd_ml_criterion over the symmetric positive definite X_s from the positive definite
/// X0_s, as spd_tls_kernel minimizes its criterion (the same trust-region Newton method in the
/// affine-invariant geometry with the exact Hessian, stopping rule and unbounded test), with `out`
/// in the same form (out.criterion is the likelihood criterion). Where eigenvalues head to zero
/// while f decreases (the infimum on the boundary), spd_ml_boundary continues to the minimizer over
/// the positive semidefinite matrices. Returns false as spd_tls_kernel does. O(n^6) per iteration
/// (the Hessian's Cholesky factorization; O(n^4) to form it), as spd_tls_kernel.
bool spd_ml_kernel(const DynamicReduction& data, const ScaledNoise& noise, int max_iterations,
                   const Eigen::MatrixXd& X0_s, SpdTlsKernel<Eigen::Dynamic>& out);

/// spd_ml_kernel from SPDE where rank_a == n and SPDE is positive definite, else from the positive
/// definite projection of generalized tls-sym (where Sigma_B > 0), in coordinates where the start
/// has a unit diagonal (an exact power-of-two congruence: the Newton method's tests of
/// definiteness and of the boundary then do not depend on the data's units). Returns false, with
/// out.iterations the steps taken, when no start is numerically positive definite or the run
/// fails.
bool spd_ml_solve(const DynamicReduction& data, const ScaledNoise& noise, int max_iterations,
                  SpdTlsKernel<Eigen::Dynamic>& out);

}  // namespace spdfit::detail
