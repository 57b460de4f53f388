// spdfit hexapod model [--geometry G.json] [--json] [--write-geometry FILE] [-o FILE]: the Jacobian,
// the joint-space mass-inertia matrix M_p and the modes of a hexapod. The library's workflow
// (hexapod/model_request.hpp: model_option_table, run_model, its renderings).
#include <iostream>
#include <memory>

#include <CLI/CLI.hpp>

#include "hexapod_commands.hpp"
#include "output.hpp"
#include "spdfit/hexapod/geometry.hpp"
#include "spdfit/hexapod/model_request.hpp"
#include "table_options.hpp"

namespace spdfit::cli {

Command add_hexapod_model(CLI::App& parent, const GlobalOptions&) {
  using hexapod::ModelRequest;
  CLI::App* sub = parent.add_subcommand(
      "model",
      "The Jacobian, the joint-space mass-inertia matrix M_p (thesis eq. 2.12) and the modes of a hexapod");
  auto options = std::make_shared<TableOptions<ModelRequest>>(*sub, hexapod::model_option_table());

  auto run = [options]() {
    const auto& table = hexapod::model_option_table();
    ModelRequest request;
    options->apply(request);
    const hexapod::ModelResult result = run_spelled(table, [&] { return hexapod::run_model(request); });
    if (!request.write_geometry.empty()) {
      emit(hexapod::geometry_json(result.geometry), request.write_geometry);
      // On stderr: stdout carries the model, which may be piped on.
      std::cerr << "spdfit: wrote the geometry to " << request.write_geometry << " (edit it, then --geometry "
                << request.write_geometry << ")\n";
    }
    emit(request.output.json ? hexapod::to_json(result) : hexapod::report(result), request.output.output);
  };
  return {sub, run};
}

}  // namespace spdfit::cli
