// The hexapod generator's options for noise of its own per sensor and a rest segment
// (--noise-std-a, --noise-std-b, --rest-samples, --scale-b), which `hexapod simulate` and the
// experiments share.
#pragma once

#include <CLI/CLI.hpp>

#include <string>

#include "spdfit/hexapod/simulate.hpp"

namespace spdfit::cli {

struct SimulationNoiseCli {
  std::string std_a, std_b;
  Eigen::Index rest_samples = 0;
  double scale_b = 1.0;
  CLI::Option* std_a_option = nullptr;
  CLI::Option* std_b_option = nullptr;
};

/// Adds --noise-std-a, --noise-std-b (each needing the other), --rest-samples and --scale-b to
/// `sub`; --noise-std-a excludes `noise_var` (the command's --noise-var) when given.
void add_simulation_noise_options(CLI::App& sub, SimulationNoiseCli& cli, CLI::Option* noise_var = nullptr);

/// Whether --noise-std-a (and so --noise-std-b) was given.
bool gives_noise_std(const SimulationNoiseCli& cli);

/// `options` with the standard deviations (one or one per column), the rest rows and the scale of
/// B; then checked (SimulationOptions::is_valid): a UsageError naming the option for a value the
/// generator refuses.
void apply_simulation_noise_options(const SimulationNoiseCli& cli, hexapod::SimulationOptions& options);

}  // namespace spdfit::cli
