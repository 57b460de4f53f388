// spdfit solve [--json] [--threshold T] [--output FILE] A b: the library's workflow
// (spdfit/solve_request.hpp) with its options from its table.
#include <memory>

#include <CLI/CLI.hpp>

#include "cli.hpp"
#include "output.hpp"
#include "spdfit/render.hpp"
#include "spdfit/solve_request.hpp"
#include "table_options.hpp"

namespace spdfit::cli {

Command add_solve_command(CLI::App& app, const GlobalOptions& global) {
  auto table = std::make_shared<std::unique_ptr<TableOptions<SolveRequest>>>();
  CLI::App* sub = app.add_subcommand(
      "solve", "Classify and solve A x = b: rank, consistency, finite solutions and solutions at infinity");
  *table = std::make_unique<TableOptions<SolveRequest>>(*sub, solve_option_table());

  auto run = [table, &global]() {
    SolveRequest request;
    request.read = global.read;
    (*table)->apply(request);
    const SolveRun run = run_solve(request);
    for (const Warning& w : run.warnings) warn(global, w);
    if (const auto failure = run.failure()) throw DataFailure(failure->message, failure->code);
    emit(request.output.json ? to_json(run.result) : report(run.result), request.output.output);
  };
  return {sub, run};
}

}  // namespace spdfit::cli
