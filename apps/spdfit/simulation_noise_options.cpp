#include "simulation_noise_options.hpp"

#include "cli.hpp"
#include "table_options.hpp"
#include "validators.hpp"

namespace spdfit::cli {

void add_simulation_noise_options(CLI::App& sub, SimulationNoiseCli& cli, CLI::Option* noise_var) {
  cli.std_a_option = sub.add_option("--noise-std-a", cli.std_a,
                                    "Standard deviation of the noise in A: one for every column, or one per column "
                                    "(comma-separated); 0: exact. Instead of --noise-var")
                         ->type_name("S");
  cli.std_b_option = sub.add_option("--noise-std-b", cli.std_b,
                                    "Standard deviation of the noise in B, as --noise-std-a (in B's units before "
                                    "--scale-b)")
                         ->type_name("S");
  cli.std_a_option->needs(cli.std_b_option);
  cli.std_b_option->needs(cli.std_a_option);
  if (noise_var != nullptr) cli.std_a_option->excludes(noise_var);
  sub.add_option("--rest-samples", cli.rest_samples,
                 "Also N rows recorded at rest (accelerations zero, forces constant) with the same noise")
      ->check(CLI::Range(Eigen::Index{0}, Eigen::Index{100000000}))
      ->type_name("N");
  sub.add_option("--scale-b", cli.scale_b,
                 "Multiply B (and the rest rows of B) by F after drawing: 0.001 gives forces in kN, the true X "
                 "then M_p / 1000")
      ->check(positive())
      ->type_name("F");
}

bool gives_noise_std(const SimulationNoiseCli& cli) { return cli.std_a_option && cli.std_a_option->count() > 0; }

void apply_simulation_noise_options(const SimulationNoiseCli& cli, hexapod::SimulationOptions& options) {
  const auto vector = [](const std::vector<double>& v) {
    return Eigen::VectorXd(Eigen::Map<const Eigen::VectorXd>(v.data(), Eigen::Index(v.size())));
  };
  if (gives_noise_std(cli)) {
    options.noise_std_a = vector(std::get<std::vector<double>>(parse_option_text(OptionType::RealList, "--noise-std-a", cli.std_a)));
    options.noise_std_b = vector(std::get<std::vector<double>>(parse_option_text(OptionType::RealList, "--noise-std-b", cli.std_b)));
  }
  options.rest_samples = cli.rest_samples;
  options.scale_b = cli.scale_b;
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
