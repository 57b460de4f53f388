// What a user should know about a simulation's settings before fitting its data.
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>

#include "spdfit/hexapod/simulate.hpp"
#include "spdfit/outcome.hpp"

namespace spdfit::hexapod {

/// The warnings for data simulated with `options` for `truth` (n x n): fewer samples than n, which
/// the estimators need at least ("fewer samples (2) than M_p has columns (6): the estimators need
/// m >= n"). Empty when nothing. `spdfit hexapod simulate` and Python's spdfit.hexapod.simulate
/// show these as warnings.
std::vector<Warning> simulation_warnings(const Eigen::MatrixXd& truth, const SimulationOptions& options);

}  // namespace spdfit::hexapod
