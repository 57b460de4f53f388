// Least squares over the symmetric positive semidefinite matrices (psd-ls), with a certificate.
#pragma once

#include <Eigen/Core>

#include "spdfit/fit_result.hpp"
#include "spdfit/reduction.hpp"

namespace spdfit {

/// The symmetric X minimizing ||A X - B||_F subject to X >= epsilon I, epsilon =
/// FitOptions::min_eig (0 by default: X positive semidefinite, possibly singular): the
/// positive-semidefinite Procrustes problem of stiffness and compliance identification. Where
/// symmetric Procrustes is already >= epsilon I, it is the answer (to rounding).
///
/// Method: from the triangular factor (never A^T A), in the eigenbasis of R11^T R11, where the
/// objective is a diagonal quadratic over the semidefinite cone: symmetric Procrustes if
/// feasible; else, for full-rank A, a semismooth Newton method on the cone's normal map
/// (preconditioned by a diagonal congruence; each step one symmetric eigendecomposition and a
/// conjugate-gradient solve on the face the iterate identifies, quadratically convergent where
/// the minimizer is strictly complementary). Where that does not pass the test below
/// (rank-deficient A, a degenerate minimizer at rounding level), spectral projected gradient
/// (Barzilai-Borwein steps with a non-monotone safeguard) goes on from its iterate, with exact
/// solves on the face of the cone the iterates identify once their rank settles. It stops when
/// the relative KKT residual
///
///     ||Y - P(Y - S / ||A^T A||_2)||_F ||A^T A||_2 / (||A^T A||_2 ||X||_F + ||A^T B||_F) <= 1e-12,
///
/// Y = X - epsilon I, S = sym(A^T A X - A^T B), P the projection onto the semidefinite cone (zero
/// exactly at the minimizer), or after FitOptions::max_iterations iterations with the feasible
/// iterate of smallest residual, converged = false and a warning.
///
/// Diagnostics: iterations, gradient_norm (the relative KKT residual), converged, and the
/// certificate (primal_min_eig, dual_min_eig, complementarity, duality_gap; see PsdCertificate),
/// computed from the returned X, from which a reader can check optimality. A rank-deficient A
/// makes the minimizer non-unique (a warning); the one returned has zero components in the
/// directions where A has no curvature on the identified face.
///
/// With a noise model (FitOptions::noise), weighted by B's noise covariance: it minimizes
/// sum_i r_i^T Sigma_B^-1 r_i (r_i the rows of A X - B) over symmetric X >= epsilon I, the same
/// problem for the data [A C, (B - epsilon A) C^-1], C = Sigma_B^1/2, with X = epsilon I + C Y C,
/// and the certificate is the weighted problem's (PsdCertificate). It models noise in B only: a
/// nonzero Sigma_A gives a warning saying that it is ignored. Needs Sigma_B positive definite
/// (else std::invalid_argument naming the option).
///
/// Preconditions: as least_squares. Cost: O(m n^2) for the factor, then O(n^3) per iteration
/// (0 when Procrustes is feasible; typically 3 to 5 Newton steps).
FitResult psd_least_squares(const Reduction& data);
FitResult psd_least_squares(const Eigen::Ref<const Eigen::MatrixXd>& A, const Eigen::Ref<const Eigen::MatrixXd>& B,
                            const FitOptions& options = {});

}  // namespace spdfit
