#include "spdfit/experiment/thesis.hpp"

#include <limits>
#include <stdexcept>
#include <string>

namespace spdfit::experiment {

const MethodErrors& ThesisExperimentResult::of(Method method) const {
  for (const MethodErrors& m : methods) {
    if (m.method == method) return m;
  }
  throw std::invalid_argument("ThesisExperimentResult: no results for method " +
                              std::string(to_string(method)));
}

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
  result.trials = monte_carlo.trials;
  result.seed = monte_carlo.seed;

  const std::vector<Method>& methods = options.methods;
  const std::size_t method_count = methods.size();
  std::vector<std::vector<double>> errors(
      method_count, std::vector<double>(monte_carlo.trials, std::numeric_limits<double>::quiet_NaN()));
  run_trials(monte_carlo, [&](std::size_t k, Random& random) {
    // Each thread keeps its own matrices from trial to trial: no allocation per trial.
    thread_local hexapod::Measurements data;
    thread_local std::vector<Eigen::MatrixXd> X;
    hexapod::simulate_into(truth, options.simulation, random, data);
    estimate(data.A, data.B, methods, X);
    for (std::size_t i = 0; i < method_count; ++i) {
      if (X[i].size() > 0) errors[i][k] = (X[i] - truth).norm();  // trial k's own slot
    }
  });

  for (std::size_t i = 0; i < method_count; ++i) {
    MethodErrors m;
    m.method = methods[i];
    m.summary = summarize(errors[i]);
    m.errors = std::move(errors[i]);
    result.methods.push_back(std::move(m));
  }
  return result;
}

}  // namespace spdfit::experiment
