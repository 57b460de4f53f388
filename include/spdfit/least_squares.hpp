// Unconstrained least squares, X = A^+ B.
#pragma once

#include <Eigen/Core>

#include "spdfit/fit_result.hpp"
#include "spdfit/reduction.hpp"

namespace spdfit {

/// The unconstrained least-squares estimate X = A^+ B, minimizing ||A X - B||_F
/// (thesis 000, section 3.1; lecture notes 002, sections 3.6-3.8).
///
/// Works from the data: with A of full column rank, X solves the triangular system
/// R11 X = R12 from the Householder QR of [A B]. When A is rank-deficient (rank r < n under
/// the options' cut-off), X is the minimum-norm solution V diag(1/sigma_i) U^T R12 from the SVD
/// of R11 with the small singular values edited to zero (notes 002, eq. 3.21), and a warning
/// says so. The estimate is in general neither symmetric nor definite. B may have d != n columns
/// (several right-hand sides, as numpy.linalg.lstsq): X is then n x d.
///
/// A noise model (FitOptions::noise) does not change X: A^+ B is the maximum-likelihood estimate of
/// an unconstrained X whatever B's noise covariance, and noise in A it ignores (a warning says so
/// when the model has some); the model changes only the diagnostics it reports.
///
/// Preconditions: A m x n, B m x d with m >= n >= 1, d >= 1, and finite entries (else
/// std::invalid_argument). Cost: O(m (n + d)^2) for the factor, O((n + d)^3) after it.
FitResult least_squares(const Reduction& data);
FitResult least_squares(const Eigen::Ref<const Eigen::MatrixXd>& A,
                        const Eigen::Ref<const Eigen::MatrixXd>& B, const FitOptions& options = {});

}  // namespace spdfit
