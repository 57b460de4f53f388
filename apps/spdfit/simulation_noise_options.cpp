#include "simulation_noise_options.hpp"

#include "cli.hpp"
#include "table_options.hpp"
#include "validators.hpp"

#include <algorithm>
#include <iterator>
#include <string_view>
#include <vector>

namespace spdfit::cli {

namespace {

constexpr std::string_view kNoiseOptions[] = {"noise_std_a", "noise_std_b", "rest_samples", "scale_b"};

}  // namespace

void add_simulation_noise_options(CLI::App& sub, SimulationNoiseCli& cli, CLI::Option* noise_var) {
  std::vector<std::string_view> others;
  for (const auto& spec : hexapod::simulate_option_table()) {
    if (std::find(std::begin(kNoiseOptions), std::end(kNoiseOptions), spec.name) == std::end(kNoiseOptions)) {
      others.push_back(spec.name);
    }
  }
  cli.options = std::make_unique<TableOptions<hexapod::SimulateRequest>>(sub, hexapod::simulate_option_table(), others);
  if (noise_var != nullptr) cli.options->option("noise_std_a")->excludes(noise_var);
}

bool gives_noise_std(const SimulationNoiseCli& cli) { return cli.options && cli.options->was_given("noise_std_a"); }

void apply_simulation_noise_options(const SimulationNoiseCli& cli, hexapod::SimulationOptions& options) {
  const auto& table = hexapod::simulate_option_table();
  hexapod::SimulateRequest request;
  request.options = options;
  cli.options->apply(request);
  // The table's rules among these four (the deviations of A and B come together).
  run_spelled(table, [&] { check_option_combination(table, cli.options->given()); });
  options.noise_std_a = request.options.noise_std_a;
  options.noise_std_b = request.options.noise_std_b;
  options.rest_samples = request.options.rest_samples;
  options.scale_b = request.options.scale_b;
  std::string error;
  if (!options.is_valid(&error)) {
    // The generator names its fields; the command line's options are the same words with hyphens.
    for (const auto& [field, option] : {std::pair<std::string, std::string>{"noise_std_a", "--noise-std-a"},
                                        {"noise_std_b", "--noise-std-b"},
                                        {"force_noise_var", "--force-noise-var"},
                                        {"noise_var", "--noise-var"}}) {
      for (std::size_t at = error.find(field); at != std::string::npos; at = error.find(field, at + option.size())) {
        if (at > 0 && (error[at - 1] == '_' || error[at - 1] == '-')) continue;
        error.replace(at, field.size(), option);
      }
    }
    throw UsageError(error);
  }
}

}  // namespace spdfit::cli
