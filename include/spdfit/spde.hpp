// The area-criterion estimate of a symmetric positive definite X (SPDE).
#pragma once

#include <Eigen/Core>

#include "spdfit/fit_result.hpp"
#include "spdfit/reduction.hpp"

namespace spdfit {

/// The symmetric positive definite estimate minimizing the area criterion
/// ||A Y - B Y^-T||_F^2 over X = Y Y^T (Chen & McInroy, Definition II.1): the unique SPD
/// solution of
///
///     X P X = Q,   P = A^T A,  Q = B^T B      (Theorem III.3, eq. 10-11; thesis eq. 5.24).
///
/// Computed from the data, not from P and Q (which square the condition number): with R11 and
/// R_b the triangular factors of A and B, X = R11^-1 H R11^-T where H is the symmetric polar
/// factor of M = R_b R11^T. In practice X = L L^T with L = R11^-1 V_M diag(s_M)^(1/2) from the
/// SVD of M, so that X is exactly symmetric and positive (semi)definite by construction. On
/// noise-free data the relative error is about cond(A) * eps. The diagnostics carry the
/// achieved area criterion and its closed-form minimum 2 tr(Sigma_Q~ - A^T B) (Corollary III.4),
/// which agree to rounding.
///
/// B of rank r < n: the positive semidefinite minimizer of rank exactly r (Corollary III.7),
/// with a warning. A rank-deficient: Status::NumericalFailure (the criterion has no minimizer).
///
/// spde has no noise model: with FitOptions::noise it throws std::invalid_argument naming auto and
/// spd-tls, which take one (fit_all runs it without the model and says so in its warnings).
///
/// Preconditions: as least_squares. Cost: O(m n^2) for the factor, O(n^3) after it.
FitResult spde(const Reduction& data);
FitResult spde(const Eigen::Ref<const Eigen::MatrixXd>& A, const Eigen::Ref<const Eigen::MatrixXd>& B,
               const FitOptions& options = {});

}  // namespace spdfit
