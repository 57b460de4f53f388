// spdfit hexapod model|simulate|identify: the hexapod's M_p from its geometry, simulated
// measurements, and M_p identified from measurements.
#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>
#include <sstream>

#include <CLI/CLI.hpp>

#include "bootstrap_options.hpp"
#include "cli.hpp"
#include "experiment_output.hpp"
#include "input.hpp"
#include "output.hpp"
#include "spdfit/fit_files.hpp"
#include "spdfit/hexapod/geometry.hpp"
#include "spdfit/hexapod/identify.hpp"
#include "spdfit/hexapod/model.hpp"
#include "spdfit/hexapod/simulate.hpp"
#include "spdfit/io.hpp"
#include "spdfit/random.hpp"
#include "validators.hpp"

namespace spdfit::cli {

namespace {

constexpr const char* kBuiltInName = "built-in cubic-configuration hexapod (docs/hexapod.md)";

hexapod::Geometry load_geometry(const std::string& path) {
  return path.empty() ? hexapod::cubic_geometry() : hexapod::read_geometry(path);
}

std::string vector_text(const Eigen::VectorXd& v, int digits) {
  std::string out;
  for (Eigen::Index i = 0; i < v.size(); ++i) out += (i ? "  " : "") + fixed(v(i), digits);
  return out;
}

// ---- model -----------------------------------------------------------------------------------

Command add_model(CLI::App& parent, const GlobalOptions&) {
  struct Cli {
    std::string geometry, output, write_geometry;
    bool json = false;
  };
  auto cli = std::make_shared<Cli>();
  CLI::App* sub = parent.add_subcommand(
      "model",
      "The Jacobian, the joint-space mass-inertia matrix M_p (thesis eq. 2.12) and the modes of a hexapod");
  sub->add_option("--geometry", cli->geometry,
                  "Geometry file (JSON, SI units; see docs/hexapod.md). Default: the built-in cubic hexapod");
  sub->add_flag("--json", cli->json,
                "Print everything as JSON, the geometry included (a template for a file)");
  sub->add_option("-o,--output", cli->output, "Write to FILE instead of stdout");
  sub->add_option("--write-geometry", cli->write_geometry,
                  "Also write the geometry to FILE in the geometry-file format (a template to edit)");

  auto run = [cli]() {
    const hexapod::Geometry geometry = load_geometry(cli->geometry);
    if (!cli->write_geometry.empty()) emit(hexapod::geometry_json(geometry), cli->write_geometry);
    const hexapod::ModelDescription model = hexapod::describe(geometry);
    const std::string source = cli->geometry.empty() ? kBuiltInName : cli->geometry;
    if (cli->json) {
      nlohmann::json out;
      out["geometry_source"] = source;
      out["jacobian"] = matrix_json(model.jacobian);
      out["mass_matrix"] = matrix_json(model.mass_matrix);
      out["modes_hz"] = vector_json(model.modes_hz);
      out["mass_matrix_eigenvalues"] = vector_json(model.mass_matrix_eigenvalues);
      out["jacobian_condition"] = number_json(model.jacobian_condition);
      out["payload_mass_matrix"] = matrix_json(model.payload_mass_matrix);
      out["strut_lengths"] = vector_json(model.strut_lengths);
      out["strut_directions"] = matrix_json(model.strut_directions.transpose());
      out["geometry"] = nlohmann::json::parse(hexapod::geometry_json(geometry));
      emit(out.dump(2) + "\n", cli->output);
      return;
    }
    std::ostringstream out;
    out << "Hexapod: " << source << "\n"
        << "payload " << fixed(geometry.payload_mass, 3)
        << " kg; strut lengths (m): " << vector_text(model.strut_lengths, 4) << "\n\n"
        << "Jacobian J, l_dot = J [v; w] (rows: struts; v, w of the payload's centre of mass in {B} axes); "
        << "cond(J) = " << fixed(model.jacobian_condition, 2) << "\n"
        << side_by_side({"J"}, {Eigen::MatrixXd(model.jacobian)})
        << "Joint-space mass-inertia matrix (thesis eq. 2.12), kg\n"
        << side_by_side({"M_p"}, {Eigen::MatrixXd(model.mass_matrix)})
        << "eigenvalues of M_p (kg): " << vector_text(model.mass_matrix_eigenvalues, 4)
        << "\nmodes sqrt(eig(M_p^-1 K)) / 2 pi (Hz), K = diag(strut_stiffness): " << vector_text(model.modes_hz, 2)
        << "\n";
    emit(out.str(), cli->output);
  };
  return {sub, run};
}

// ---- simulate --------------------------------------------------------------------------------

Command add_simulate(CLI::App& parent, const GlobalOptions& global) {
  struct Cli {
    hexapod::SimulationOptions options;
    std::string distribution = "uniform", truth = "thesis", geometry, out;
    std::uint64_t seed = 1;
    double force_noise_var = 0.0;
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
  sub->add_option(
         "--seed", cli->seed,
         "Seed; the data are those of trial 0 of 'spdfit experiment thesis' with the same seed and settings")
      ->capture_default_str();
  sub->add_option("--out", cli->out, "Directory to write A.csv, B.csv, truth.csv and simulation.json to")
      ->required();

  auto run = [cli, force_noise, &global]() {
    Eigen::MatrixXd M;
    std::string truth_source;
    if (!cli->geometry.empty()) {
      M = hexapod::joint_space_mass_matrix(hexapod::read_geometry(cli->geometry));
      truth_source = "geometry " + cli->geometry;
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
    const hexapod::Measurements data = hexapod::simulate(M, options, cli->seed);

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
          << (dir / "B.csv").string() << " --truth " << (dir / "truth.csv").string() << "\n";
    }
    emit(out.str(), "");
  };
  return {sub, run};
}

// ---- identify --------------------------------------------------------------------------------

Eigen::MatrixXd parse_stiffness(const std::string& text, Eigen::Index n) {
  std::vector<double> values;
  std::stringstream in(text);
  std::string field;
  while (std::getline(in, field, ',')) {
    std::size_t used = 0;
    double value = 0;
    try {
      value = std::stod(field, &used);
    } catch (const std::exception&) {
      used = 0;
    }
    if (used == 0 || field.find_first_not_of(" \t", used) != std::string::npos || !(value >= 0.0)) {
      throw UsageError("--stiffness: '" + field + "' is not a non-negative number");
    }
    values.push_back(value);
  }
  if (values.size() == 1) values.assign(static_cast<std::size_t>(n), values.front());
  if (values.size() != static_cast<std::size_t>(n)) {
    throw UsageError("--stiffness: give one number or " + std::to_string(n) +
                     " comma-separated numbers, not " + std::to_string(values.size()));
  }
  return Eigen::Map<const Eigen::VectorXd>(values.data(), n).asDiagonal();
}

// Each symmetric estimate's eigenvalues and modes with their bootstrap intervals.
std::string bootstrap_report(const std::vector<hexapod::MethodIdentification>& methods,
                             const hexapod::IdentifyOptions& options) {
  std::ostringstream out;
  out << "\nbootstrap: " << options.fit.bootstrap << " resamples of the rows (seed " << options.fit.seed
      << "); value +- standard error   [" << percent_text(options.fit.confidence)
      << " interval]; values closer than their standard errors share one interval\n";
  for (const hexapod::MethodIdentification& m : methods) {
    const auto& b = m.result.bootstrap;
    if (!b || !b->eigenvalues) continue;
    out << to_string(m.result.method) << " (" << b->failed << " of " << b->replicates << " resamples failed)\n"
        << "  eigenvalues (kg)\n"
        << spectrum_text(*b->eigenvalues, "    ");
    if (m.modes_uncertainty) out << "  modes (Hz)\n" << spectrum_text(*m.modes_uncertainty, "    ");
  }
  return out.str();
}

std::string identify_report(const std::vector<hexapod::MethodIdentification>& methods,
                            const hexapod::IdentifyOptions& options) {
  std::ostringstream out;
  const Diagnostics& data = methods.front().result.diagnostics;
  char line[320];
  std::snprintf(line, sizeof line,
                "data: m = %ld samples of n = %ld struts; cond(A) = %.3g, cond(B) = %.3g (rank %ld, %ld)\n\n",
                static_cast<long>(data.m), static_cast<long>(data.n), data.cond_a, data.cond_b,
                static_cast<long>(data.rank_a), static_cast<long>(data.rank_b));
  out << line;
  std::vector<std::string> titles;
  std::vector<Eigen::MatrixXd> matrices;
  if (options.truth) {
    titles.emplace_back("truth");
    matrices.push_back(*options.truth);
  }
  for (const hexapod::MethodIdentification& m : methods) {
    if (!m.result.ok()) continue;
    titles.emplace_back(to_string(m.result.method));
    matrices.push_back(m.result.X);
  }
  out << "Estimates of M_p\n" << side_by_side(titles, matrices);

  std::snprintf(line, sizeof line, "%-11s %-10s %-10s %12s %12s %12s%s\n", "method", "symmetric", "definite",
                "residual", "area", "min eig", options.truth ? "  error ||M_hat - truth||_F" : "");
  out << line;
  for (const hexapod::MethodIdentification& m : methods) {
    const FitResult& r = m.result;
    const std::string name(to_string(r.method));
    if (!r.ok()) {
      out << name << std::string(12 - std::min<std::size_t>(name.size(), 11), ' ') << "failed: " << r.message
          << '\n';
      continue;
    }
    const Diagnostics& d = r.diagnostics;
    std::snprintf(line, sizeof line, "%-11s %-10s %-10s %12s %12s %12s%s\n", name.c_str(),
                  d.symmetric ? "yes" : "no", d.positive_definite ? "positive" : (d.symmetric ? "no" : "-"),
                  fixed(d.residual_norm).c_str(), d.area_criterion ? fixed(*d.area_criterion).c_str() : "-",
                  d.min_eigenvalue ? fixed(*d.min_eigenvalue).c_str() : "-",
                  m.error_vs_truth ? ("  " + fixed(*m.error_vs_truth)).c_str() : "");
    out << line;
  }
  out << "\neigenvalues (kg)" << (options.stiffness ? " and modes sqrt(eig(M_hat^-1 K)) / 2 pi (Hz)" : "")
      << "\n";
  for (const hexapod::MethodIdentification& m : methods) {
    if (!m.result.ok()) continue;
    const std::string name(to_string(m.result.method));
    std::snprintf(line, sizeof line, "%-11s ", name.c_str());
    if (!m.eigenvalues) {
      out << line << "not symmetric, so not a mass matrix: no eigenvalues or modes shown\n";
      continue;
    }
    out << line << vector_text(*m.eigenvalues, 4) << '\n';
    if (options.stiffness) {
      out << std::string(12, ' ')
          << (m.modes_hz ? vector_text(*m.modes_hz, 2) + " Hz" : "not positive definite: no modes") << '\n';
    }
  }
  if (options.fit.bootstrap > 0) out << bootstrap_report(methods, options);
  if (options.truth) {
    const hexapod::MethodIdentification* best = nullptr;
    for (const hexapod::MethodIdentification& m : methods) {
      if (m.error_vs_truth && (!best || *m.error_vs_truth < *best->error_vs_truth)) best = &m;
    }
    if (best)
      out << "\nclosest to the truth: " << to_string(best->result.method) << " (error "
          << fixed(*best->error_vs_truth) << ")\n";
  }
  return out.str();
}

Command add_identify(CLI::App& parent, const GlobalOptions& global) {
  struct Cli {
    std::string a_path, b_path, truth, geometry, stiffness, output;
    bool json = false;
    BootstrapCli bootstrap;
  };
  auto cli = std::make_shared<Cli>();
  CLI::App* sub = parent.add_subcommand(
      "identify", "Identify M_p from accelerations A and base forces B (B ~= A M_p) with every estimator");
  sub->add_option("A", cli->a_path, "File of payload accelerations along the struts (m x 6)")->required();
  sub->add_option("B", cli->b_path, "File of base forces (m x 6)")->required();
  sub->add_option("--truth", cli->truth, "File of the true M_p, to report each method's error");
  auto* geometry =
      sub->add_option("--geometry", cli->geometry, "Geometry file whose strut stiffness gives the modes");
  auto* stiffness =
      sub->add_option("--stiffness", cli->stiffness,
                      "Strut stiffness (N/m) for the modes: one number, or one per strut, comma-separated");
  stiffness->excludes(geometry);
  sub->add_flag("--json", cli->json, "Print every result as JSON");
  sub->add_option("-o,--output", cli->output, "Write to FILE instead of stdout");
  add_bootstrap_options(*sub, cli->bootstrap,
                        "each method's standard errors and the intervals of its eigenvalues and modes",
                        "Threads for --bootstrap (default: one per core)");

  auto run = [cli, &global]() {
    const DataPair data = load_pair(cli->a_path, cli->b_path, global);
    const Eigen::Index n = data.A.cols();
    if (data.B.cols() != n) {
      throw io::DataError(cli->b_path, 0, 0,
                          "B has " + std::to_string(data.B.cols()) + " columns but A (" + cli->a_path + ") has " +
                              std::to_string(n) + ": the mass-inertia matrix is square, so forces and "
                                                   "accelerations need the same struts");
    }
    hexapod::IdentifyOptions options;
    apply_bootstrap_options(cli->bootstrap, options.fit);
    if (!cli->truth.empty()) {
      options.truth = load_matrix(cli->truth, global);
      if (options.truth->rows() != n || options.truth->cols() != n) {
        throw io::DataError(cli->truth, 0, 0,
                            "the true M_p must be " + std::to_string(n) + "x" + std::to_string(n));
      }
    }
    if (!cli->geometry.empty()) {
      const hexapod::Geometry geometry = hexapod::read_geometry(cli->geometry);
      if (n != 6)
        throw io::DataError(cli->a_path, 0, 0, "a hexapod geometry needs data with 6 columns (struts)");
      options.stiffness = Eigen::MatrixXd(geometry.strut_stiffness.asDiagonal());
    } else if (!cli->stiffness.empty()) {
      options.stiffness = parse_stiffness(cli->stiffness, n);
    }
    const std::vector<hexapod::MethodIdentification> methods = hexapod::identify(data.A, data.B, options);
    for (const hexapod::MethodIdentification& m : methods) {
      for (const std::string& w : m.result.warnings)
        warn(global, std::string(to_string(m.result.method)) + ": " + w);
    }
    if (!cli->json) {
      emit(identify_report(methods, options), cli->output);
      return;
    }
    nlohmann::json out;
    out["m"] = data.A.rows();
    out["n"] = n;
    if (options.truth) out["truth"] = matrix_json(*options.truth);
    out["stiffness"] = options.stiffness ? matrix_json(*options.stiffness) : nlohmann::json(nullptr);
    out["methods"] = nlohmann::json::object();
    for (const hexapod::MethodIdentification& m : methods) {
      nlohmann::json j = result_json(m.result);
      if (m.eigenvalues) j["eigenvalues"] = vector_json(*m.eigenvalues);
      if (m.modes_hz) j["modes_hz"] = vector_json(*m.modes_hz);
      if (m.error_vs_truth) j["error_vs_truth"] = number_json(*m.error_vs_truth);
      if (m.modes_uncertainty) j["bootstrap"]["modes_hz"] = spectrum_json(*m.modes_uncertainty);
      out["methods"][std::string(to_string(m.result.method))] = std::move(j);
    }
    emit(out.dump(2) + "\n", cli->output);
  };
  return {sub, run};
}

}  // namespace

Command add_hexapod_command(CLI::App& app, const GlobalOptions& global) {
  CLI::App* sub =
      app.add_subcommand("hexapod", "A flexure-jointed hexapod's M_p: model, simulated data, identification");
  sub->require_subcommand(1);
  auto children = std::make_shared<std::vector<Command>>(
      std::vector<Command>{add_model(*sub, global), add_simulate(*sub, global), add_identify(*sub, global)});
  auto run = [children]() {
    for (const Command& child : *children) {
      if (child.app->parsed()) child.run();
    }
  };
  return {sub, run};
}

}  // namespace spdfit::cli
