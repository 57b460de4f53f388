// The true payload of a simulation when it differs from the geometry's nominal one:
// --payload-mass, --payload-com and --payload-inertia, shared by `hexapod simulate` and
// `experiment physical`.
#pragma once

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>
#include <string>

#include "spdfit/hexapod/geometry.hpp"
#include "spdfit/rigid_body.hpp"

namespace spdfit::cli {

/// The options as given.
struct PayloadCli {
  std::string mass, com, inertia;
  CLI::Option *mass_option = nullptr, *com_option = nullptr, *inertia_option = nullptr;

  /// Whether any of the three was given.
  bool given() const { return mass_option->count() + com_option->count() + inertia_option->count() > 0; }
};

/// Adds the three options to `sub`, each help text starting with `whose` ("With --geometry: the
/// true payload's").
void add_payload_options(CLI::App* sub, PayloadCli& payload, const std::string& whose);

/// The geometry's nominal payload (hexapod::nominal_payload) with the options' changes: the mass,
/// the centre of mass x,y,z, the inertia about it as 3 numbers (the diagonal), 6 (ixx, ixy, ixz,
/// iyy, iyz, izz: URDF's order) or 9 (row by row). A UsageError naming the option for a count
/// or a text that is not numbers, and for a payload that is not well formed (is_well_formed).
RigidBodyInertia payload_of(const PayloadCli& payload, const hexapod::Geometry& geometry);

/// {"mass", "center_of_mass" [3], "inertia" [3x3]}.
nlohmann::json payload_json(const RigidBodyInertia& body);

}  // namespace spdfit::cli
