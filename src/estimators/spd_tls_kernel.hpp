// Internal: the arithmetic of spd-tls (spd_total_least_squares.hpp), a Riemannian Newton method
// over the symmetric positive definite matrices, as a kernel over the compile-time bound MaxN
// like the others in kernels.hpp (instantiated for every bound of SPDFIT_FOR_EACH_MAX_N).
#pragma once

#include <Eigen/Core>
#include <cmath>
#include <optional>

#include "estimators/kernels.hpp"

namespace spdfit::detail {

/// What spd_tls_kernel returns, in the factor's scaled units (see BasicReduction).
template <int MaxN>
struct SpdTlsKernel {
  SquareMatrix<MaxN> X_s;       ///< the estimate (positive definite, or semidefinite on the boundary)
  double criterion = 0.0;       ///< f(X_s) = tr(E (r_s^2 I + X_s^2)^-1)
  double gradient_norm = 0.0;   ///< ||X^1/2 grad f(X) X^1/2||_F at the last iterate
  int iterations = 0;           ///< Newton steps tried (accepted or not)
  bool converged = false;       ///< the stopping rule held
  Eigen::Index boundary_zeros = 0;  ///< eigenvalues set to zero: the infimum is on the boundary
  bool unbounded = false;  ///< no minimizer: f decreases as an eigenvalue grows without bound
};

/// The TLS criterion for symmetric X_s with noise ratio r_s, in scaled units:
///
///     f(X) = tr(E (r^2 I + X^2)^-1),   E = (R11 X - R12)^T (R11 X - R12) + R22^T R22,
///
/// the squared distance ||[dA dB/r]||_F^2 of the rows of [A B/r] to the subspace
/// {[a b] : a X = b} (for n = 1, (a x - b)^2 / (r^2 + x^2)). X_s symmetric, r_s > 0. O(n^3).
template <int MaxN>
double spd_tls_criterion(const BasicReduction<MaxN>& data, const SquareMatrix<MaxN>& X_s, double r_s);

/// Minimizes spd_tls_criterion over the symmetric positive definite X_s from the positive
/// definite start X0_s, by Newton's method in the affine-invariant geometry (trust region on
/// the step S of X^1/2 exp(S) X^1/2), until ||X^1/2 grad f X^1/2||_F <= 1e-10 f (or the
/// rounding level of the computed gradient) or max_iterations steps. Returns false, touching
/// nothing but `out.iterations`, when X0_s is not numerically positive definite (smallest
/// eigenvalue <= n eps times the largest) or the eigensolver fails. An infimum on the boundary
/// (eigenvalues heading to 0 while f decreases) continues on the face without them (where an
/// infimum at infinity stops with `unbounded`, as in the interior), then from the face's minimizer
/// to the minimizer over the positive semidefinite matrices (spd_ml_boundary with Sigma_A = I,
/// Sigma_B = r^2 I, in dynamic matrices), kept where its criterion is lower; boundary_zeros is the
/// estimate's rank deficiency.
/// O(n^3) per iteration in the interior, O(n^6) on the boundary.
template <int MaxN>
bool spd_tls_kernel(const BasicReduction<MaxN>& data, double r_s, int max_iterations,
                    const SquareMatrix<MaxN>& X0_s, SpdTlsKernel<MaxN>& out);

/// The noise ratio r_s = options.noise_ratio 2^(exponent_a - exponent_b) in the factor's units
/// (there A_s = A 2^-ea, B_s = B 2^-eb, X_s = X 2^(ea - eb), so r^2 I + X^2 = 2^2(eb-ea)
/// (r_s^2 I + X_s^2)), or nothing when r_s^2 is out of floating-point range.
template <int MaxN>
std::optional<double> spd_tls_noise_ratio(const BasicReduction<MaxN>& data) {
  const double r_s = std::ldexp(data.options.noise_ratio, data.exponent_a - data.exponent_b);
  if (!(r_s > 0.0) || !std::isfinite(r_s * r_s) || r_s * r_s == 0.0) return std::nullopt;
  return r_s;
}

/// spd-tls from its starts, as spd_total_least_squares and the small-problem path run it: from
/// SPDE where rank_a == n and SPDE is positive definite, else from the positive semidefinite
/// projection of tls-sym (Higham). Returns false, with out.iterations the steps taken, when
/// neither start is numerically positive definite. O(n^3) per iteration.
template <int MaxN>
bool spd_tls_solve(const BasicReduction<MaxN>& data, double r_s, int max_iterations, SpdTlsKernel<MaxN>& out);

}  // namespace spdfit::detail
