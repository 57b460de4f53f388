// spdfit nearest [options] X: the library's workflow (spdfit/nearest_request.hpp: run_nearest)
// with its options from its table (nearest_command_table).
#include <memory>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "cli.hpp"
#include "output.hpp"
#include "spdfit/labels.hpp"
#include "spdfit/nearest_request.hpp"
#include "spdfit/render.hpp"
#include "table_options.hpp"

namespace spdfit::cli {

namespace {
// The columns of F under --header: "factor 1", "factor 2", ...
std::vector<std::string> factor_names(Eigen::Index k) {
  std::vector<std::string> names;
  for (Eigen::Index j = 0; j < k; ++j) names.push_back("factor " + std::to_string(j + 1));
  return names;
}
}  // namespace

Command add_nearest_command(CLI::App& app, const GlobalOptions& global) {
  auto table = std::make_shared<std::unique_ptr<TableOptions<NearestCommand>>>();
  CLI::App* sub = app.add_subcommand(
      "nearest",
      "Repair a covariance or correlation matrix: the nearest symmetric positive definite matrix to X (Higham), "
      "or with a fixed diagonal (--corr, --keep-diag, --via-corr), entries kept (--fixed), elementwise weights "
      "(--h-weights), a rank (--rank) or factor structure (--factors)");
  *table = std::make_unique<TableOptions<NearestCommand>>(*sub, nearest_command_table());

  auto run = [table, &global]() {
    NearestCommand command;
    command.read = global.read;
    (*table)->apply(command);
    const OutputRequest& output = command.output;
    if (output.json) check_text_output(output.output, "--json");
    if (output.header) check_text_output(output.output, "--header");
    try {
      check_nearest_request((*table)->given());
    } catch (const OptionError& e) {
      throw_usage(e);
    }
    const NearestRun result = run_nearest(command);
    for (const Warning& w : result.warnings) warn(global, w);
    // With `factors_only` the answer is F (n x K): its rows are the variables, its columns the factors.
    const bool loadings = command.repair.factors_only;
    const Eigen::MatrixXd& answer = loadings ? result.result.F : result.result.X;
    if (output.header) {
      emit(labelled_csv(answer, result.names, loadings ? factor_names(answer.cols()) : result.names), output.output);
    } else if (output.json) {
      emit(to_json(result), output.output);
    } else {
      emit_matrix(answer, output.output);
    }
  };
  return {sub, run};
}

}  // namespace spdfit::cli
