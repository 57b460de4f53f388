// The method the data call for: spde, spd-tls or psd-ls, chosen from the data and the noise model.
#pragma once

#include <Eigen/Core>

#include "spdfit/fit_result.hpp"
#include "spdfit/reduction.hpp"

namespace spdfit {

/// Chooses among spde, spd-tls and psd-ls from the data (rows m, columns n, the noise against the
/// weakest direction of the signal) and runs the chosen method. The estimate is positive definite,
/// or a warning says that it is not: with a noise model where the likelihood's infimum is on the
/// boundary (the constrained maximum-likelihood estimate, below), or when the chosen method ended
/// on the boundary and the fallback below failed too (which an eigensolver failure alone causes).
///
/// Without a noise model (FitOptions::noise), from the noise estimate (Diagnostics::noise_sigma),
/// assuming equal noise in every column of A and B in the units given (the reason's text says so
/// and how to give a noise model):
/// - A rank-deficient: spde is undefined, so spd-tls (code "rank_deficient_a").
/// - Otherwise spd-tls when the data have enough rows for the noise they carry, m - n >= 4 n
///   and (m - n) snr >= 30 (code "many_samples"), else spde, whose bias is then smaller than
///   the scatter of the total least-squares fits (code "few_samples"). Here
///   snr = sigma_n(A)^2 / (m sigma^2) - 1 is the signal-to-noise ratio of the weakest direction of
///   A (sigma^2 the noise estimate, Diagnostics::noise_sigma); the thresholds come from the
///   Monte Carlo comparison in docs/guide.md. Data consistent to rounding (snr >= 1e10): spde,
///   exact there (code "noise_free").
///
/// With a noise model (the reason's text names its source):
/// - A rank-deficient: spd-tls, the maximum-likelihood estimate (code "rank_deficient_a").
/// - A exact (Sigma_A = 0), or its noise negligible (the bias it gives least squares,
///   m (A^T A)^-1 Sigma_A X, below a third of a standard error per parameter on average, in the
///   Mahalanobis norm of least squares' covariance): psd-ls weighted by Sigma_B with the floor
///   below (code "noise_in_b").
/// - Otherwise the same rule as above with snr = min_v ||A v||^2 / (m v^T Sigma_A v) - 1 (with
///   Sigma_A = sigma^2 I the snr above):
///   spd-tls, the maximum-likelihood estimate (code "many_samples"), or with too few rows for a
///   stable likelihood fit spde, which runs without the noise model and says so (code
///   "few_samples").
///
/// With a noise model, where spd-tls ends on the boundary (the likelihood criterion has no
/// minimizer over the positive definite matrices), its estimate is the minimizer over the positive
/// semidefinite ones, of rank r < n: the constrained maximum-likelihood estimate, which honours
/// Sigma_A and follows the data's units. auto returns it (code "boundary"), with a warning, when
/// spd-tls converged (its optimality conditions, diagnostics.boundary_certificate, hold to 1e-8).
/// Otherwise, if the chosen method fails or returns a matrix that is not positive definite (the
/// criterion's infimum on the boundary, without a noise model), psd-ls (weighted by Sigma_B with
/// a noise model, which needs Sigma_B positive definite) with the floor 1e-8 ||X_ls||_F (X_ls the
/// least-squares estimate) (code "boundary"); if that fails too, the first failure is returned
/// (its message says that the fallback failed), or the first estimate with a warning that it is
/// not positive definite.
///
/// The result's `method` is the chosen one; diagnostics.chosen_method and diagnostics.reason
/// (code and text) say which and why; diagnostics.noise_model is the noise model auto chose by.
/// FitOptions::noise_ratio applies to spd-tls and the noise estimate, FitOptions::max_iterations
/// to spd-tls and psd-ls. With a noise model auto needs Sigma_A or Sigma_B positive definite
/// (else std::invalid_argument). The choice, and so the estimate, follow the data's units:
/// A -> a A D, B -> b B D^-1 with the noise converted alike gives (b / a) D^-1 X D^-1. Cost: that
/// of the chosen method plus one SVD of the 2n x 2n factor.
FitResult auto_fit(const Reduction& data);
FitResult auto_fit(const Eigen::Ref<const Eigen::MatrixXd>& A, const Eigen::Ref<const Eigen::MatrixXd>& B,
                   const FitOptions& options = {});

}  // namespace spdfit
