// `hexapod identify` as one library workflow: the request (the data, every estimator's options,
// the physical fit's), its option table, from which the command line, Python and MATLAB take their
// options, the rules among them (checked once, here), the run, and its result.
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <Eigen/Core>

#include "spdfit/fit_request.hpp"
#include "spdfit/hexapod/geometry.hpp"
#include "spdfit/hexapod/identify.hpp"
#include "spdfit/hexapod/physical.hpp"
#include "spdfit/options.hpp"
#include "spdfit/output_request.hpp"
#include "spdfit/outcome.hpp"

namespace spdfit::hexapod {

/// Everything `hexapod identify` needs: M_p from accelerations A and base forces B (B ~= A M_p) by
/// every estimator, and with `physical` the payload's mass properties through the geometry.
struct IdentifyRequest {
  MatrixInput a;  ///< the accelerations (m x n), a file or values
  MatrixInput b;  ///< the forces (m x n); empty with fit.a_cols and fit.b_cols (both from a's file)
  /// The options every estimator shares: the noise (ratio or model), the iteration limit, the rank
  /// cut-off, the bootstrap's, the columns of one file, and how files are read (fit.read).
  FitRequest fit;
  std::optional<MatrixInput> truth;  ///< the true M_p (n x n), to report each estimate's error
  /// The strut stiffness, for the modes: one number (every strut), n numbers (a diagonal K) or
  /// the n x n matrix K. Not with a geometry (whose struts' stiffness gives the modes).
  std::optional<MatrixInput> stiffness;
  GeometryInput geometry;  ///< the hexapod's geometry: its stiffness gives the modes
  bool physical = false;   ///< also the physical fit of the payload (needs the geometry)
  PhysicalOptions physical_options;
  OutputRequest output;    ///< the command line's: JSON or the report, and where
};

/// The options of an IdentifyRequest, in the order help lists them: the data (positional a, b),
/// truth, geometry, stiffness, physical, the physical fit's (physical_option_table), and the fit's
/// that every estimator shares (fit_option_table: noise, iterations, rank, columns, bootstrap), and
/// the command line's json and output.
const std::vector<OptionSpec<IdentifyRequest>>& identify_option_table();

/// Checks the options given (`given`: library names) against the table's rules and the request's
/// own: the physical fit's options need `physical`, `physical` needs `geometry`, `geometry` and
/// `stiffness` exclude each other, B is needed unless `a_cols` and `b_cols` choose both from A's
/// file. Throws OptionError (Tier::Usage).
void check_identify_request(const IdentifyRequest& request, const std::vector<std::string_view>& given);

/// What `hexapod identify` found: every estimator's identification, the physical estimate (with
/// `physical`), and every warning in the order a front end shows them (the readers', each
/// estimator's prefixed with its method's name, the physical fit's prefixed with "physical: ").
struct Identification {
  std::vector<MethodIdentification> methods;
  IdentifyOptions options;  ///< the truth, stiffness and fit options the estimators ran with
  std::optional<PhysicalEstimate> physical;
  std::optional<Geometry> geometry;  ///< the geometry given
  std::vector<Warning> warnings;
  /// A and B from one file (a_cols, b_cols): which columns each came from; empty otherwise.
  std::string a_columns, b_columns;

  /// A numerical failure of the fit asked for (the physical fit's): its problem, thrown by front
  /// ends after they print the result (the command line exits 1); nothing when it succeeded.
  std::optional<Problem> failure() const;
};

/// Runs the request: reads A and B (files, or the values given), checks their sizes against each
/// other, the truth, the stiffness and the geometry (io::DataError naming a file, InputError
/// naming the option otherwise), resolves the noise model for n columns, runs every estimator
/// (identify) and with `physical` the physical fit (identify_physical) with the fit's shared
/// options copied (apply_fit_options). A physical fit that fails numerically is the result's
/// failure(), not an exception. Cost: identify's and identify_physical's.
Identification run_identify(const IdentifyRequest& request);

/// The result as `spdfit hexapod identify --json` prints it (to_json(methods, options[, physical])).
std::string to_json(const Identification& identification);
/// The result as `spdfit hexapod identify` prints it (report(methods, options[, physical, geometry])).
std::string report(const Identification& identification);

}  // namespace spdfit::hexapod
