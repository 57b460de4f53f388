// spdfit nearest [options] X: the library's workflow (spdfit/nearest_request.hpp: run_nearest)
// with its options from its table (nearest_command_table).
#include <memory>

#include <CLI/CLI.hpp>

#include "cli.hpp"
#include "output.hpp"
#include "spdfit/labels.hpp"
#include "spdfit/nearest_request.hpp"
#include "spdfit/render.hpp"
#include "table_options.hpp"

namespace spdfit::cli {

Command add_nearest_command(CLI::App& app, const GlobalOptions& global) {
  auto table = std::make_shared<std::unique_ptr<TableOptions<NearestCommand>>>();
  CLI::App* sub = app.add_subcommand(
      "nearest",
      "Repair a covariance or correlation matrix: the nearest symmetric positive definite matrix to X (Higham), "
      "or with a fixed diagonal (--corr, --keep-diag, --via-corr)");
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
    if (output.header) {
      emit(labelled_csv(result.result.X, result.names, result.names), output.output);
    } else if (output.json) {
      emit(to_json(result), output.output);
    } else {
      emit_matrix(result.result.X, output.output);
    }
  };
  return {sub, run};
}

}  // namespace spdfit::cli
