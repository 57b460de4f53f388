#include "spdfit/experiment/paper.hpp"

#include <cmath>
#include <functional>
#include <limits>
#include <stdexcept>
#include <string>

namespace spdfit::experiment {

namespace {

using Generate = std::function<void(Random&, Eigen::MatrixXd& A, Eigen::MatrixXd& B)>;

// The shared loop of both experiments: generate (A, B), run every estimator, record the signed
// errors of the independent entries for the chosen methods.
EntryExperimentResult run_entry_experiment(const Eigen::MatrixXd& truth, const std::vector<Method>& methods,
                                           const MonteCarloOptions& monte_carlo, const Generate& generate) {
  check_methods(methods, "experiment");
  EntryExperimentResult result;
  result.trials = monte_carlo.trials;
  result.seed = monte_carlo.seed;
  result.truth = truth;
  result.entries = upper_triangle_entries(truth.rows());
  const Eigen::Index entry_count = static_cast<Eigen::Index>(result.entries.size());

  std::vector<Eigen::MatrixXd> errors(
      methods.size(), Eigen::MatrixXd::Constant(static_cast<Eigen::Index>(monte_carlo.trials), entry_count,
                                                std::numeric_limits<double>::quiet_NaN()));
  run_trials(monte_carlo, [&](std::size_t k, Random& random) {
    // Each thread keeps its own matrices from trial to trial: no allocation per trial.
    thread_local Eigen::MatrixXd A, B;
    thread_local std::vector<Eigen::MatrixXd> X;
    generate(random, A, B);
    estimate(A, B, methods, X);
    for (std::size_t i = 0; i < methods.size(); ++i) {
      if (X[i].size() == 0) continue;  // the method failed on this trial
      for (Eigen::Index e = 0; e < entry_count; ++e) {
        const auto [r, c] = result.entries[static_cast<std::size_t>(e)];
        errors[i](static_cast<Eigen::Index>(k), e) = X[i](r, c) - truth(r, c);  // trial k's own row
      }
    }
  });
  for (std::size_t i = 0; i < methods.size(); ++i) {
    result.methods.push_back(summarize_entries(methods[i], std::move(errors[i])));
  }
  return result;
}

}  // namespace

const EntryStatistics& EntryExperimentResult::of(Method method) const {
  for (const EntryStatistics& m : methods) {
    if (m.method == method) return m;
  }
  throw std::invalid_argument("experiment result: method " + std::string(to_string(method)) + " was not run");
}

std::vector<PairedComparison> EntryExperimentResult::compare(Method a, Method b) const {
  const EntryStatistics &x = of(a), &y = of(b);
  std::vector<PairedComparison> out;
  std::vector<double> abs_a(static_cast<std::size_t>(x.errors.rows())), abs_b(static_cast<std::size_t>(y.errors.rows()));
  for (Eigen::Index e = 0; e < x.errors.cols(); ++e) {
    for (Eigen::Index k = 0; k < x.errors.rows(); ++k) abs_a[static_cast<std::size_t>(k)] = std::abs(x.errors(k, e));
    for (Eigen::Index k = 0; k < y.errors.rows(); ++k) abs_b[static_cast<std::size_t>(k)] = std::abs(y.errors(k, e));
    out.push_back(compare_paired(abs_a, abs_b));
  }
  return out;
}

EntryExperimentResult::Wins EntryExperimentResult::wins(Method a, Method b) const {
  const EntryStatistics &x = of(a), &y = of(b);
  Wins out;
  out.mae = static_cast<std::size_t>((x.mae.array() < y.mae.array()).count());
  out.std = static_cast<std::size_t>((x.std.array() < y.std.array()).count());
  out.entries = entries.size();
  return out;
}

EntryExperimentResult run_paper_hexapod(const PaperHexapodOptions& options,
                                        const MonteCarloOptions& monte_carlo) {
  const Eigen::MatrixXd truth = options.truth.size() ? options.truth : hexapod::thesis_mass_matrix();
  std::string error;
  if (!options.simulation.is_valid(&error)) throw std::invalid_argument("paper-hexapod experiment: " + error);
  if (options.simulation.samples < truth.rows()) {
    throw std::invalid_argument("paper-hexapod experiment: need at least as many samples as M_p has columns");
  }
  return run_entry_experiment(
      truth, options.methods, monte_carlo, [&](Random& random, Eigen::MatrixXd& A, Eigen::MatrixXd& B) {
        hexapod::Measurements data = hexapod::simulate(truth, options.simulation, random);
        A = std::move(data.A);
        B = std::move(data.B);
      });
}

Eigen::MatrixXd paper_2x2_truth() { return (Eigen::MatrixXd(2, 2) << 3.0, 1.0, 1.0, 1.0).finished(); }

Eigen::MatrixXd paper_2x2_design() {
  // The paper prints A transposed: [5 -3 1 -1; 2 1 -2 1]; B0 = A0 X = [17 -8 1 -2; 7 -2 -1 0]^T.
  return (Eigen::MatrixXd(4, 2) << 5.0, 2.0, -3.0, 1.0, 1.0, -2.0, -1.0, 1.0).finished();
}

EntryExperimentResult run_paper_2x2(const Paper2x2Options& options, const MonteCarloOptions& monte_carlo) {
  if (!(options.std_a >= 0.0) || !std::isfinite(options.std_a) || !(options.std_b >= 0.0) ||
      !std::isfinite(options.std_b)) {
    throw std::invalid_argument(
        "paper-2x2 experiment: the noise standard deviations must be finite and >= 0");
  }
  const Eigen::MatrixXd X = paper_2x2_truth();
  const Eigen::MatrixXd A0 = paper_2x2_design();
  const Eigen::MatrixXd B0 = A0 * X;
  return run_entry_experiment(
      X, options.methods, monte_carlo, [&](Random& random, Eigen::MatrixXd& A, Eigen::MatrixXd& B) {
        A = A0;
        B = B0;
        hexapod::add_noise(A, options.std_a * options.std_a, hexapod::NoiseDistribution::Gaussian, random);
        hexapod::add_noise(B, options.std_b * options.std_b, hexapod::NoiseDistribution::Gaussian, random);
      });
}

std::vector<double> paper_2x2_sweep_levels() {
  std::vector<double> levels;
  for (int k = 0; k < 20; ++k) levels.push_back(k / 10.0);
  return levels;
}

std::vector<EntryExperimentResult> run_paper_2x2_sweep(const Paper2x2Options& options,
                                                       const std::vector<double>& std_a_levels,
                                                       const MonteCarloOptions& monte_carlo) {
  std::vector<EntryExperimentResult> results;
  for (double std_a : std_a_levels) {
    Paper2x2Options level = options;
    level.std_a = std_a;
    results.push_back(run_paper_2x2(level, monte_carlo));
  }
  return results;
}

}  // namespace spdfit::experiment
