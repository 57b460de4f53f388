// Internal: auto's choice with a noise model, and its last step, which keeps its promise of a
// positive definite estimate or says that it could not.
#pragma once

#include <string>

#include "estimators/kernels.hpp"
#include "estimators/noise_weights.hpp"

namespace spdfit::detail {

/// auto's choice with a noise model: spd-tls, the maximum-likelihood estimate, where A is
/// rank-deficient ("rank_deficient_a") or has enough rows for its noise ("many_samples", the
/// thresholds of auto_choice with the signal-to-noise ratio snr = 1 / lambda_max(m R11^-T Sigma_A R11^-1) - 1,
/// the smallest of ||A v||^2 / (m v^T Sigma_A v) - 1); psd-ls weighted by Sigma_B where A is exact or
/// its noise negligible ("noise_in_b": the bias that Sigma_A gives least squares,
/// b = m (A^T A)^-1 Sigma_A X, in the Mahalanobis norm of least squares' covariance W (x) (A^T A)^-1,
/// W = X Sigma_A X + Sigma_B, is below a tenth of the n d parameters); else spde, which has no
/// noise model ("few_samples"). All of it is unchanged by a change of units A -> A D, B -> B D^-1.
/// O(n^3).
AutoChoice auto_noise_choice(const DynamicReduction& data, const ScaledNoise& noise);

/// auto's last step. `first` is the chosen method's result; `fallback` psd-ls with auto's floor
/// (a failed or default result where it could not run). Returns `first` when it is positive
/// definite beyond rounding; else `fallback` when it is, with `reason` rewritten to "boundary" and
/// a warning; else `first` as it is: when it failed, with the fallback's failure added to its
/// message, and when it succeeded, with a warning that the estimate is not positive definite.
FitResult auto_settle(FitResult first, FitResult fallback, AutoReason& reason, double floor);

/// auto's last step with a noise model where spd-tls ended on the boundary (`ml` succeeded and
/// converged, with a Diagnostics::boundary_certificate whose conditions hold): its estimate, the minimizer of the likelihood criterion over
/// the positive semidefinite matrices (rank r < n; no positive definite X has a lower criterion),
/// is the constrained maximum-likelihood estimate, and auto's: it honours Sigma_A and follows the
/// data's units, as psd-ls with an isotropic floor would not. `reason` becomes "boundary" and
/// the first warning says so.
FitResult auto_settle_on_boundary(FitResult ml, AutoReason& reason);

}  // namespace spdfit::detail
