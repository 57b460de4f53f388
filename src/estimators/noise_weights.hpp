// Internal: what the estimators do with a noise model (FitOptions::noise): its covariances in the
// factor's scaled units, what each method needs of it, and the whitening that turns the methods
// that model noise in B only (procrustes, psd-ls) into their unweighted selves.
#pragma once

#include <Eigen/Core>
#include <optional>
#include <string>

#include "factor/basic_reduction.hpp"
#include "spdfit/method.hpp"

namespace spdfit::detail {

/// The noise model's covariances in the factor's units: Sigma_A 2^-2ea (the noise of A 2^-ea) and
/// Sigma_B 2^-2eb, with its classification (NoiseModel::a_is_zero, ...).
struct ScaledNoise {
  Eigen::MatrixXd cov_a, cov_b;
  bool a_zero = false, a_definite = false, b_definite = false;
};

/// data's noise model in its scaled units, or nothing without one. The model was resolved to the
/// data's sizes by reduce. Cost O(n^2).
std::optional<ScaledNoise> scaled_noise(const DynamicReduction& data);

// noise_refusal (declared in factor/basic_reduction.hpp, for data_of) says what each method needs
// of Sigma_A and Sigma_B, naming the options that gave them: spde takes no noise model; procrustes
// and psd-ls need Sigma_B > 0; tls, tls-sym and tls-psd need Sigma_B > 0 unless Sigma_A = 0;
// spd-tls and auto need Sigma_A > 0 or Sigma_B > 0 (X Sigma_A X + Sigma_B > 0 for every X > 0).
// ls takes any. data_of and fit_files throw OptionError with the refusal.

/// The bias that the noise model's Sigma_A gives least squares, b = m (A^T A)^-1 Sigma_A X (X the
/// least-squares estimate; its symmetric part when square), in units of least squares' scatter:
/// the Mahalanobis norm squared vec(b)^T Cov^-1 vec(b), Cov(vec X) = W (x) (A^T A)^-1 with
/// W = X^T Sigma_A X + Sigma_B, divided by the n d parameters (the mean squared bias per
/// parameter, in standard errors). Nothing where A is rank-deficient or W is not positive
/// definite. Unchanged by a change of units A -> A D, B -> B D^-1. O(n^3).
std::optional<double> noise_in_a_bias(const DynamicReduction& data, const ScaledNoise& noise);

/// Below this noise_in_a_bias, A's noise is negligible for the methods that model noise in B only
/// (on average below a third of a standard error per parameter): auto chooses psd-ls there, and
/// those methods do not warn that they ignore it. One threshold, so that the two never disagree.
inline constexpr double kNegligibleNoiseBias = 0.1;

/// The warning for a method that models noise in B only (ls, procrustes, psd-ls) given a noise
/// model whose noise in A is not negligible (noise_in_a_bias above kNegligibleNoiseBias, or
/// unknown), with the bias's size; or nothing.
std::optional<Warning> ignored_noise_warning(const DynamicReduction& data, Method method);

/// `data` without its noise model: the methods as they run without one (fit_all's spde).
Reduction without_noise(const Reduction& data);

/// The data of a method that models noise in B only, whitened: with C = Sigma_B^1/2 (symmetric),
/// the factor of [A C, (B - floor A) C^-1], so that min ||(A X - B) C^-1||_F over symmetric
/// X >= floor I is min ||A C Y - (B - floor A) C^-1||_F over symmetric Y >= 0 with
/// X = floor I + C Y C: the weighted problem is the unweighted one on these data. Needs
/// Sigma_B > 0 and d = n.
struct WhitenedB {
  DynamicReduction data;  ///< the whitened reduction, no noise model, exponents of its own
  Eigen::MatrixXd C_s;    ///< Sigma_B^1/2 in the original factor's units
  int shift = 0;          ///< X_s = floor_s I + 2^shift C_s Y_s C_s
  double floor_s = 0.0;   ///< the floor in the original factor's units
};
/// `vectors_a`: whether the whitened reduction needs R11's singular vectors. Cost O(n^3).
WhitenedB whiten_b(const DynamicReduction& data, const ScaledNoise& noise, double floor_s, bool vectors_a);
/// The estimate X_s in the original factor's units from the whitened one, Y_s. Exactly symmetric.
Eigen::MatrixXd unwhiten_b(const WhitenedB& w, const Eigen::MatrixXd& Y_s);

}  // namespace spdfit::detail
