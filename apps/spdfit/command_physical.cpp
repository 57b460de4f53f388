// spdfit physical regress Y TAU --bodies K [...]: physically consistent least squares for any model
// linear in the inertial parameters of K rigid bodies. The library's workflow (physical/regress.hpp:
// regress_option_table, check_regress_request, run_regress, its renderers).
#include <memory>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "cli.hpp"
#include "output.hpp"
#include "spdfit/option_spelling.hpp"
#include "spdfit/physical/regress.hpp"
#include "table_options.hpp"

namespace spdfit::cli {

Command add_physical_command(CLI::App& app, const GlobalOptions& global) {
  using physical::RegressRequest;
  CLI::App* sub = app.add_subcommand("physical", "Physically consistent identification of rigid bodies");
  sub->require_subcommand(1);
  auto options = std::make_shared<std::unique_ptr<TableOptions<RegressRequest>>>();
  CLI::App* regress = sub->add_subcommand(
      "regress",
      "Physically consistent least squares tau ~= Y phi for K rigid bodies (each body's pseudo-inertia positive "
      "semidefinite): base parameters, undetermined combinations, a prior, the certificate (docs/payload.md)");
  *options = std::make_unique<TableOptions<RegressRequest>>(*regress, physical::regress_option_table());

  auto run = [options, &global]() {
    const auto& table = physical::regress_option_table();
    RegressRequest request;
    (*options)->apply(request);
    run_spelled(table, [&] { physical::check_regress_request(request, (*options)->given()); });
    const physical::RegressResult result = run_spelled(table, [&] { return physical::run_regress(request, global.read); });
    for (const Warning& w : result.warnings) warn_spelled(global, w, table);
    emit(request.output.json ? physical::to_json(result) : physical::report(result), request.output.output);
    if (!result.ok()) throw DataFailure("the regression failed: " + result.message);
  };
  auto command_run = [regress, run]() {
    if (regress->parsed()) run();
  };
  return {sub, command_run};
}

}  // namespace spdfit::cli
