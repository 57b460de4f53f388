// Multidimensional total least squares and its symmetric and semidefinite repairs.
#pragma once

#include <Eigen/Core>

#include "spdfit/fit_result.hpp"
#include "spdfit/reduction.hpp"

namespace spdfit {

/// The multidimensional total least-squares estimate X = -V12 V22^-1 (thesis 000, eq. 4.37),
/// where [V12; V22] are the right singular vectors of [A B] belonging to its d smallest
/// singular values (V12 n x d, V22 d x d; B has d columns, d = n for a square X). Computed from
/// the SVD of the (n + d) x (n + d) triangular factor R of [A B], which has the same singular
/// values and right singular vectors.
///
/// Failure (Status::NumericalFailure): V22 numerically singular (no TLS solution exists).
/// Warning: sigma_n and sigma_{n+1} of [A B] equal to within the rank cut-off, so that the
/// solution is not unique (Theorem 4.7's condition sigma_n > sigma_{n+1} fails).
/// TLS is not invariant under scaling A and B by different factors: scale them to comparable
/// noise levels first.
///
/// With a noise model (FitOptions::noise), generalized TLS (Van Huffel & Vandewalle): TLS of the
/// whitened data [A T_A, B Sigma_B^-1/2] (noise of unit variance in every column) and X mapped
/// back, the maximum-likelihood estimate of an unconstrained X; the directions in which A has no
/// noise (zero standard deviations, or Sigma_A's null space) are fitted by least squares (mixed
/// LS-TLS), and Sigma_A = 0 is least squares A^+ B. The tls_* diagnostics are then those of the
/// whitened data, in units of the noise's standard deviation (the correction norm is about
/// sqrt(d (m - n)) when the model is right). Needs Sigma_B positive definite unless Sigma_A = 0
/// (else std::invalid_argument naming the option). So do tls-sym and tls-psd below, which repair
/// this estimate.
///
/// Preconditions: as least_squares; a non-square X (d != n) also needs m >= n + d rows (else
/// std::invalid_argument). Cost: O(m (n + d)^2) for the factor, O((n + d)^3) after it.
FitResult total_least_squares(const Reduction& data);
FitResult total_least_squares(const Eigen::Ref<const Eigen::MatrixXd>& A,
                              const Eigen::Ref<const Eigen::MatrixXd>& B, const FitOptions& options = {});

/// The symmetric part (X_TLS + X_TLS^T) / 2 of the TLS estimate (thesis eq. 4.38): the nearest
/// symmetric matrix to it in the Frobenius norm. Fails where total_least_squares fails; needs
/// d = n (std::invalid_argument otherwise), as the repair below does.
FitResult total_least_squares_symmetric(const Reduction& data);
FitResult total_least_squares_symmetric(const Eigen::Ref<const Eigen::MatrixXd>& A,
                                        const Eigen::Ref<const Eigen::MatrixXd>& B,
                                        const FitOptions& options = {});

/// Higham's nearest symmetric positive semidefinite matrix to the TLS estimate
/// (thesis eq. 4.39, section 3.3; see nearest_spd). Fails where total_least_squares fails.
FitResult total_least_squares_psd(const Reduction& data);
FitResult total_least_squares_psd(const Eigen::Ref<const Eigen::MatrixXd>& A,
                                  const Eigen::Ref<const Eigen::MatrixXd>& B, const FitOptions& options = {});

}  // namespace spdfit
