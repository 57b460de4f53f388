// Total least squares over the symmetric positive definite matrices (spd-tls).
#pragma once

#include <Eigen/Core>

#include "spdfit/fit_result.hpp"
#include "spdfit/reduction.hpp"

namespace spdfit {

/// Total least squares with the positive definite constraint built in (the open problem of the
/// thesis, chapter 7): minimizes ||[dA dB/r]||_F^2 subject to (A + dA) X = B + dB over symmetric
/// positive definite X, r = FitOptions::noise_ratio. For symmetric X this is
///
///     f(X) = tr((A X - B)^T (A X - B) (r^2 I + X^2)^-1),
///
/// the squared distance of the rows of [A B/r] to the subspace {[a b] : a X = b} (for n = 1,
/// (a x - b)^2 / (r^2 + x^2)). Where the unconstrained TLS estimate is symmetric positive
/// definite, it is this minimizer; unlike tls-sym and tls-psd, the constraint is part of the fit,
/// so the estimate is consistent (its error falls as m grows) and positive definite.
///
/// Method: Riemannian Newton with a trust region in the affine-invariant geometry (steps
/// X^1/2 exp(S) X^1/2, exact Hessian), from SPDE, or where A is rank-deficient from the
/// semidefinite projection of tls-sym. f and its derivatives come from the triangular factor R
/// of [A B], never from Gram matrices. Stops when ||X^1/2 grad f(X) X^1/2||_F <= 1e-10 f(X)
/// (scale-invariant; or at the rounding level of the computed gradient on noise-free data), or
/// after FitOptions::max_iterations steps. Diagnostics: iterations, gradient_norm (that norm,
/// in the units of f), converged.
///
/// Not converged: the best iterate, converged = false, a warning (status Success). Infimum on
/// the boundary (f keeps decreasing as X becomes singular): the optimum on that face, a
/// semidefinite X, with a warning. Status::NumericalFailure when the infimum is at infinity
/// (f keeps decreasing as an eigenvalue passes 1e6 ||B|| / sigma_min(A): very noisy data with m
/// close to n), when there is no positive definite starting point (A rank-deficient and
/// tls-sym's projection singular, or TLS undefined), or when r 2^(exponent_a - exponent_b) is
/// out of floating-point range.
///
/// Accuracy: on noisy data the estimate is the criterion's minimizer to the stopping rule. On
/// noise-free data with an ill-conditioned A (cond(A) ~ 1e8) the iteration can stop where the
/// criterion is flat along A's weak directions, with relative errors up to ~1e-2 where spde is
/// exact to cond(A) eps; auto chooses spde for such data.
///
/// Preconditions: as least_squares. Cost: O(m n^2) for the factor, then O(n^6) per Newton step
/// (the Newton system has n (n + 1) / 2 unknowns; typically 3 to 8 steps from SPDE), so it is
/// meant for the small n of mass and stiffness matrices (n up to a few tens).
FitResult spd_total_least_squares(const Reduction& data);
FitResult spd_total_least_squares(const Eigen::Ref<const Eigen::MatrixXd>& A,
                                  const Eigen::Ref<const Eigen::MatrixXd>& B, const FitOptions& options = {});

}  // namespace spdfit
