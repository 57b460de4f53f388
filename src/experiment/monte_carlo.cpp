#include "spdfit/experiment/monte_carlo.hpp"

#include <stdexcept>

#include "estimators/small_problem.hpp"
#include "numerics/parallel.hpp"
#include "spdfit/fit.hpp"
#include "spdfit/reduction.hpp"
#include "spdfit/triangular_factor.hpp"

namespace spdfit::experiment {

bool MonteCarloOptions::is_valid(std::string* error) const {
  if (trials < 1) {
    if (error) *error = "the number of trials must be at least 1";
    return false;
  }
  return true;
}

void check_methods(const std::vector<Method>& methods, const std::string& what) {
  if (methods.empty()) throw std::invalid_argument(what + ": no methods to compare");
  for (std::size_t i = 0; i < methods.size(); ++i) {
    for (std::size_t j = 0; j < i; ++j) {
      if (methods[i] == methods[j]) {
        throw std::invalid_argument(what + ": method " + std::string(to_string(methods[i])) + " is listed twice");
      }
    }
  }
}

void run_trials(const MonteCarloOptions& options, const std::function<void(std::size_t, Random&)>& trial) {
  std::string error;
  if (!options.is_valid(&error)) throw std::invalid_argument("run_trials: " + error);
  detail::parallel_for(
      options.trials, options.threads,
      [&](std::size_t k) {
        Random random(trial_seed(options.seed, k));
        trial(k, random);
      },
      options.progress);
}

void estimate(const Eigen::Ref<const Eigen::MatrixXd>& A, const Eigen::Ref<const Eigen::MatrixXd>& B,
              const std::vector<Method>& methods, std::vector<Eigen::MatrixXd>& X) {
  if (detail::estimate_small(A, B, methods, X)) return;
  FitOptions options;
  options.diagnostics = false;
  const Reduction data = reduce(TriangularFactor::from_data(A, B), options);
  X.resize(methods.size());
  for (std::size_t i = 0; i < methods.size(); ++i) {
    FitResult result = fit(data, methods[i]);
    X[i] = result.ok() ? std::move(result.X) : Eigen::MatrixXd();
  }
}

}  // namespace spdfit::experiment
