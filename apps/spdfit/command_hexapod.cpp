// spdfit hexapod model|simulate|identify: the hexapod's M_p from its geometry, simulated
// measurements, and M_p identified from measurements. Each subcommand has its own file
// (command_hexapod_*.cpp); this one registers them.
#include <memory>
#include <vector>

#include <CLI/CLI.hpp>

#include "hexapod_commands.hpp"

namespace spdfit::cli {

Command add_hexapod_command(CLI::App& app, const GlobalOptions& global) {
  CLI::App* sub =
      app.add_subcommand("hexapod", "A flexure-jointed hexapod's M_p: model, simulated data, identification");
  sub->require_subcommand(1);
  auto children = std::make_shared<std::vector<Command>>(std::vector<Command>{
      add_hexapod_model(*sub, global), add_hexapod_simulate(*sub, global), add_hexapod_identify(*sub, global)});
  auto run = [children]() {
    for (const Command& child : *children) {
      if (child.app->parsed()) child.run();
    }
  };
  return {sub, run};
}

}  // namespace spdfit::cli
