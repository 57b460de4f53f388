// spdfit hexapod identify A B [options]: M_p identified from measured accelerations and forces by
// every estimator, and with --physical the payload's mass properties. The library's workflow
// (hexapod/identify_request.hpp): its table gives the options, its check the rules, its run the
// result, its renderers the output.
#include <CLI/CLI.hpp>
#include <memory>

#include "hexapod_commands.hpp"
#include "output.hpp"
#include "spdfit/hexapod/identify_request.hpp"
#include "table_options.hpp"

namespace spdfit::cli {

Command add_hexapod_identify(CLI::App& parent, const GlobalOptions& global) {
  using hexapod::IdentifyRequest;
  auto table = std::make_shared<std::unique_ptr<TableOptions<IdentifyRequest>>>();
  CLI::App* sub = parent.add_subcommand(
      "identify", "Identify M_p from accelerations A and base forces B (B ~= A M_p) with every estimator");
  *table = std::make_unique<TableOptions<IdentifyRequest>>(*sub, hexapod::identify_option_table());

  auto run = [table, &global]() {
    IdentifyRequest request;
    request.fit.read = global.read;
    (*table)->apply(request);
    try {
      hexapod::check_identify_request(request, (*table)->given());
    } catch (const OptionError& e) {
      throw_usage(e);
    }
    const hexapod::Identification result = hexapod::run_identify(request);
    for (const Warning& w : result.warnings) warn(global, w);
    emit(request.output.json ? hexapod::to_json(result) : hexapod::report(result), request.output.output);
    // The report says why too; the exit status tells a script that the fit asked for failed.
    if (const auto failure = result.failure()) throw DataFailure(failure->message, failure->code);
  };
  return {sub, run};
}

}  // namespace spdfit::cli
