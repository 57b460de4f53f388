// spdfit compare [--truth T] [--json] A B: every estimator on the same data, side by side.
#include <cstdio>
#include <memory>
#include <sstream>

#include <CLI/CLI.hpp>

#include "cli.hpp"
#include "input.hpp"
#include "output.hpp"
#include "validators.hpp"
#include "spdfit/fit.hpp"
#include "spdfit/fit_files.hpp"
#include "spdfit/io.hpp"

namespace spdfit::cli {

namespace {

struct CompareOptionsCli {
  std::string a_path, b_path, truth_path, output;
  bool json = false;
  double noise_ratio = 1.0;
};

std::string yes_no(bool value) { return value ? "yes" : "no"; }

std::string optional_text(const std::optional<double>& value) {
  if (!value) return "-";
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.6g", *value);
  return buffer;
}

std::string report(const std::vector<FitResult>& results, const std::optional<Eigen::MatrixXd>& truth) {
  std::ostringstream out;
  const Diagnostics& data = results.front().diagnostics;
  char line[256];
  const std::string d_text = data.d == data.n ? "" : ", d = " + std::to_string(data.d);
  std::snprintf(line, sizeof line, "data: m = %ld samples, n = %ld%s; rank(A) = %ld, cond(A) = %.3g; "
                "rank(B) = %ld, cond(B) = %.3g\n\n",
                static_cast<long>(data.m), static_cast<long>(data.n), d_text.c_str(), static_cast<long>(data.rank_a),
                data.cond_a, static_cast<long>(data.rank_b), data.cond_b);
  out << line;
  if (data.d != data.n) out << "(X is " << data.n << " x " << data.d << ": only ls and tls fit a non-square X)\n\n";

  std::vector<std::string> titles;
  std::vector<Eigen::MatrixXd> estimates;
  if (truth) {
    titles.emplace_back("truth");
    estimates.push_back(*truth);
  }
  for (const FitResult& r : results) {
    if (!r.ok()) continue;
    titles.emplace_back(to_string(r.method));
    estimates.push_back(r.X);
  }
  out << side_by_side(titles, estimates);

  std::snprintf(line, sizeof line, "%-11s %-12s %-12s %-14s %-10s %-10s%s\n", "method", "residual", "area",
                "min eigenvalue", "symmetric", "definite", truth ? "  error ||X - truth||_F" : "");
  out << line;
  for (const FitResult& r : results) {
    if (!r.ok()) {
      std::snprintf(line, sizeof line, "%-11s failed: %s\n", std::string(to_string(r.method)).c_str(),
                    r.message.c_str());
      out << line;
      continue;
    }
    const Diagnostics& d = r.diagnostics;
    std::string error;
    if (truth) error = "  " + optional_text((r.X - *truth).norm());
    std::snprintf(line, sizeof line, "%-11s %-12.6g %-12s %-14s %-10s %-10s%s\n",
                  std::string(to_string(r.method)).c_str(), d.residual_norm, optional_text(d.area_criterion).c_str(),
                  optional_text(d.min_eigenvalue).c_str(), yes_no(d.symmetric).c_str(),
                  d.positive_definite ? "positive" : (d.symmetric ? "no" : "-"), error.c_str());
    out << line;
  }
  return out.str();
}

}  // namespace

Command add_compare_command(CLI::App& app, const GlobalOptions& global) {
  auto options = std::make_shared<CompareOptionsCli>();
  CLI::App* sub = app.add_subcommand("compare", "Run every estimator on A X ~= B and show them side by side");
  sub->add_option("--truth", options->truth_path, "File of the true X, to report each method's error");
  sub->add_flag("--json", options->json, "Print every result as JSON");
  sub->add_option("-o,--output", options->output, "Write to FILE instead of stdout");
  sub->add_option("--noise-ratio", options->noise_ratio,
                  "sigma_B / sigma_A for the total least-squares methods and the noise estimate (default 1)")
      ->check(positive());
  sub->add_option("A", options->a_path, "File of A (m x n): delimited text or .npy")->required();
  sub->add_option("B", options->b_path, "File of B (m x n; m x d for ls and tls, X n x d): delimited text or .npy")->required();

  auto run = [options, &global]() {
    const DataPair data = load_pair(options->a_path, options->b_path, global);
    std::optional<Eigen::MatrixXd> truth;
    if (!options->truth_path.empty()) {
      truth = load_matrix(options->truth_path, global);
      if (truth->rows() != data.A.cols() || truth->cols() != data.B.cols()) {
        throw io::DataError(options->truth_path, 0, 0, "the true X must be " + std::to_string(data.A.cols()) +
                                                           "x" + std::to_string(data.B.cols()));
      }
    }
    FitOptions fit_options;
    fit_options.noise_ratio = options->noise_ratio;
    const std::vector<FitResult> results = fit_all(data.A, data.B, fit_options);
    for (const FitResult& r : results) {
      for (const std::string& w : r.warnings) warn(global, std::string(to_string(r.method)) + ": " + w);
    }
    if (!options->json) {
      emit(report(results, truth), options->output);
      return;
    }
    nlohmann::json out;
    out["m"] = data.A.rows();
    out["n"] = data.A.cols();
    out["d"] = data.B.cols();
    out["results"] = nlohmann::json::array();
    for (const FitResult& r : results) {
      nlohmann::json j = result_json(r);
      if (truth && r.ok()) j["error_vs_truth"] = number_json((r.X - *truth).norm());
      out["results"].push_back(std::move(j));
    }
    emit(out.dump(2) + "\n", options->output);
  };
  return {sub, run};
}

}  // namespace spdfit::cli
