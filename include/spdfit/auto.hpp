// The method the data call for: spde, spd-tls or psd-ls, chosen from the data alone.
#pragma once

#include <Eigen/Core>

#include "spdfit/fit_result.hpp"
#include "spdfit/reduction.hpp"

namespace spdfit {

/// Chooses among spde, spd-tls and psd-ls from the data (rows m, columns n, the noise estimate
/// against the weakest direction of the signal) and runs the chosen method; never returns a
/// matrix that is not positive definite.
///
/// - A rank-deficient: spde is undefined, so spd-tls (code "rank_deficient_a").
/// - Otherwise spd-tls when the data have enough rows for the noise they carry, m - n >= 4 n
///   and (m - n) snr >= 30 (code "many_samples"), else spde, whose bias is then smaller than
///   the scatter of the total least-squares fits (code "few_samples"). Here
///   snr = sigma_n(A)^2 / (m sigma^2) - 1 is the signal-to-noise ratio of the weakest direction of
///   A (sigma^2 the noise estimate, Diagnostics::noise_sigma); the thresholds come from the
///   Monte Carlo comparison in docs/guide.md. Data consistent to rounding (snr >= 1e10): spde,
///   exact there (code "noise_free").
/// - If the chosen method fails or returns a matrix that is not positive definite (the
///   criterion's infimum on the boundary), psd-ls with the floor 1e-8 ||X_ls||_F (X_ls the least-squares estimate) (code
///   "boundary"); if that fails too, the first failure is returned.
///
/// The result's `method` is the chosen one; diagnostics.chosen_method and diagnostics.reason
/// (code and text) say which and why. FitOptions::noise_ratio applies to spd-tls and the noise
/// estimate, FitOptions::max_iterations to spd-tls and psd-ls. Cost: that of the chosen method
/// plus one SVD of the 2n x 2n factor.
FitResult auto_fit(const Reduction& data);
FitResult auto_fit(const Eigen::Ref<const Eigen::MatrixXd>& A, const Eigen::Ref<const Eigen::MatrixXd>& B,
                   const FitOptions& options = {});

}  // namespace spdfit
