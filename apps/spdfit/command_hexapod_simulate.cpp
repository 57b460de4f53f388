// spdfit hexapod simulate --noise-var V --out DIR [...]: accelerations A and base forces
// B = A M_p with noise, the thesis' appendix-B generator, written as files.
#include <CLI/CLI.hpp>
#include <filesystem>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>

#include "hexapod_commands.hpp"
#include "input.hpp"
#include "output.hpp"
#include "payload_options.hpp"
#include "simulation_noise_options.hpp"
#include "table_options.hpp"
#include "spdfit/hexapod/geometry.hpp"
#include "spdfit/hexapod/model.hpp"
#include "spdfit/hexapod/simulate.hpp"
#include "spdfit/hexapod/simulation_warnings.hpp"
#include "spdfit/io.hpp"
#include "spdfit/rigid_body.hpp"
#include "validators.hpp"

namespace spdfit::cli {

Command add_hexapod_simulate(CLI::App& parent, const GlobalOptions& global) {
  struct Cli {
    hexapod::SimulationOptions options;
    std::string distribution = "uniform", truth = "thesis", geometry, out;
    std::uint64_t seed = 1;
    double force_noise_var = 0.0;
    std::string preload;
    PayloadCli payload;
    SimulationNoiseCli noise;
  };
  auto cli = std::make_shared<Cli>();
  CLI::App* sub = parent.add_subcommand(
      "simulate",
      "Simulated accelerations A and base forces B = A M_p with noise (the thesis' appendix-B generator)");
  sub->add_option("--samples", cli->options.samples, "Samples m (rows of A and B)")
      ->check(integer_in(1, 100000000))
      ->capture_default_str();
  auto* noise_var =
      sub->add_option("--noise-var", cli->options.noise_var,
                      "Variance V of the noise in every entry of A and B (or --noise-std-a and --noise-std-b)")
          ->check(non_negative());
  auto* force_noise =
      sub->add_option(
             "--force-noise-var", cli->force_noise_var,
             "Variance of the noise in B when it differs from A's (default: --noise-var, as the thesis)")
          ->check(non_negative());
  sub->add_option(
         "--signal-var", cli->options.signal_var,
         "Variance S of the true accelerations, uniform on [-sqrt(3 S), sqrt(3 S)] (default 25/3: [-5, 5])")
      ->check(positive());
  sub->add_option("--distribution", cli->distribution,
                  "Noise distribution: uniform (the thesis') or gaussian")
      ->check(CLI::IsMember({"uniform", "gaussian"}))
      ->capture_default_str();
  auto* truth =
      sub->add_option("--truth", cli->truth, "True M_p: 'thesis' (eq. 6.1) or a matrix file (n x n)")
          ->capture_default_str();
  auto* geometry =
      sub->add_option("--geometry", cli->geometry, "Use the M_p of this geometry file as the truth");
  geometry->excludes(truth);
  add_payload_options(sub, cli->payload, "With --geometry: the true payload's");
  sub->add_option(
         "--seed", cli->seed,
         "Seed; the data are those of trial 0 of 'spdfit experiment thesis' with the same seed and settings")
      ->capture_default_str();
  sub->add_option("--out", cli->out,
                  "Directory to write A.csv, B.csv, truth.csv and simulation.json to (and rest_A.csv, rest_B.csv "
                  "with --rest-samples)")
      ->required();
  add_simulation_noise_options(*sub, cli->noise, noise_var);
  sub->add_option("--preload", cli->preload,
                  "A static load in every row of B, moving or at rest (untared forces): one value for every strut, "
                  "or one per strut (comma-separated), in B's units before --scale-b. Default: none")
      ->type_name("F");

  auto run = [cli, force_noise, noise_var, &global]() {
    if (noise_var->count() == 0 && !gives_noise_std(cli->noise)) {
      throw UsageError("give the noise: --noise-var V, or --noise-std-a S and --noise-std-b S");
    }
    Eigen::MatrixXd M;
    std::string truth_source;
    std::optional<hexapod::Geometry> geometry_read;
    std::optional<RigidBodyInertia> payload;
    if (cli->payload.given() && cli->geometry.empty()) {
      throw UsageError(
          "--payload-mass, --payload-com and --payload-inertia change the payload of --geometry: give it");
    }
    if (!cli->geometry.empty()) {
      geometry_read = hexapod::read_geometry(cli->geometry);
      if (cli->payload.given()) {
        payload = payload_of(cli->payload, *geometry_read);
        M = hexapod::joint_space_mass_matrix(*geometry_read, *payload);
        truth_source = "geometry " + cli->geometry + " with the payload of --payload-*";
      } else {
        M = hexapod::joint_space_mass_matrix(*geometry_read);
        truth_source = "geometry " + cli->geometry;
      }
    } else if (cli->truth == "thesis") {
      M = hexapod::thesis_mass_matrix();
      truth_source = "thesis eq. 6.1";
    } else {
      M = load_matrix(cli->truth, global);
      if (M.rows() != M.cols()) {
        throw io::DataError(
            cli->truth, 0, 0,
            "the true M_p must be square, not " + std::to_string(M.rows()) + "x" + std::to_string(M.cols()));
      }
      if (!M.isApprox(M.transpose())) warn(global, cli->truth + ": the true M_p is not symmetric");
      truth_source = cli->truth;
    }
    hexapod::SimulationOptions options = cli->options;
    options.distribution = *hexapod::parse_noise_distribution(cli->distribution);
    if (force_noise->count() > 0) options.force_noise_var = cli->force_noise_var;
    apply_simulation_noise_options(cli->noise, options);
    if (!cli->preload.empty()) {
      const auto values =
          std::get<std::vector<double>>(parse_option_text(OptionType::RealList, "--preload", cli->preload));
      if (values.size() != 1 && static_cast<Eigen::Index>(values.size()) != M.rows()) {
        throw UsageError("--preload has " + std::to_string(values.size()) + " values for " +
                         std::to_string(M.rows()) + " struts: give one for every strut, or one per strut");
      }
      options.rest_force = values.size() == 1 ? Eigen::VectorXd::Constant(M.rows(), values.front())
                                              : Eigen::VectorXd(Eigen::Map<const Eigen::VectorXd>(values.data(), M.rows()));
    }
    for (const auto& w : hexapod::simulation_warnings(M, options)) warn(global, w);
    // The payload's simulate draws what simulate(M, options, seed) draws for its M.
    const hexapod::Measurements data = payload
                                           ? hexapod::simulate(*geometry_read, *payload, options, cli->seed)
                                           : hexapod::simulate(M, options, cli->seed);

    namespace fs = std::filesystem;
    std::error_code error;
    fs::create_directories(cli->out, error);
    if (error) throw io::DataError(cli->out, 0, 0, "cannot create the output directory: " + error.message());
    const fs::path dir(cli->out);
    io::write_csv((dir / "A.csv").string(), data.A);
    io::write_csv((dir / "B.csv").string(), data.B);
    // The true X of the data written: M_p in B's units over A's.
    io::write_csv((dir / "truth.csv").string(), M * options.scale_b);
    if (options.rest_samples > 0) {
      io::write_csv((dir / "rest_A.csv").string(), data.rest_A);
      io::write_csv((dir / "rest_B.csv").string(), data.rest_B);
    }
    nlohmann::json settings;
    settings["samples"] = options.samples;
    settings["noise_var"] = options.noise_var;
    settings["force_noise_var"] = options.force_noise_var.value_or(options.noise_var);
    settings["signal_var"] = options.signal_var;
    settings["distribution"] = cli->distribution;
    settings["truth"] = truth_source;
    if (payload) settings["payload"] = payload_json(*payload);
    settings["seed"] = cli->seed;
    if (options.noise_std_a) settings["noise_std_a"] = std::vector<double>(options.noise_std_a->begin(), options.noise_std_a->end());
    if (options.noise_std_b) settings["noise_std_b"] = std::vector<double>(options.noise_std_b->begin(), options.noise_std_b->end());
    settings["scale_b"] = options.scale_b;
    settings["rest_samples"] = options.rest_samples;
    if (options.rest_force.size() > 0) {
      settings["preload"] = std::vector<double>(options.rest_force.begin(), options.rest_force.end());
    }
    settings["files"] = {{"A", "A.csv"}, {"B", "B.csv"}, {"truth", "truth.csv"}};
    if (options.rest_samples > 0) {
      settings["files"]["rest_A"] = "rest_A.csv";
      settings["files"]["rest_B"] = "rest_B.csv";
    }
    emit(settings.dump(2) + "\n", (dir / "simulation.json").string());

    std::ostringstream out;
    out << "wrote " << (dir / "A.csv").string() << " (" << data.A.rows() << "x" << data.A.cols()
        << " accelerations), " << (dir / "B.csv").string() << " (forces), " << (dir / "truth.csv").string()
        << " (M_p: " << truth_source << "), " << (dir / "simulation.json").string();
    if (options.rest_samples > 0) {
      out << ", " << (dir / "rest_A.csv").string() << " and " << (dir / "rest_B.csv").string() << " ("
          << options.rest_samples << " rows at rest)";
    }
    out << "\n";
    // The next step only when it can succeed: identify needs at least as many samples as columns.
    if (options.samples >= M.rows()) {
      out << "identify M_p from them with:\n  spdfit hexapod identify " << (dir / "A.csv").string() << ' '
          << (dir / "B.csv").string() << " --truth " << (dir / "truth.csv").string()
          << (payload ? " --physical --geometry " + cli->geometry : std::string());
      if (options.rest_samples > 0) {
        out << " --rest-a " << (dir / "rest_A.csv").string() << " --rest-b " << (dir / "rest_B.csv").string();
      }
      out << "\n";
    }
    emit(out.str(), "");
  };
  return {sub, run};
}

}  // namespace spdfit::cli
