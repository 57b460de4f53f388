// spdfit compare [--truth T] [--json] A B: every estimator on the same data, side by side; the
// library's workflow (spdfit/compare.hpp: run_compare) with its options from its table.
#include <memory>

#include <CLI/CLI.hpp>

#include "cli.hpp"
#include "output.hpp"
#include "spdfit/compare.hpp"
#include "spdfit/render.hpp"
#include "table_options.hpp"

namespace spdfit::cli {

Command add_compare_command(CLI::App& app, const GlobalOptions& global) {
  auto table = std::make_shared<std::unique_ptr<TableOptions<CompareRequest>>>();
  CLI::App* sub = app.add_subcommand("compare", "Run every estimator on A X ~= B and show them side by side");
  *table = std::make_unique<TableOptions<CompareRequest>>(*sub, compare_option_table());

  auto run = [table, &global]() {
    CompareRequest request;
    request.fit.read = global.read;
    (*table)->apply(request);
    try {
      check_compare_request(request, (*table)->given());
    } catch (const OptionError& e) {
      throw_usage(e);
    }
    const CompareRun result = run_compare(request);
    for (const Warning& w : result.warnings) warn(global, w);
    emit(request.output.json ? to_json(result.comparison) : report(result.comparison), request.output.output);
  };
  return {sub, run};
}

}  // namespace spdfit::cli
