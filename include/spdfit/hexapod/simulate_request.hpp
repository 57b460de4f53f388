// `spdfit hexapod simulate`: the request (the generator's options, the truth, a payload that differs
// from the geometry's), its option table, the workflow and what it writes, so that the command
// line and Python's spdfit.hexapod.simulate simulate the same data.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <Eigen/Core>

#include "spdfit/hexapod/geometry.hpp"
#include "spdfit/hexapod/simulate.hpp"
#include "spdfit/io.hpp"
#include "spdfit/options.hpp"
#include "spdfit/outcome.hpp"
#include "spdfit/rigid_body.hpp"

namespace spdfit::hexapod {

/// Changes to a geometry's nominal payload: the true payload of a simulation that differs from it.
struct PayloadChange {
  std::optional<double> mass;          ///< kg
  std::vector<double> center_of_mass;  ///< x, y, z ({P}'s axes, from the nominal centre of mass); empty: 0
  std::vector<double> inertia;         ///< about the centre of mass: 3 (diagonal), 6 (URDF's order) or 9 numbers
  bool given() const { return mass || !center_of_mass.empty() || !inertia.empty(); }
};

/// The geometry's nominal payload (nominal_payload) with `change` applied. OptionError naming the
/// option (`payload_mass`, `payload_com`, `payload_inertia`) for a count of numbers that does not
/// fit, or a change after which the payload is not a body (is_well_formed).
RigidBodyInertia payload_with(const Geometry& geometry, const PayloadChange& change);

/// {"mass", "center_of_mass" [3], "inertia" [3 x 3]} as JSON text (one line).
std::string payload_json(const RigidBodyInertia& body);

/// What `hexapod simulate` draws.
struct SimulateRequest {
  SimulationOptions options;  ///< samples, noise, signal, distribution, rest rows, scale of B, preload
  bool noise_given = false;   ///< `noise_var` or `noise_std_a` given (the command line requires one)
  MatrixInput truth;          ///< the true M_p: none or "thesis" (eq. 6.1), a matrix or its file
  GeometryInput geometry;     ///< or the M_p of a geometry (with `payload`'s changes)
  PayloadChange payload;
  std::vector<double> preload;  ///< a static load in every row of B: one value or one per strut
  std::uint64_t seed = 1;
  std::string out;  ///< the directory the command line writes to
};

/// The options of `hexapod simulate` (and of Python's spdfit.hexapod.simulate).
const std::vector<OptionSpec<SimulateRequest>>& simulate_option_table();

/// The rules of the table (check_option_combination) and the noise, which the command line
/// requires (`noise_var`, or `noise_std_a` and `noise_std_b`): OptionError.
void check_simulate_request(const SimulateRequest& request, const std::vector<std::string_view>& given);

/// Simulated measurements with what they were drawn from.
struct SimulateResult {
  Measurements data;
  Eigen::MatrixXd truth;             ///< M_p (before the scale of B)
  std::string truth_source;          ///< "thesis eq. 6.1", "geometry G.json", the matrix's file, ...
  std::optional<RigidBodyInertia> payload;  ///< the changed payload, when one was given
  SimulationOptions options;         ///< as drawn (the preload in rest_force)
  std::uint64_t seed = 1;
  std::vector<Warning> warnings;
};

/// The workflow of `hexapod simulate`: the truth resolved (a matrix file read with `read`; a file
/// that is not a square matrix is an io::DataError), the options checked, the data drawn (trial 0
/// of `experiment thesis` with the same seed and settings).
SimulateResult run_simulate(const SimulateRequest& request, const io::ReadOptions& read = {});

/// simulation.json: the settings the data were drawn with and the files' names.
std::string simulation_json(const SimulateResult& result);

/// Writes A.csv, B.csv, truth.csv (M_p times the scale of B: the true X of the files), the rest
/// rows when drawn, and simulation.json into `directory` (created); returns what was written, for
/// people, with the command that identifies M_p from them. io::DataError naming the directory.
std::string write_simulation(const SimulateResult& result, const std::string& directory,
                             const std::string& geometry_path = {});

}  // namespace spdfit::hexapod
