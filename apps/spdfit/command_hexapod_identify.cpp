// spdfit hexapod identify A B [--truth T] [--geometry G | --stiffness K] [--bootstrap N] [--json]:
// M_p identified from measured accelerations and forces by every estimator.
#include <algorithm>
#include <cstdio>
#include <memory>
#include <sstream>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "bootstrap_options.hpp"
#include "hexapod_commands.hpp"
#include "input.hpp"
#include "output.hpp"
#include "spdfit/hexapod/geometry.hpp"
#include "spdfit/hexapod/identify.hpp"
#include "spdfit/io.hpp"

namespace spdfit::cli {

namespace {

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

}  // namespace

Command add_hexapod_identify(CLI::App& parent, const GlobalOptions& global) {
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

}  // namespace spdfit::cli
