// The noise-model table of docs/guide.md ("Units and noise"): the thesis' hexapod model with
// per-channel Gaussian noise, each row one run of the thesis experiment (experiment/thesis.hpp)
// with the methods auto and psd-ls fitted without a noise model, and spd-tls and auto fitted with
// the true covariances and with those of a rest segment. With --dump DIR it also writes every
// trial's data (the experiment's own draws) and spdfit's maximum-likelihood estimate with the true
// covariances, for bench/noise_table.py to compare with an independent SciPy optimizer.
//
//   build/bench/spdfit_noise_table --case both --samples 1000 --trials 40 [--dump DIR]
//
// Cases: "both" (noise std in A 0.2, 0.4, 0.8, 0.2, 0.4, 0.8; in B 3, 1, 0.3, 3, 1, 0.3), "kn"
// (the same with B in kN: B / 1000), "b-only" (A exact).
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "spdfit/experiment/thesis.hpp"
#include "spdfit/fit.hpp"
#include "spdfit/hexapod/simulate.hpp"
#include "spdfit/io.hpp"
#include "spdfit/random.hpp"

namespace {

using spdfit::Method;
using spdfit::experiment::FitNoise;

int usage() {
  std::fprintf(stderr,
               "usage: spdfit_noise_table [--case both|kn|b-only] [--samples M] [--trials N] [--seed S] "
               "[--rest-samples R] [--dump DIR]\n");
  return 2;
}

}  // namespace

int main(int argc, char** argv) {
  std::string which = "both", dump;
  long samples = 1000, trials = 40, rest = 2000;
  unsigned long long seed = 1;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (i + 1 >= argc) return usage();
    const char* value = argv[++i];
    if (arg == "--case") {
      which = value;
    } else if (arg == "--samples") {
      samples = std::atol(value);
    } else if (arg == "--trials") {
      trials = std::atol(value);
    } else if (arg == "--seed") {
      seed = std::strtoull(value, nullptr, 10);
    } else if (arg == "--rest-samples") {
      rest = std::atol(value);
    } else if (arg == "--dump") {
      dump = value;
    } else {
      return usage();
    }
  }
  if (which != "both" && which != "kn" && which != "b-only") return usage();

  spdfit::experiment::ThesisExperimentOptions options;
  options.simulation.samples = samples;
  options.simulation.distribution = spdfit::hexapod::NoiseDistribution::Gaussian;
  Eigen::VectorXd std_a(6), std_b(6);
  std_a << 0.2, 0.4, 0.8, 0.2, 0.4, 0.8;
  std_b << 3.0, 1.0, 0.3, 3.0, 1.0, 0.3;
  if (which == "b-only") std_a.setZero();
  options.simulation.noise_std_a = std_a;
  options.simulation.noise_std_b = std_b;
  options.simulation.rest_samples = rest;
  if (which == "kn") options.simulation.scale_b = 1e-3;
  options.methods = {Method::Auto, Method::PsdLeastSquares, Method::SpdTotalLeastSquares};
  options.noise_models = {FitNoise::None, FitNoise::True, FitNoise::Rest};
  spdfit::experiment::MonteCarloOptions monte_carlo;
  monte_carlo.trials = static_cast<std::size_t>(trials);
  monte_carlo.seed = seed;

  const spdfit::experiment::ThesisExperimentResult result = spdfit::experiment::run_thesis_experiment(options,
                                                                                                        monte_carlo);
  std::printf("case %s, m = %ld, %ld trials, rest segment %ld rows, seed %llu: mean ||M - M_hat||_F (standard error)\n",
              which.c_str(), samples, trials, rest, seed);
  for (const spdfit::experiment::MethodErrors& m : result.methods) {
    std::printf("%-8s noise model %-5s %.4f (%.4f)  failures %zu\n", std::string(spdfit::to_string(m.method)).c_str(),
                std::string(spdfit::experiment::to_string(m.noise)).c_str(), m.summary.mean,
                m.summary.standard_error(), m.summary.failures);
  }

  if (dump.empty()) return 0;
  // The experiment's data again (trial k draws from Random(trial_seed(seed, k)), as run_trials),
  // and spdfit's estimates with the true and the rest covariances.
  namespace fs = std::filesystem;
  fs::create_directories(dump);
  const Eigen::MatrixXd truth = spdfit::hexapod::thesis_mass_matrix();
  const spdfit::NoiseModel true_noise = spdfit::hexapod::true_noise_model(options.simulation, 6);
  spdfit::io::write_npy((fs::path(dump) / "truth.npy").string(), truth);
  spdfit::io::write_npy((fs::path(dump) / "cov_a.npy").string(), true_noise.resolved(6, 6).cov_a());
  spdfit::io::write_npy((fs::path(dump) / "cov_b.npy").string(), true_noise.resolved(6, 6).cov_b());
  std::ofstream((fs::path(dump) / "scale_b.txt").string()) << spdfit::io::format_double(options.simulation.scale_b)
                                                           << "\n";
  for (long k = 0; k < trials; ++k) {
    spdfit::Random random(spdfit::trial_seed(seed, static_cast<std::size_t>(k)));
    const spdfit::hexapod::Measurements data = spdfit::hexapod::simulate(truth, options.simulation, random);
    const std::string prefix = (fs::path(dump) / ("trial" + std::to_string(k) + "_")).string();
    spdfit::io::write_npy(prefix + "A.npy", data.A);
    spdfit::io::write_npy(prefix + "B.npy", data.B);
    spdfit::FitOptions with_true;
    with_true.noise = true_noise;
    spdfit::FitOptions with_rest;
    with_rest.noise = spdfit::NoiseModel::from_rest(data.rest_A, data.rest_B);
    const spdfit::FitResult ml = spdfit::fit(data.A, data.B, Method::SpdTotalLeastSquares, with_true);
    const spdfit::FitResult ml_rest = spdfit::fit(data.A, data.B, Method::SpdTotalLeastSquares, with_rest);
    const spdfit::FitResult auto_rest = spdfit::fit(data.A, data.B, Method::Auto, with_rest);
    if (ml.ok()) spdfit::io::write_npy(prefix + "X_ml_true.npy", ml.X);
    if (ml_rest.ok()) spdfit::io::write_npy(prefix + "X_ml_rest.npy", ml_rest.X);
    if (auto_rest.ok()) spdfit::io::write_npy(prefix + "X_auto_rest.npy", auto_rest.X);
  }
  return 0;
}
