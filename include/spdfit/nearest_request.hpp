// One request for a covariance or correlation repair (the `nearest` command, Python's
// nearest_spd and nearest_correlation, MATLAB's spdfit.nearest), with the table of its options.
#pragma once

#include <Eigen/Core>
#include <optional>
#include <string_view>
#include <vector>

#include "spdfit/nearest_correlation.hpp"
#include "spdfit/nearest_spd.hpp"
#include "spdfit/options.hpp"

namespace spdfit {

/// What a repair needs besides the matrix: which repair, and its options.
struct NearestRequest {
  /// The nearest correlation matrix (unit diagonal; nearest_correlation).
  bool corr = false;
  /// Keep the input's diagonal (nearest_keep_diagonal); with corr the diagonal is the unit one.
  bool keep_diag = false;
  /// statsmodels' cov_nearest route: to a correlation, repaired, scaled back (nearest_via_correlation).
  bool via_corr = false;
  /// The floor: absolute, relative to the largest eigenvalue, or NAG's alpha (a unit diagonal's
  /// floor); none given: the relative EigenvalueFloor::kRepairDefault (EigenvalueFloor::chosen).
  std::optional<double> min_eig, min_eig_rel, alpha;
  /// The Newton methods' weights, iteration limit and tolerance (NearestCorrelationOptions).
  Eigen::VectorXd weights;
  int max_iterations = NearestCorrelationOptions{}.max_iterations;
  double tolerance = NearestCorrelationOptions{}.tolerance;

  /// Whether the repair fixes a diagonal (corr, keep_diag or via_corr): Qi and Sun's Newton method.
  bool newton() const { return corr || keep_diag || via_corr; }
  /// The floor the options give (EigenvalueFloor::chosen).
  EigenvalueFloor floor() const;
  /// The Newton methods' options.
  NearestCorrelationOptions correlation_options() const;
};

/// The options of a NearestRequest, in the order help lists them: corr, keep_diag, via_corr,
/// min_eig, min_eig_rel, alpha, weights, max_iterations, tolerance.
const std::vector<OptionSpec<NearestRequest>>& nearest_option_table();

/// Checks the options a user gave (library names) against the table's rules (weights, max_iterations
/// and tolerance need a Newton repair, alpha a unit diagonal, the floors exclude each other).
/// Throws OptionError; its list of what an option needs leaves out the options in `unavailable`
/// (those a front-end function cannot take).
void check_nearest_request(const std::vector<std::string_view>& given,
                           const std::vector<std::string_view>& unavailable = {});

/// The repair the request names: nearest_correlation, nearest_keep_diagonal,
/// nearest_via_correlation or nearest_spd. Throws std::invalid_argument on bad input, as they do.
NearestResult nearest(const Eigen::Ref<const Eigen::MatrixXd>& C, const NearestRequest& request);

}  // namespace spdfit
