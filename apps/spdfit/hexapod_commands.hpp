// The three subcommands of `spdfit hexapod` (CLI internal): each file registers one, and
// command_hexapod.cpp registers them under `hexapod`.
#pragma once

#include "cli.hpp"

namespace CLI {
class App;
}

namespace spdfit::cli {

/// `hexapod model`: the Jacobian, M_p and the modes of a geometry (command_hexapod_model.cpp).
Command add_hexapod_model(CLI::App& parent, const GlobalOptions& global);
/// `hexapod simulate`: the thesis' data generator (command_hexapod_simulate.cpp).
Command add_hexapod_simulate(CLI::App& parent, const GlobalOptions& global);
/// `hexapod identify`: M_p from A and B with every estimator (command_hexapod_identify.cpp).
Command add_hexapod_identify(CLI::App& parent, const GlobalOptions& global);

}  // namespace spdfit::cli
