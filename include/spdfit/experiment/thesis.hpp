// The thesis' numerical experiments (000, chapter 6), repeated as a Monte Carlo experiment.
#pragma once

#include <array>
#include <optional>
#include <string_view>
#include <vector>

#include <Eigen/Core>

#include "spdfit/experiment/monte_carlo.hpp"
#include "spdfit/experiment/statistics.hpp"
#include "spdfit/hexapod/simulate.hpp"
#include "spdfit/method.hpp"

namespace spdfit::experiment {

/// One of the thesis' experiments as it reports it: the noise variance and the Frobenius errors
/// ||M_p - M_hat||_F of its single run for symmetric Procrustes (eq. 6.6, 6.12, 6.18), TLS made
/// symmetric by eq. 4.38 (eq. 6.8, 6.14, 6.20) and SPD estimation (eq. 6.10, 6.16, 6.22).
struct ThesisReportedRun {
  int experiment;
  double noise_var;
  double procrustes, tls_sym, spde;
};

/// Experiments 1-3 (thesis chapter 6). The M-file draws uniform noise nm (rand - 0.5) with
/// nm = 1, 3.2, 3.9, variance nm^2/12 = 0.083, 0.853, 1.268; the text rounds to these.
inline constexpr std::array<ThesisReportedRun, 3> kThesisReportedRuns = {{
    {1, 0.082, 0.6755, 0.6899, 0.6630},
    {2, 0.86, 2.3610, 2.3007, 1.9689},
    {3, 1.28, 2.9120, 3.7761, 2.0083},
}};

/// The noise model the methods of an experiment are fitted with (FitOptions::noise).
enum class FitNoise {
  None,  ///< none: the methods assume equal noise in every column of A and B
  True,  ///< the generator's true covariances (hexapod::true_noise_model)
  Rest,  ///< the sample covariances of the trial's rest rows (SimulationOptions::rest_samples)
};

/// "none", "true" or "rest".
constexpr std::string_view to_string(FitNoise noise) {
  switch (noise) {
    case FitNoise::None:
      return "none";
    case FitNoise::True:
      return "true";
    case FitNoise::Rest:
      return "rest";
  }
  return "unknown";
}
std::optional<FitNoise> parse_fit_noise(std::string_view name);

/// The set-up of the thesis experiment: the appendix-B generator with M_p of eq. 6.1.
struct ThesisExperimentOptions {
  /// samples (m = 12), noise_var (required), signal_var (25/3), distribution (uniform).
  hexapod::SimulationOptions simulation;
  /// The true M_p; empty means thesis_mass_matrix() (eq. 6.1).
  Eigen::MatrixXd truth;
  /// The methods to run, in the order results list them (default: kSourceDocumentMethods, the
  /// thesis' six). Must be non-empty and without repeats.
  std::vector<Method> methods{kSourceDocumentMethods.begin(), kSourceDocumentMethods.end()};
  /// The noise models every method is fitted with, each in turn (results noise model by noise
  /// model, each with every method): with the per-column noise of simulation.noise_std_a and
  /// noise_std_b, {None, True, Rest} compares equal noise assumed, the true covariances and a rest
  /// segment's (Rest needs simulation.rest_samples >= 2). spde, which takes no noise model, runs
  /// with None only. Non-empty, without repeats.
  std::vector<FitNoise> noise_models{FitNoise::None};
};

/// One method's errors over the trials.
struct MethodErrors {
  Method method = Method::Spde;
  FitNoise noise = FitNoise::None;  ///< the noise model it was fitted with
  /// ||M_p - M_hat / scale_b||_F per trial (in the truth's units, whatever simulation.scale_b);
  /// NaN where the method failed
  std::vector<double> errors;
  Summary summary;             ///< of `errors`
};

/// The result of the thesis experiment.
struct ThesisExperimentResult {
  ThesisExperimentOptions options;  ///< as run (truth filled in)
  std::size_t trials = 0;
  std::uint64_t seed = 0;
  std::vector<MethodErrors> methods;  ///< in the options' order (noise model by noise model)

  /// The errors of `method` (fitted with `noise`); throws std::invalid_argument when it was not run.
  const MethodErrors& of(Method method, FitNoise noise = FitNoise::None) const;

  /// The method among `among` (fitted with `noise`) with the smallest mean error, the first of
  /// equal means. Throws std::invalid_argument when `among` is empty or names a method not run.
  Method best_of(const std::vector<Method>& among, FitNoise noise = FitNoise::None) const;

  /// Method a against b trial by trial (compare_paired of their errors), both fitted with
  /// `noise`; order_of says whether a is significantly more accurate. Throws
  /// std::invalid_argument for a method that was not run.
  PairedComparison compare(Method a, Method b, FitNoise noise = FitNoise::None) const;
};

/// Repeats the thesis experiment: in trial k, simulate (hexapod::simulate with the trial's own
/// Random) and run the options' estimators (experiment::estimate without a noise model, fit with
/// one); record each one's Frobenius error against the truth. Runs on options' threads; the numbers depend only on the seed (run_trials).
/// Throws std::invalid_argument on invalid options. Cost O(trials (m n^2 + n^3)).
ThesisExperimentResult run_thesis_experiment(const ThesisExperimentOptions& options,
                                             const MonteCarloOptions& monte_carlo);

}  // namespace spdfit::experiment
