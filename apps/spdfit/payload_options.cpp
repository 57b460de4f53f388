// --payload-mass, --payload-com and --payload-inertia from the simulate table.
#include "payload_options.hpp"

#include <string_view>
#include <vector>

#include "cli.hpp"

namespace spdfit::cli {

void add_payload_options(CLI::App* sub, PayloadCli& payload) {
  std::vector<std::string_view> others;
  for (const auto& spec : hexapod::simulate_option_table()) {
    if (spec.name != "payload_mass" && spec.name != "payload_com" && spec.name != "payload_inertia") {
      others.push_back(spec.name);
    }
  }
  payload.options =
      std::make_unique<TableOptions<hexapod::SimulateRequest>>(*sub, hexapod::simulate_option_table(), others);
}

RigidBodyInertia payload_of(const PayloadCli& payload, const hexapod::Geometry& geometry) {
  hexapod::SimulateRequest request;
  payload.options->apply(request);
  return run_spelled(hexapod::simulate_option_table(), [&] { return hexapod::payload_with(geometry, request.payload); });
}

}  // namespace spdfit::cli
