// spdfit physical regress Y TAU --bodies K [...]: physically consistent least squares for any model
// linear in the inertial parameters of K rigid bodies. Options from regress_option_table.
#include <memory>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "cli.hpp"
#include "spdfit/option_spelling.hpp"
#include "output.hpp"
#include "spdfit/io.hpp"
#include "spdfit/physical/regress.hpp"
#include "table_options.hpp"

namespace spdfit::cli {

Command add_physical_command(CLI::App& app, const GlobalOptions& global) {
  CLI::App* sub = app.add_subcommand("physical", "Physically consistent identification of rigid bodies");
  sub->require_subcommand(1);
  struct Cli {
    std::string y, tau, output;
    bool json = false;
    std::unique_ptr<TableOptions<physical::RegressRequest>> table;
  };
  auto cli = std::make_shared<Cli>();
  CLI::App* regress = sub->add_subcommand(
      "regress",
      "Physically consistent least squares tau ~= Y phi for K rigid bodies (each body's pseudo-inertia positive "
      "semidefinite): base parameters, undetermined combinations, a prior, the certificate (docs/payload.md)");
  regress->add_option("Y", cli->y, "The stacked regressor (rows = samples x outputs; 10 K body columns, then any "
                                   "extra columns)")
      ->required();
  regress->add_option("TAU", cli->tau, "The stacked outputs (one column, Y's rows)")->required();
  cli->table = std::make_unique<TableOptions<physical::RegressRequest>>(*regress, physical::regress_option_table());
  regress->add_flag("--json", cli->json, "Print the result as JSON");
  regress->add_option("-o,--output", cli->output, "Write to FILE instead of stdout");

  auto run = [cli, &global]() {
    const auto& table = physical::regress_option_table();
    physical::RegressRequest request;
    try {
      check_option_combination(table, cli->table->given());
    } catch (const OptionError& e) {
      throw UsageError(spell_options_with(e.what(), Frontend::Cli, table));
    }
    cli->table->apply(request);
    physical::RegressResult result;
    try {
      result = physical::regress_files(cli->y, cli->tau, request, global.read);
    } catch (const OptionError& e) {
      throw UsageError(spell_options_with(e.what(), Frontend::Cli, table));
    } catch (const io::DataError& e) {
      throw DataFailure(spell_options_with(e.what(), Frontend::Cli, table));
    }
    for (const std::string& w : result.warnings) warn(global, spell_options_with(w, Frontend::Cli, table));
    emit(cli->json ? physical::to_json(result) : physical::report(result), cli->output);
    if (!result.ok()) throw DataFailure("the regression failed: " + result.message);
  };
  auto command_run = [regress, run]() {
    if (regress->parsed()) run();
  };
  return {sub, command_run};
}

}  // namespace spdfit::cli
