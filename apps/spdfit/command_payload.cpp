// spdfit payload identify LOG [...] | design CANDIDATES --poses K [...]: a payload's mass, centre
// of mass and inertia from a wrist force/torque sensor's log, and the poses to log it at. The
// library's workflows (payload/identify.hpp, payload/design.hpp): their tables give the options,
// their checks the rules, their runs the results, their renderers the output.
#include <memory>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "cli.hpp"
#include "output.hpp"
#include "spdfit/io.hpp"
#include "spdfit/option_spelling.hpp"
#include "spdfit/payload/design.hpp"
#include "spdfit/payload/identify.hpp"
#include "table_options.hpp"

namespace spdfit::cli {

namespace {

Command add_payload_identify(CLI::App& parent, const GlobalOptions& global) {
  using payload::IdentifyRequest;
  auto options = std::make_shared<std::unique_ptr<TableOptions<IdentifyRequest>>>();
  CLI::App* sub = parent.add_subcommand(
      "identify",
      "A payload's mass, centre of mass, inertia (moving poses) and the sensor's biases from a force/torque log over "
      "many poses, physically consistent (docs/payload.md)");
  *options = std::make_unique<TableOptions<IdentifyRequest>>(*sub, payload::identify_option_table());

  auto run = [options, &global]() {
    const auto& table = payload::identify_option_table();
    IdentifyRequest request;
    request.read = global.read;
    (*options)->apply(request);
    run_spelled(table, [&] { payload::check_identify_request(request, (*options)->given()); });
    const payload::PayloadEstimate estimate = run_spelled(table, [&] { return payload::run_identify(request); });
    for (const Warning& w : estimate.warnings) warn_spelled(global, w, table);
    std::string urdf;
    if (!request.urdf.empty()) urdf = run_spelled(table, [&] { return payload::urdf_text(estimate, request); });
    emit(request.output.json ? payload::to_json(estimate) : payload::report(estimate), request.output.output);
    if (!urdf.empty()) io::write_text(request.urdf, urdf);
    if (!estimate.ok()) throw DataFailure("payload identification failed: " + estimate.message);
  };
  return {sub, run};
}

Command add_payload_design(CLI::App& parent, const GlobalOptions& global) {
  using payload::DesignRequest;
  auto options = std::make_shared<std::unique_ptr<TableOptions<DesignRequest>>>();
  CLI::App* sub = parent.add_subcommand(
      "design", "Choose K of the candidate orientations (one per row) that determine the payload best (D-, E- or "
                "A-optimal), against random choices from the same pool");
  *options = std::make_unique<TableOptions<DesignRequest>>(*sub, payload::design_option_table());

  auto run = [options, &global]() {
    const auto& table = payload::design_option_table();
    DesignRequest request;
    request.read = global.read;
    (*options)->apply(request);
    run_spelled(table, [&] { payload::check_design_request(request, (*options)->given()); });
    const payload::DesignResult result = run_spelled(table, [&] { return payload::run_design(request); });
    for (const Warning& w : result.warnings) warn_spelled(global, w, table);
    emit(request.output.json ? payload::to_json(result) : payload::report(result), "");
    if (!request.output.output.empty()) io::write_text(request.output.output, payload::chosen_rows_csv(result));
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
