// spdfit hexapod simulate --noise-var V --out DIR [...]: accelerations A and base forces
// B = A M_p with noise, the thesis' appendix-B generator, written as files.
#include <filesystem>
#include <memory>
#include <optional>
#include <sstream>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "hexapod_commands.hpp"
#include "input.hpp"
#include "output.hpp"
#include "spdfit/hexapod/geometry.hpp"
#include "spdfit/hexapod/model.hpp"
#include "spdfit/hexapod/simulate.hpp"
#include "spdfit/io.hpp"
#include "spdfit/rigid_body.hpp"
#include "table_options.hpp"
#include "validators.hpp"

namespace spdfit::cli {

namespace {

// The payload options: the true payload when it differs from the geometry's nominal one.
struct PayloadCli {
  std::string mass, com, inertia;
  CLI::Option *mass_option = nullptr, *com_option = nullptr, *inertia_option = nullptr;

  bool given() const { return mass_option->count() + com_option->count() + inertia_option->count() > 0; }
};

void add_payload_options(CLI::App* sub, PayloadCli& payload) {
  payload.mass_option = sub->add_option("--payload-mass", payload.mass,
                                        "With --geometry: the true payload's mass (kg; default the geometry's)");
  payload.com_option =
      sub->add_option("--payload-com", payload.com,
                      "With --geometry: the true payload's centre of mass x,y,z (m, {P}'s axes, from {P}'s "
                      "origin, the nominal centre of mass; default 0,0,0)");
  payload.inertia_option = sub->add_option(
      "--payload-inertia", payload.inertia,
      "With --geometry: the true payload's inertia about its centre of mass ({P}'s axes, kg m^2): 3 numbers "
      "(the diagonal), 6 (ixx,ixy,ixz,iyy,iyz,izz as URDF orders them) or 9 (row by row); default the "
      "geometry's");
  payload.mass_option->type_name("KG");
  payload.com_option->type_name("X,Y,Z");
  payload.inertia_option->type_name("I");
}

// The comma-separated numbers of option `spelling`, whose count must be one of `counts`.
std::vector<double> numbers(const std::string& spelling, const std::string& text, std::initializer_list<std::size_t> counts,
                            const std::string& expected) {
  const std::vector<double> values = std::get<std::vector<double>>(parse_option_text(OptionType::RealList, spelling, text));
  for (std::size_t c : counts) {
    if (values.size() == c) return values;
  }
  throw UsageError(spelling + ": give " + expected + ", not " + std::to_string(values.size()) + " numbers");
}

// The geometry's nominal payload with the options' changes.
RigidBodyInertia payload_of(const PayloadCli& cli, const hexapod::Geometry& geometry) {
  RigidBodyInertia body = hexapod::nominal_payload(geometry);
  if (cli.mass_option->count() > 0) body.mass = numbers("--payload-mass", cli.mass, {1}, "one number")[0];
  if (cli.com_option->count() > 0) {
    const std::vector<double> c = numbers("--payload-com", cli.com, {3}, "3 comma-separated numbers x,y,z");
    body.center_of_mass = Eigen::Vector3d(c[0], c[1], c[2]);
  }
  if (cli.inertia_option->count() > 0) {
    const std::vector<double> v =
        numbers("--payload-inertia", cli.inertia, {3, 6, 9}, "3 (the diagonal), 6 (ixx,ixy,ixz,iyy,iyz,izz) or 9 numbers");
    Eigen::Matrix3d I;
    if (v.size() == 3) {
      I = Eigen::Vector3d(v[0], v[1], v[2]).asDiagonal();
    } else if (v.size() == 6) {
      I << v[0], v[1], v[2], v[1], v[3], v[4], v[2], v[4], v[5];
    } else {
      I << v[0], v[1], v[2], v[3], v[4], v[5], v[6], v[7], v[8];
    }
    body.inertia = I;
  }
  std::string error;
  if (!is_well_formed(body, &error)) {
    const std::string option = error.rfind("mass", 0) == 0 ? "--payload-mass"
                               : error.rfind("center_of_mass", 0) == 0 ? "--payload-com"
                                                                         : "--payload-inertia";
    throw UsageError(option + ": " + error);
  }
  return body;
}

nlohmann::json payload_json(const RigidBodyInertia& body) {
  nlohmann::json inertia = nlohmann::json::array();
  for (int i = 0; i < 3; ++i) inertia.push_back({body.inertia(i, 0), body.inertia(i, 1), body.inertia(i, 2)});
  return {{"mass", body.mass},
          {"center_of_mass", {body.center_of_mass(0), body.center_of_mass(1), body.center_of_mass(2)}},
          {"inertia", inertia}};
}

}  // namespace

Command add_hexapod_simulate(CLI::App& parent, const GlobalOptions& global) {
  struct Cli {
    hexapod::SimulationOptions options;
    std::string distribution = "uniform", truth = "thesis", geometry, out;
    std::uint64_t seed = 1;
    double force_noise_var = 0.0;
    PayloadCli payload;
  };
  auto cli = std::make_shared<Cli>();
  CLI::App* sub = parent.add_subcommand(
      "simulate",
      "Simulated accelerations A and base forces B = A M_p with noise (the thesis' appendix-B generator)");
  sub->add_option("--samples", cli->options.samples, "Samples m (rows of A and B)")
      ->check(CLI::Range(Eigen::Index{1}, Eigen::Index{100000000}))
      ->capture_default_str();
  sub->add_option("--noise-var", cli->options.noise_var, "Variance V of the noise in every entry of A and B")
      ->required()
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
  add_payload_options(sub, cli->payload);
  sub->add_option(
         "--seed", cli->seed,
         "Seed; the data are those of trial 0 of 'spdfit experiment thesis' with the same seed and settings")
      ->capture_default_str();
  sub->add_option("--out", cli->out, "Directory to write A.csv, B.csv, truth.csv and simulation.json to")
      ->required();

  auto run = [cli, force_noise, &global]() {
    Eigen::MatrixXd M;
    std::string truth_source;
    std::optional<hexapod::Geometry> geometry_read;
    std::optional<RigidBodyInertia> payload;
    if (cli->payload.given() && cli->geometry.empty()) {
      throw UsageError("--payload-mass, --payload-com and --payload-inertia change the payload of --geometry: give it");
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
    if (options.samples < M.rows()) {
      warn(global, "fewer samples (" + std::to_string(options.samples) + ") than M_p has columns (" +
                       std::to_string(M.rows()) + "): the estimators need m >= n");
    }
    // The payload's simulate draws what simulate(M, options, seed) draws for its M.
    const hexapod::Measurements data =
        payload ? hexapod::simulate(*geometry_read, *payload, options, cli->seed) : hexapod::simulate(M, options, cli->seed);

    namespace fs = std::filesystem;
    std::error_code error;
    fs::create_directories(cli->out, error);
    if (error) throw io::DataError(cli->out, 0, 0, "cannot create the output directory: " + error.message());
    const fs::path dir(cli->out);
    io::write_csv((dir / "A.csv").string(), data.A);
    io::write_csv((dir / "B.csv").string(), data.B);
    io::write_csv((dir / "truth.csv").string(), M);
    nlohmann::json settings;
    settings["samples"] = options.samples;
    settings["noise_var"] = options.noise_var;
    settings["force_noise_var"] = options.force_noise_var.value_or(options.noise_var);
    settings["signal_var"] = options.signal_var;
    settings["distribution"] = cli->distribution;
    settings["truth"] = truth_source;
    if (payload) settings["payload"] = payload_json(*payload);
    settings["seed"] = cli->seed;
    settings["files"] = {{"A", "A.csv"}, {"B", "B.csv"}, {"truth", "truth.csv"}};
    emit(settings.dump(2) + "\n", (dir / "simulation.json").string());

    std::ostringstream out;
    out << "wrote " << (dir / "A.csv").string() << " (" << data.A.rows() << "x" << data.A.cols()
        << " accelerations), " << (dir / "B.csv").string() << " (forces), " << (dir / "truth.csv").string()
        << " (M_p: " << truth_source << "), " << (dir / "simulation.json").string() << "\n";
    // The next step only when it can succeed: identify needs at least as many samples as columns.
    if (options.samples >= M.rows()) {
      out << "identify M_p from them with:\n  spdfit hexapod identify " << (dir / "A.csv").string() << ' '
          << (dir / "B.csv").string() << " --truth " << (dir / "truth.csv").string()
          << (payload ? " --physical --geometry " + cli->geometry : std::string()) << "\n";
    }
    emit(out.str(), "");
  };
  return {sub, run};
}

}  // namespace spdfit::cli
