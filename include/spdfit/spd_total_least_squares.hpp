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
/// With a noise model (FitOptions::noise: the covariances Sigma_A, Sigma_B of each row's noise in
/// A and B), the maximum-likelihood estimate of the errors-in-variables model over the symmetric
/// positive definite X: it minimizes
///
///     f(X) = sum_i r_i^T (X Sigma_A X + Sigma_B)^-1 r_i,   r_i the i-th row of A X - B,
///
/// by the same method (here the weight does not commute with X, and the start is the better of
/// SPDE and the positive definite projection of generalized tls-sym). Equal noise, Sigma_A =
/// s^2 I and Sigma_B = s^2 r^2 I, is the criterion above divided by s^2: the same estimate.
/// Sigma_A = 0 is least squares weighted by Sigma_B^-1 over the positive semidefinite matrices
/// (psd-ls's weighted problem). Where the infimum is on the boundary, the estimate is the
/// minimizer of f over the positive semidefinite matrices, of rank r < n (Newton's method on the
/// matrices of rank r, whose range turns as well as its eigenvalues move, r falling where an
/// eigenvalue leaves and rising where the multiplier of X >= 0 has a negative eigenvalue), with
/// the warning above and diagnostics.boundary_certificate: the constrained problem's first-order
/// conditions (BoundaryCertificate), each to about 1e-10 relative to f when converged; where they
/// do not hold to 1e-8, converged is false with a warning quoting them. An estimate that is not
/// singular has none. gradient_norm is then in the units of f, which is
/// dimensionless (about d (m - n) at the minimum when the noise model is right). Needs Sigma_A or
/// Sigma_B positive definite (else std::invalid_argument naming the options). The estimate follows
/// the data's units, on the boundary too: scaling A by a and B by b (and Sigma_A by a^2, Sigma_B by b^2) gives (b / a) X,
/// and A D, B D^-1 (Sigma_A -> D Sigma_A D, Sigma_B -> D^-1 Sigma_B D^-1) gives D^-1 X D^-1.
///
/// Preconditions: as least_squares. Cost: O(m n^2) for the factor, then O(n^6) per Newton step
/// (the Newton system has n (n + 1) / 2 unknowns; typically 3 to 8 steps from SPDE), so it is
/// meant for the small n of mass and stiffness matrices (n up to a few tens).
FitResult spd_total_least_squares(const Reduction& data);
FitResult spd_total_least_squares(const Eigen::Ref<const Eigen::MatrixXd>& A,
                                  const Eigen::Ref<const Eigen::MatrixXd>& B, const FitOptions& options = {});

}  // namespace spdfit
