// spdfit hexapod simulate --noise-var V --out DIR [...]: accelerations A and base forces
// B = A M_p with noise, the thesis' appendix-B generator, written as files. The library's workflow
// (hexapod/simulate_request.hpp: simulate_option_table, run_simulate, write_simulation).
#include <memory>

#include <CLI/CLI.hpp>

#include "hexapod_commands.hpp"
#include "output.hpp"
#include "spdfit/hexapod/simulate_request.hpp"
#include "spdfit/option_spelling.hpp"
#include "table_options.hpp"

namespace spdfit::cli {

Command add_hexapod_simulate(CLI::App& parent, const GlobalOptions& global) {
  using hexapod::SimulateRequest;
  CLI::App* sub = parent.add_subcommand(
      "simulate",
      "Simulated accelerations A and base forces B = A M_p with noise (the thesis' appendix-B generator)");
  auto options = std::make_shared<TableOptions<SimulateRequest>>(*sub, hexapod::simulate_option_table());

  auto run = [options, &global]() {
    const auto& table = hexapod::simulate_option_table();
    SimulateRequest request;
    options->apply(request);
    run_spelled(table, [&] { hexapod::check_simulate_request(request, options->given()); });
    const hexapod::SimulateResult result = run_spelled(table, [&] { return hexapod::run_simulate(request, global.read); });
    for (const Warning& w : result.warnings) warn_spelled(global, w, table);
    emit(hexapod::write_simulation(result, request.out, request.geometry.path), "");
  };
  return {sub, run};
}

}  // namespace spdfit::cli
