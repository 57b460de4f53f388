// spdfit payload identify LOG [...] | design CANDIDATES --poses K [...]: a payload's mass, centre
// of mass and inertia from a wrist force/torque sensor's log, and the poses to log it at. The
// options come from the library's tables (identify_option_table, design_option_table).
#include <memory>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "cli.hpp"
#include "spdfit/option_spelling.hpp"
#include "output.hpp"
#include "spdfit/io.hpp"
#include "spdfit/payload/design.hpp"
#include "spdfit/payload/identify.hpp"
#include "table_options.hpp"

namespace spdfit::cli {

namespace {

// A library message about this command's options, spelled with its own table first.
template <typename Request>
[[noreturn]] void usage(const std::exception& e, const std::vector<OptionSpec<Request>>& table) {
  throw UsageError(spell_options_with(e.what(), Frontend::Cli, table));
}

template <typename Request, typename Fn>
auto run_spelled(const std::vector<OptionSpec<Request>>& table, Fn&& fn) {
  try {
    return fn();
  } catch (const OptionError& e) {
    usage(e, table);
  } catch (const io::ColumnSelectionError& e) {
    usage(e, table);
  } catch (const io::DataError& e) {
    throw DataFailure(spell_options_with(e.what(), Frontend::Cli, table));
  }
}

Command add_payload_identify(CLI::App& parent, const GlobalOptions& global) {
  struct Cli {
    std::string log, output;
    bool json = false;
    std::unique_ptr<TableOptions<payload::IdentifyRequest>> table;
  };
  auto cli = std::make_shared<Cli>();
  CLI::App* sub = parent.add_subcommand(
      "identify",
      "A payload's mass, centre of mass, inertia (moving poses) and the sensor's biases from a force/torque log over "
      "many poses, physically consistent (docs/payload.md)");
  sub->add_option("LOG", cli->log, "The log: one table (any format spdfit reads), columns chosen by the --*-cols "
                                   "options")
      ->required();
  cli->table = std::make_unique<TableOptions<payload::IdentifyRequest>>(*sub, payload::identify_option_table());
  sub->add_flag("--json", cli->json, "Print the estimate as JSON");
  sub->add_option("-o,--output", cli->output, "Write to FILE instead of stdout");

  auto run = [cli, &global]() {
    const auto& table = payload::identify_option_table();
    payload::IdentifyRequest request;
    request.read = global.read;
    run_spelled(table, [&] {
      check_option_combination(table, cli->table->given());
      return 0;
    });
    cli->table->apply(request);
    const payload::PayloadEstimate estimate =
        run_spelled(table, [&] { return payload::identify_file(cli->log, request); });
    for (const std::string& w : estimate.warnings) warn(global, spell_options_with(w, Frontend::Cli, table));
    std::string urdf;
    if (!request.urdf.empty()) urdf = run_spelled(table, [&] { return payload::urdf_text(estimate, request); });
    emit(cli->json ? payload::to_json(estimate) : payload::report(estimate), cli->output);
    if (!urdf.empty()) io::write_text(request.urdf, urdf);
    if (!estimate.ok()) throw DataFailure("payload identification failed: " + estimate.message);
  };
  return {sub, run};
}

Command add_payload_design(CLI::App& parent, const GlobalOptions& global) {
  struct Cli {
    std::string candidates, output;
    bool json = false;
    std::unique_ptr<TableOptions<payload::DesignRequest>> table;
  };
  auto cli = std::make_shared<Cli>();
  CLI::App* sub = parent.add_subcommand(
      "design", "Choose K of the candidate orientations (one per row) that determine the payload best (D-, E- or "
                "A-optimal), against random choices from the same pool");
  sub->add_option("CANDIDATES", cli->candidates, "The candidate poses: one per row, the orientation as payload "
                                                 "identify takes it (--quat-cols, --rotation-cols or --gravity-cols)")
      ->required();
  cli->table = std::make_unique<TableOptions<payload::DesignRequest>>(*sub, payload::design_option_table());
  sub->add_flag("--json", cli->json, "Print the result as JSON");
  sub->add_option("-o,--output", cli->output, "Write the chosen rows (every column, as CSV) to FILE");

  auto run = [cli, &global]() {
    const auto& table = payload::design_option_table();
    payload::DesignRequest request;
    request.read = global.read;
    run_spelled(table, [&] {
      check_option_combination(table, cli->table->given());
      return 0;
    });
    cli->table->apply(request);
    const payload::DesignResult result = run_spelled(table, [&] { return payload::design_file(cli->candidates, request); });
    for (const std::string& w : result.warnings) warn(global, spell_options_with(w, Frontend::Cli, table));
    emit(cli->json ? payload::to_json(result) : payload::report(result), "");
    if (!cli->output.empty()) io::write_text(cli->output, payload::chosen_rows_csv(result));
  };
  return {sub, run};
}

}  // namespace

Command add_payload_command(CLI::App& app, const GlobalOptions& global) {
  CLI::App* sub = app.add_subcommand(
      "payload", "A payload on a wrist force/torque sensor: identify its mass properties, design the poses");
  sub->require_subcommand(1);
  auto children = std::make_shared<std::vector<Command>>(
      std::vector<Command>{add_payload_identify(*sub, global), add_payload_design(*sub, global)});
  auto run = [children]() {
    for (const Command& child : *children) {
      if (child.app->parsed()) child.run();
    }
  };
  return {sub, run};
}

}  // namespace spdfit::cli
