// spdfit inertia repair [--min-eig-rel R] [--metric M] [-o FILE] FILE: the nearest physically
// consistent rigid-body inertia, for a JSON body or every link of a URDF file. The library's
// workflow (inertia_repair.hpp: inertia_repair_option_table, run_inertia_repair, the renderers).
#include <iostream>
#include <memory>

#include <CLI/CLI.hpp>

#include "cli.hpp"
#include "output.hpp"
#include "spdfit/inertia_repair.hpp"
#include "spdfit/option_spelling.hpp"
#include "table_options.hpp"

namespace spdfit::cli {

Command add_inertia_command(CLI::App& app, const GlobalOptions& global) {
  CLI::App* inertia = app.add_subcommand("inertia", "Rigid-body inertias: repair physically inconsistent ones");
  inertia->require_subcommand(1);
  CLI::App* repair = inertia->add_subcommand(
      "repair",
      "The nearest physically consistent inertia (mass and centre of mass kept): FILE is JSON "
      "{\"mass\", \"center_of_mass\", \"inertia\"} (SI, about the centre of mass; or the --json of hexapod identify "
      "--physical or payload identify) or a URDF file (.urdf, .xml), whose every link's <inertial> is checked");
  auto options = std::make_shared<TableOptions<InertiaRepairRequest>>(*repair, inertia_repair_option_table());

  auto run = [options, &global]() {
    const auto& table = inertia_repair_option_table();
    InertiaRepairRequest request;
    options->apply(request);
    const InertiaRepairRun result = run_spelled(table, [&] { return run_inertia_repair(request); });
    if (result.urdf) {
      std::cerr << urdf_repair_report(*result.urdf);
      emit(result.urdf->text, request.output.output);
    } else {
      for (const Warning& w : result.body->warnings) warn(global, w);
      emit(inertia_repair_json(*result.body), request.output.output);
    }
  };
  auto command_run = [repair, run]() {
    if (repair->parsed()) run();
  };
  return {inertia, command_run};
}

}  // namespace spdfit::cli
