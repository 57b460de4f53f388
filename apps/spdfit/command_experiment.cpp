// spdfit experiment thesis|paper-hexapod|paper-2x2|physical: the seeds' Monte Carlo experiments.
// Their options are the library's tables (experiment/experiment_request.hpp); what they print is
// experiment_output.cpp's.
#include <functional>
#include <cmath>
#include <CLI/CLI.hpp>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "cli.hpp"
#include "experiment_output.hpp"
#include "output.hpp"
#include "table_options.hpp"
#include "spdfit/experiment/experiment_request.hpp"
#include "spdfit/experiment/paper.hpp"
#include "spdfit/experiment/physical.hpp"
#include "spdfit/experiment/thesis.hpp"
#include "spdfit/format.hpp"
#include "spdfit/hexapod/geometry.hpp"
#include "spdfit/io.hpp"
#include "spdfit/options.hpp"
#include "validators.hpp"

namespace spdfit::cli {

namespace {

// Whether the results include both methods (the text reports compare them when they do).
template <typename Result>
bool has_both(const Result& result, Method a, Method b) {
  bool found_a = false, found_b = false;
  for (const auto& m : result.methods) {
    found_a = found_a || m.method == a;
    found_b = found_b || m.method == b;
  }
  return found_a && found_b;
}

using experiment::ExperimentKind;
using experiment::ExperimentRequest;

// An experiment's subcommand with the options of its library table; `report` runs the request
// (checked) and prints its results.
Command add_experiment(CLI::App& parent, const GlobalOptions& global, ExperimentKind kind, const std::string& description,
                       const std::string& footer,
                       std::function<void(const ExperimentRequest&, experiment::MonteCarloOptions)> report) {
  const auto& table = experiment::experiment_option_table(kind);
  CLI::App* sub = parent.add_subcommand(std::string(experiment::to_string(kind)), description);
  if (!footer.empty()) sub->footer(footer);
  auto options = std::make_shared<TableOptions<ExperimentRequest>>(*sub, table);
  auto run = [options, kind, &table, &global, report]() {
    ExperimentRequest request = experiment::experiment_request(kind);
    options->apply(request);
    run_spelled(table, [&] { experiment::check_experiment_request(request, options->given()); });
    experiment::MonteCarloOptions monte_carlo = experiment::monte_carlo_options(request);
    std::string label = "experiment " + std::string(experiment::to_string(kind));
    if (request.sweep) label += " --sweep";
    monte_carlo.progress = trials_progress(global, label);
    report(request, std::move(monte_carlo));
  };
  return {sub, run};
}

std::string describe(const hexapod::SimulationOptions& s) {
  std::ostringstream out;
  out << "m = " << s.samples << " samples of 6 strut accelerations (uniform, variance "
      << format_fixed(s.signal_var, 3) << "),\n"
      << hexapod::to_string(s.distribution) << " noise of variance " << s.noise_var;
  if (s.noise_std_a || s.noise_std_b) {
    const auto list = [](const std::optional<Eigen::VectorXd>& v, double variance) {
      if (!v) return format_number(std::sqrt(variance), Precision::Medium);
      std::string text;
      for (Eigen::Index i = 0; i < v->size(); ++i) text += (i ? ", " : "") + format_number((*v)(i), Precision::Medium);
      return text;
    };
    out.str("");
    out << "m = " << s.samples << " samples of 6 strut accelerations (uniform, variance "
        << format_fixed(s.signal_var, 3) << "),\n"
        << hexapod::to_string(s.distribution) << " noise of standard deviation " << list(s.noise_std_a, s.noise_var)
        << " in A and " << list(s.noise_std_b, s.force_noise_var.value_or(s.noise_var)) << " in B";
  } else if (s.force_noise_var && *s.force_noise_var != s.noise_var) {
    out << " in every entry of A and " << *s.force_noise_var << " in every entry of B";
  } else {
    out << " in every entry of A and B";
  }
  if (s.scale_b != 1.0) out << ", B scaled by " << format_number(s.scale_b, Precision::Medium);
  if (s.rest_samples > 0) out << ", " << s.rest_samples << " rows at rest";
  return out.str();
}

// The options of an experiment from a checked request; a refusal spelled with its table.
template <typename Options>
Options experiment_options(const ExperimentRequest& request, Options (*of)(const ExperimentRequest&)) {
  return run_spelled(experiment::experiment_option_table(request.kind), [&] { return of(request); });
}

void report_thesis(const ExperimentRequest& request, const experiment::MonteCarloOptions& monte_carlo) {
  const experiment::ThesisExperimentOptions options = experiment_options(request, &experiment::thesis_options);
  const experiment::ThesisExperimentResult result = experiment::run_thesis_experiment(options, monte_carlo);
  if (!request.csv.empty()) emit(thesis_csv(result), request.csv);
  if (request.output.json) {
    emit(thesis_json(result).dump(2) + "\n", request.output.output);
    return;
  }
  std::ostringstream out;
  out << "Thesis experiment (seed 000, chapter 6), M_p of eq. 6.1:\n"
      << describe(result.options.simulation) << ".\n"
      << result.trials << " trials, seed " << result.seed << ". Error ||M_p - M_hat||_F:\n\n"
      << thesis_table(result);
  if (has_both(result, Method::Spde, Method::SymmetricProcrustes)) {
    out << '\n' << paired_line(result, Method::Spde, Method::SymmetricProcrustes);
  }
  emit(out.str(), request.output.output);
}

void report_paper_hexapod(const ExperimentRequest& request, const experiment::MonteCarloOptions& monte_carlo) {
  const experiment::PaperHexapodOptions options = experiment_options(request, &experiment::paper_hexapod_options);
  const experiment::EntryExperimentResult result = experiment::run_paper_hexapod(options, monte_carlo);
  if (!request.csv.empty()) emit(entry_csv(result, "m"), request.csv);
  if (request.output.json) {
    nlohmann::json out;
    out["experiment"] = "paper-hexapod";
    out["noise_var"] = options.simulation.noise_var;
    out["force_noise_var"] = options.simulation.force_noise_var.value_or(options.simulation.noise_var);
    out["samples"] = options.simulation.samples;
    out["trials"] = result.trials;
    out["seed"] = result.seed;
    out["signal_var"] = options.simulation.signal_var;
    out["distribution"] = std::string(hexapod::to_string(options.simulation.distribution));
    out["entries"] = entries_json(result);
    out["truth"] = matrix_json(result.truth);
    out["methods"] = entry_methods_json(result);
    emit(out.dump(2) + "\n", request.output.output);
    return;
  }
  std::ostringstream out;
  out << "The paper's hexapod experiment (seed 001, Figure 2), M_p of thesis eq. 6.1:\n"
      << describe(options.simulation) << ".\n"
      << result.trials << " trials, seed " << result.seed
      << ". |e|: mean absolute error; std e: standard deviation of the error.\n\n"
      << entry_table(result, "m");
  if (has_both(result, Method::Spde, Method::SymmetricProcrustes)) {
    const experiment::EntryExperimentResult::Wins wins = result.wins(Method::Spde, Method::SymmetricProcrustes);
    out << '\n'
        << "spde has the smaller mean absolute error on " << wins.mae << " of " << wins.entries
        << " entries and the smaller standard deviation on " << wins.std << ".\n";
  }
  emit(out.str(), request.output.output);
}

void report_paper_2x2_sweep(const ExperimentRequest& request, const experiment::Paper2x2Options& options,
                            const experiment::MonteCarloOptions& monte_carlo) {
  const std::vector<double> levels = experiment::paper_2x2_sweep_levels();
  const std::vector<experiment::EntryExperimentResult> results =
      experiment::run_paper_2x2_sweep(options, levels, monte_carlo);
  const std::string csv = sweep_csv(levels, options.std_b, results);
  if (!request.csv.empty()) emit(csv, request.csv);
  if (request.output.json) {
    nlohmann::json out;
    out["experiment"] = "paper-2x2";
    out["sweep"] = true;
    out["std_b"] = options.std_b;
    out["trials"] = request.trials;
    out["seed"] = request.seed;
    out["entries"] = entries_json(results.front());
    out["levels"] = nlohmann::json::array();
    for (std::size_t l = 0; l < levels.size(); ++l) {
      out["levels"].push_back({{"std_a", levels[l]}, {"methods", entry_methods_json(results[l])}});
    }
    emit(out.dump(2) + "\n", request.output.output);
  } else if (!request.csv.empty()) {
    std::ostringstream out;
    out << "The paper's 2x2 example (seed 001, Figure 3), std_b = " << options.std_b << ", " << request.trials
        << " trials per level, seed " << request.seed << "; table written to " << request.csv << ".\n\n"
        << sweep_table(levels, results);
    emit(out.str(), request.output.output);
  } else {
    emit(csv, request.output.output);
  }
}

void report_paper_2x2(const ExperimentRequest& request, const experiment::MonteCarloOptions& monte_carlo) {
  const experiment::Paper2x2Options options = experiment_options(request, &experiment::paper_2x2_options);
  if (request.sweep) {
    report_paper_2x2_sweep(request, options, monte_carlo);
    return;
  }
  const experiment::EntryExperimentResult result = experiment::run_paper_2x2(options, monte_carlo);
  if (!request.csv.empty()) emit(entry_csv(result, "x"), request.csv);
  if (request.output.json) {
    nlohmann::json out;
    out["experiment"] = "paper-2x2";
    out["std_a"] = options.std_a;
    out["std_b"] = options.std_b;
    out["trials"] = result.trials;
    out["seed"] = result.seed;
    out["entries"] = entries_json(result);
    out["truth"] = matrix_json(result.truth);
    out["methods"] = entry_methods_json(result);
    emit(out.dump(2) + "\n", request.output.output);
    return;
  }
  std::ostringstream out;
  out << "The paper's 2x2 example (seed 001, Figure 3): std_a = " << options.std_a << ", std_b = " << options.std_b
      << "; " << result.trials << " trials, seed " << result.seed
      << ".\n|e|: mean absolute error; std e: standard deviation of the error.\n\n"
      << entry_table(result, "x");
  emit(out.str(), request.output.output);
}

void report_physical(const ExperimentRequest& request, const experiment::MonteCarloOptions& monte_carlo) {
  const experiment::PhysicalExperimentOptions options = experiment_options(request, &experiment::physical_options);
  const experiment::PhysicalExperimentResult result = experiment::run_physical_experiment(options, monte_carlo);
  emit(request.output.json ? experiment::to_json(result) : experiment::report(result), request.output.output);
}

}  // namespace

Command add_experiment_command(CLI::App& app, const GlobalOptions& global) {
  CLI::App* sub = app.add_subcommand("experiment", "Monte Carlo experiments of the source documents");
  sub->require_subcommand(1);
  auto children = std::make_shared<std::vector<Command>>(std::vector<Command>{
      add_experiment(*sub, global, ExperimentKind::Thesis,
                     "The thesis' chapter-6 experiment (M_p of eq. 6.1, appendix-B generator), repeated --trials times",
                     "", report_thesis),
      add_experiment(*sub, global, ExperimentKind::PaperHexapod,
                     "The paper's Figure 2: per-entry error statistics of the 21 parameters of M_p, Procrustes "
                     "against SPDE",
                     "The paper's data came from sensors whose noise it does not give; the default is the thesis'\n"
                     "Experiment 2 level (V = 0.86, m = 12, uniform).",
                     report_paper_hexapod),
      add_experiment(*sub, global, ExperimentKind::Paper2x2,
                     "The paper's 2x2 example (Figure 3): X = [3 1; 1 1] from A X ~= B with Gaussian noise in A and B",
                     "Methods (default): procrustes (least squares), tls (unsymmetrized, the paper's footnote 2), "
                     "spde.\nmae: mean |x_hat - x|; std: standard deviation of x_hat - x; bias: mean of x_hat - x.",
                     report_paper_2x2),
      add_experiment(*sub, global, ExperimentKind::Physical,
                     "Physical identification of the payload against the generic estimators: error of M_p over m, "
                     "and how often each estimate is physically consistent",
                     "physical: spdfit's estimator (errors in variables, physically consistent); physical-ls: its "
                     "convex least-\nsquares start; grey-box-tls and grey-box-ls: the same model without the "
                     "consistency constraint.",
                     report_physical)});
  auto run = [children]() {
    for (const Command& child : *children) {
      if (child.app->parsed()) child.run();
    }
  };
  return {sub, run};
}

}  // namespace spdfit::cli
