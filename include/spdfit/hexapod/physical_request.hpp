// The options of physical identification (hexapod/physical.hpp) declared once: the table from
// which `spdfit hexapod identify --physical` registers its options and Python's
// spdfit.hexapod.identify(..., physical=True) binds its keywords.
#pragma once

#include <string_view>
#include <vector>

#include "spdfit/fit_options.hpp"
#include "spdfit/fit_request.hpp"
#include "spdfit/hexapod/physical.hpp"
#include "spdfit/options.hpp"

namespace spdfit::hexapod {

/// The options of PhysicalOptions that front ends offer, in the order help lists them:
/// strut_masses (the command line's --fit-strut-mass, Python's fit_strut_mass), criterion,
/// consistent (Python) and unconstrained (the command line's --unconstrained: consistent false).
/// Not among them: the noise covariances (matrices); and the options the fit's table
/// (fit_option_table) has under the same names, max_iterations, rank_tolerance and the
/// bootstrap's four, which a front end that runs every estimator too takes once for all of its
/// fits (apply_fit_options).
const std::vector<OptionSpec<PhysicalOptions>>& physical_option_table();

/// The options the physical fit shares with the fit's table, copied from `fit` into `options`:
/// the bootstrap's replicates, level, seed and threads, and max_iterations and rank_tolerance
/// when the user gave them (`given`: library names; their defaults differ: 200 Newton steps for
/// the generic iterative methods, 500 for the physical fit's barrier path), and the noise model's
/// covariances (for 6 x 6: NoiseModel::resolved, whose errors it throws) as noise_cov_a and
/// noise_cov_b when `fit` has one, so that the physical fit weighs the data as the estimators do.
void apply_fit_options(const FitOptions& fit, const std::vector<std::string_view>& given,
                       PhysicalOptions& options);

/// The physical fit alone (Python's spdfit.physical.identify): the payload's mass properties from
/// accelerations A and forces B (m x 6) through the geometry's Jacobian.
struct PhysicalRequest {
  MatrixInput a, b;
  GeometryInput geometry;  ///< needed: the Jacobian and the nominal payload
  PhysicalOptions options;
  /// The options the physical fit shares with the fit's table (iterations, rank, bootstrap, noise
  /// covariances), set here by their entries and copied into `options` by run_physical.
  FitRequest fit;
};

/// The options of a PhysicalRequest: a, b, geometry (positional), physical_option_table's, and the
/// fit's that the physical fit shares (max_iterations, rank_tolerance, bootstrap, confidence, seed,
/// threads, noise_cov_a, noise_cov_b).
const std::vector<OptionSpec<PhysicalRequest>>& physical_fit_table();

/// The table's rules among the options given (library names). Throws OptionError.
void check_physical_request(const PhysicalRequest& request, const std::vector<std::string_view>& given);

/// The physical fit the request names (identify_physical): the data (values; files are read),
/// the geometry (read_geometry for a file), the shared options copied (apply_fit_options).
/// Throws as identify_physical does; a numerical failure is the estimate's status.
PhysicalEstimate run_physical(const PhysicalRequest& request);

}  // namespace spdfit::hexapod
