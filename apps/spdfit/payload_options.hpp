// The true payload of `experiment physical` when it differs from the geometry's nominal one:
// --payload-mass, --payload-com and --payload-inertia, registered from `hexapod simulate`'s
// option table (hexapod/simulate_request.hpp), which declares them once.
#pragma once

#include <memory>

#include <CLI/CLI.hpp>

#include "spdfit/hexapod/geometry.hpp"
#include "spdfit/hexapod/simulate_request.hpp"
#include "spdfit/rigid_body.hpp"
#include "table_options.hpp"

namespace spdfit::cli {

/// The three options, as registered on a command.
struct PayloadCli {
  std::unique_ptr<TableOptions<hexapod::SimulateRequest>> options;

  /// Whether any of the three was given.
  bool given() const { return options && !options->given().empty(); }
};

/// Adds the three options of the simulate table to `sub`.
void add_payload_options(CLI::App* sub, PayloadCli& payload);

/// The geometry's nominal payload with the options' changes (hexapod::payload_with): a
/// UsageError naming the option for a count or a body that does not fit.
RigidBodyInertia payload_of(const PayloadCli& payload, const hexapod::Geometry& geometry);

}  // namespace spdfit::cli
