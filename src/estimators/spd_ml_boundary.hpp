// Internal: spd-tls with a noise model where the likelihood's infimum over the positive definite
// matrices is on the boundary of the cone. The minimizer over the positive semidefinite X is a
// point of the constrained problem's first-order (KKT) conditions: with X = V_r Lambda V_r^T of
// rank r, V_0 an orthonormal basis of its null space and G = grad f(X),
//
//     V_r^T G V_r = 0 (stationarity on the face),  V_r^T G V_0 = 0 (the cross block),
//     V_0^T G V_0 >= 0 (the multiplier of X >= 0).
//
// spd_ml_boundary reaches one by Newton's method on the manifold of rank-r matrices, where the
// range of X turns as well as its eigenvalues move, changing r where an eigenvalue leaves (r - 1)
// or the multiplier has a negative eigenvalue (r + 1, along its eigenvector).
#pragma once

#include <Eigen/Core>

#include "estimators/spd_ml_model.hpp"
#include "estimators/spd_tls_kernel.hpp"
#include "spdfit/fit_result.hpp"

namespace spdfit::detail {

/// Minimizes the likelihood criterion (spd_ml_criterion) over the positive semidefinite X from
/// X = V_r diag(lambda) V_r^T, V_r the first r = lambda.size() columns of the orthogonal n x n V
/// (lambda > 0, r <= n), until the first-order conditions above hold to the stopping rule of
/// spd_ml_kernel (the manifold's Riemannian gradient ||X^1/2 grad f X^1/2|| restricted to its
/// tangent space <= 1e-10 f, or its rounding level; the multiplier's smallest eigenvalue, in the
/// same metric, >= -1e-10 f) or max_iterations steps. `infinity` is the eigenvalue beyond which
/// f decreasing means no minimizer (out.unbounded). Fills `out` as spd_ml_kernel does
/// (boundary_zeros = n - r at the end; converged: the conditions held); returns false when the
/// first point is not defined (W not positive definite) or an eigensolver fails. O(n^6) per
/// iteration (the Hessian's Cholesky factorization; O(n^4) to form it).
bool spd_ml_boundary(const spd_ml::Problem& pr, double infinity, int max_iterations, Eigen::MatrixXd V,
                     Eigen::VectorXd lambda, SpdTlsKernel<Eigen::Dynamic>& out);

/// The covariances with which the likelihood criterion is spd-tls's TLS criterion with the noise
/// ratio r (spd_tls_criterion): Sigma_A = I and Sigma_B = r^2 I (r2 = r^2 > 0), n x n.
ScaledNoise equal_scaled_noise(Eigen::Index n, double r2);

/// The first-order conditions above at X_s (symmetric positive semidefinite, in the factor's
/// units) taken as a matrix of rank `rank` (its largest eigenvalues; 0 < rank < n), as
/// BoundaryCertificate defines them: in the coordinates where X has a unit diagonal and relative
/// to f. NaN entries when f is not defined at X_s. O(n^3).
BoundaryCertificate spd_ml_certificate(const DynamicReduction& data, const ScaledNoise& noise,
                                       const Eigen::MatrixXd& X_s, Eigen::Index rank);

}  // namespace spdfit::detail
