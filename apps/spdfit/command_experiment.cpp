// spdfit experiment thesis|paper-hexapod|paper-2x2|physical: the seeds' Monte Carlo experiments.
// The library's workflow (experiment/experiment_request.hpp: the option tables, run_experiment,
// the renderings).
#include <memory>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "cli.hpp"
#include "output.hpp"
#include "progress_line.hpp"
#include "spdfit/experiment/experiment_request.hpp"
#include "table_options.hpp"

namespace spdfit::cli {

namespace {

using experiment::ExperimentKind;
using experiment::ExperimentRequest;

// An experiment's subcommand with the options of its library table.
Command add_experiment(CLI::App& parent, const GlobalOptions& global, ExperimentKind kind, const std::string& description,
                       const std::string& footer = {}) {
  const auto& table = experiment::experiment_option_table(kind);
  CLI::App* sub = parent.add_subcommand(std::string(experiment::to_string(kind)), description);
  if (!footer.empty()) sub->footer(footer);
  auto options = std::make_shared<TableOptions<ExperimentRequest>>(*sub, table);
  auto run = [options, kind, &table, &global]() {
    ExperimentRequest request = experiment::experiment_request(kind);
    options->apply(request);
    std::string label = "experiment " + std::string(experiment::to_string(kind));
    if (request.sweep) label += " --sweep";
    const experiment::ExperimentRun run = run_spelled(
        table, [&] { return experiment::run_experiment(request, options->given(), trials_progress(global, label)); });
    if (!request.csv.empty()) emit(experiment::to_csv(run), request.csv);
    emit(request.output.json ? experiment::to_json(run) : experiment::report(run, request.csv), request.output.output);
  };
  return {sub, run};
}

}  // namespace

Command add_experiment_command(CLI::App& app, const GlobalOptions& global) {
  CLI::App* sub = app.add_subcommand("experiment", "Monte Carlo experiments of the source documents");
  sub->require_subcommand(1);
  auto children = std::make_shared<std::vector<Command>>(std::vector<Command>{
      add_experiment(*sub, global, ExperimentKind::Thesis,
                     "The thesis' chapter-6 experiment (M_p of eq. 6.1, appendix-B generator), repeated --trials times"),
      add_experiment(*sub, global, ExperimentKind::PaperHexapod,
                     "The paper's Figure 2: per-entry error statistics of the 21 parameters of M_p, Procrustes "
                     "against SPDE",
                     "The paper's data came from sensors whose noise it does not give; the default is the thesis'\n"
                     "Experiment 2 level (V = 0.86, m = 12, uniform)."),
      add_experiment(*sub, global, ExperimentKind::Paper2x2,
                     "The paper's 2x2 example (Figure 3): X = [3 1; 1 1] from A X ~= B with Gaussian noise in A and B",
                     "Methods (default): procrustes (least squares), tls (unsymmetrized, the paper's footnote 2), "
                     "spde.\nmae: mean |x_hat - x|; std: standard deviation of x_hat - x; bias: mean of x_hat - x."),
      add_experiment(*sub, global, ExperimentKind::Physical,
                     "Physical identification of the payload against the generic estimators: error of M_p over m, "
                     "and how often each estimate is physically consistent",
                     "physical: spdfit's estimator (errors in variables, physically consistent); physical-ls: its "
                     "convex least-\nsquares start; grey-box-tls and grey-box-ls: the same model without the "
                     "consistency constraint.")});
  auto run = [children]() {
    for (const Command& child : *children) {
      if (child.app->parsed()) child.run();
    }
  };
  return {sub, run};
}

}  // namespace spdfit::cli
