// The symmetric Procrustes problem: the symmetric X minimizing ||A X - B||_F.
#pragma once

#include <Eigen/Core>

#include "spdfit/fit_result.hpp"
#include "spdfit/reduction.hpp"

namespace spdfit {

/// The symmetric X minimizing ||A X - B||_F, i.e. the solution of the Lyapunov equation
///
///     A^T A X + X A^T A = A^T B + B^T A          (thesis 000, eq. 3.15)
///
/// computed from the data, not from A^T A: with R11 = U diag(sigma) V^T and C = U^T R12 V,
/// the entries of V^T X V are (sigma_i c_ij + sigma_j c_ji) / (sigma_i^2 + sigma_j^2)
/// (Higham, "The symmetric Procrustes problem", 1988). The diagnostics report whether
/// A^T B + B^T A is positive definite, in which case X is too (thesis Theorem 3.2 (3)); a
/// warning says when X is not positive definite.
///
/// Rank-deficient A: the minimizer is not unique; X is the one of minimum Frobenius norm
/// (entries with sigma_i = sigma_j = 0 set to zero), with a warning.
///
/// With a noise model (FitOptions::noise), weighted by B's noise covariance: the symmetric X
/// minimizing sum_i r_i^T Sigma_B^-1 r_i, r_i the rows of A X - B (X = C Y C with Y the estimate
/// for [A C, B C^-1], C = Sigma_B^1/2; cross_term_positive_definite is then that of these data).
/// As psd-ls, a nonzero Sigma_A gives a warning and Sigma_B must be positive definite.
///
/// Preconditions: as least_squares. Cost: O(m n^2) for the factor, O(n^3) after it.
FitResult symmetric_procrustes(const Reduction& data);
FitResult symmetric_procrustes(const Eigen::Ref<const Eigen::MatrixXd>& A,
                               const Eigen::Ref<const Eigen::MatrixXd>& B, const FitOptions& options = {});

}  // namespace spdfit
