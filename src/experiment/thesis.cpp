#include "spdfit/experiment/thesis.hpp"

#include <limits>
#include <stdexcept>
#include <string>

#include "spdfit/fit.hpp"
#include "spdfit/reduction.hpp"
#include "spdfit/triangular_factor.hpp"

namespace spdfit::experiment {

std::optional<FitNoise> parse_fit_noise(std::string_view name) {
  for (FitNoise noise : {FitNoise::None, FitNoise::True, FitNoise::Rest}) {
    if (to_string(noise) == name) return noise;
  }
  return std::nullopt;
}

const MethodErrors& ThesisExperimentResult::of(Method method, FitNoise noise) const {
  for (const MethodErrors& m : methods) {
    if (m.method == method && m.noise == noise) return m;
  }
  throw std::invalid_argument("ThesisExperimentResult: no results for method " + std::string(to_string(method)) +
                              " with noise model " + std::string(to_string(noise)));
}

Method ThesisExperimentResult::best_of(const std::vector<Method>& among, FitNoise noise) const {
  if (among.empty()) throw std::invalid_argument("ThesisExperimentResult::best_of: no methods to choose from");
  Method best = among.front();
  for (Method method : among) {
    if (of(method, noise).summary.mean < of(best, noise).summary.mean) best = method;
  }
  return best;
}

PairedComparison ThesisExperimentResult::compare(Method a, Method b, FitNoise noise) const {
  return compare_paired(of(a, noise).errors, of(b, noise).errors);
}

namespace {

// One run of the experiment: a method with a noise model.
struct Run {
  Method method;
  FitNoise noise;
};

}  // namespace

ThesisExperimentResult run_thesis_experiment(const ThesisExperimentOptions& options,
                                             const MonteCarloOptions& monte_carlo) {
  ThesisExperimentResult result;
  result.options = options;
  if (result.options.truth.size() == 0) result.options.truth = hexapod::thesis_mass_matrix();
  const Eigen::MatrixXd& truth = result.options.truth;
  std::string error;
  if (!options.simulation.is_valid(&error)) throw std::invalid_argument("thesis experiment: " + error);
  if (options.simulation.samples < truth.rows()) {
    throw std::invalid_argument("thesis experiment: need at least as many samples as M_p has columns (" +
                                std::to_string(truth.rows()) + ")");
  }
  check_methods(options.methods, "thesis experiment");
  if (options.noise_models.empty()) throw std::invalid_argument("thesis experiment: no noise models to fit with");
  std::vector<Run> runs;
  for (std::size_t i = 0; i < options.noise_models.size(); ++i) {
    const FitNoise noise = options.noise_models[i];
    for (std::size_t j = 0; j < i; ++j) {
      if (options.noise_models[j] == noise) {
        throw std::invalid_argument("thesis experiment: noise model " + std::string(to_string(noise)) +
                                    " is listed twice");
      }
    }
    if (noise == FitNoise::Rest && options.simulation.rest_samples < 2) {
      throw std::invalid_argument("thesis experiment: the noise model from rest rows needs rest_samples >= 2");
    }
    for (Method method : options.methods) {
      if (noise != FitNoise::None && method == Method::Spde) continue;  // spde takes no noise model
      runs.push_back({method, noise});
    }
  }
  if (runs.empty()) {
    throw std::invalid_argument("thesis experiment: spde takes no noise model: run it with the noise model none");
  }
  // The true covariances, checked against the truth's size before any trial.
  std::optional<NoiseModel> true_noise;
  for (FitNoise noise : options.noise_models) {
    if (noise == FitNoise::True) true_noise = hexapod::true_noise_model(options.simulation, truth.rows());
  }
  result.trials = monte_carlo.trials;
  result.seed = monte_carlo.seed;
  const double scale_b = options.simulation.scale_b;

  // The methods without a noise model share experiment::estimate (the small-problem path).
  std::vector<Method> plain;
  for (const Run& run : runs)
    if (run.noise == FitNoise::None) plain.push_back(run.method);

  const std::size_t run_count = runs.size();
  std::vector<std::vector<double>> errors(
      run_count, std::vector<double>(monte_carlo.trials, std::numeric_limits<double>::quiet_NaN()));
  run_trials(monte_carlo, [&](std::size_t k, Random& random) {
    // Each thread keeps its own matrices from trial to trial: no allocation per trial.
    thread_local hexapod::Measurements data;
    thread_local std::vector<Eigen::MatrixXd> X;
    hexapod::simulate_into(truth, options.simulation, random, data);
    auto record = [&](std::size_t i, const Eigen::MatrixXd& estimate) {
      if (estimate.size() > 0) errors[i][k] = (estimate / scale_b - truth).norm();  // trial k's own slot
    };
    if (!plain.empty()) {
      estimate(data.A, data.B, plain, X);
      std::size_t next = 0;
      for (std::size_t i = 0; i < run_count; ++i)
        if (runs[i].noise == FitNoise::None) record(i, X[next++]);
    }
    std::optional<TriangularFactor> factor;
    for (FitNoise noise : {FitNoise::True, FitNoise::Rest}) {
      std::optional<Reduction> reduction;
      for (std::size_t i = 0; i < run_count; ++i) {
        if (runs[i].noise != noise) continue;
        if (!reduction) {
          if (!factor) factor = TriangularFactor::from_data(data.A, data.B);
          FitOptions fit_options;
          fit_options.diagnostics = false;
          fit_options.noise = noise == FitNoise::True ? *true_noise : NoiseModel::from_rest(data.rest_A, data.rest_B);
          reduction = reduce(*factor, fit_options);
        }
        FitResult fitted = fit(*reduction, runs[i].method);
        if (fitted.ok()) record(i, fitted.X);
      }
    }
  });

  for (std::size_t i = 0; i < run_count; ++i) {
    MethodErrors m;
    m.method = runs[i].method;
    m.noise = runs[i].noise;
    m.summary = summarize(errors[i]);
    m.errors = std::move(errors[i]);
    result.methods.push_back(std::move(m));
  }
  return result;
}

}  // namespace spdfit::experiment
