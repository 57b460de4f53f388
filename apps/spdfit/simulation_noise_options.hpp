// The hexapod generator's options for noise of its own per sensor and a rest segment
// (--noise-std-a, --noise-std-b, --rest-samples, --scale-b), which the experiments share with
// `hexapod simulate`: registered from its option table (hexapod/simulate_request.hpp).
#pragma once

#include <memory>

#include <CLI/CLI.hpp>

#include "spdfit/hexapod/simulate.hpp"
#include "spdfit/hexapod/simulate_request.hpp"
#include "table_options.hpp"

namespace spdfit::cli {

struct SimulationNoiseCli {
  std::unique_ptr<TableOptions<hexapod::SimulateRequest>> options;
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
