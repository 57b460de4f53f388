// What the repairs (nearest_spd, nearest_correlation and its fixed-diagonal variants) share: the
// checks of their input and floor, and their warnings.
#pragma once

#include "spdfit/outcome.hpp"

#include <Eigen/Core>
#include <optional>
#include <string>

#include "spdfit/nearest_spd.hpp"

namespace spdfit::detail {

/// Why a matrix to repair has NaN or Inf, as its message ends (check_repair_input, run_nearest).
inline constexpr const char* kNonfiniteCause =
    ": a pair of variables never observed together (pandas' corr() and cov() give NaN there)? Every entry needs a value";

/// Throws std::invalid_argument unless C is square, non-empty and finite and the floor is valid.
/// The repairs' messages name options (`min_eig`, `min_eig_rel`, in backticks for the front ends
/// to spell), never the library's functions.
void check_repair_input(const Eigen::Ref<const Eigen::MatrixXd>& C, EigenvalueFloor floor);

/// A warning when C is not symmetric to rounding (more often a wrong file than noise).
std::optional<Warning> asymmetry_warning(const Eigen::Ref<const Eigen::MatrixXd>& C);

/// A floor resolved to an absolute one: a relative floor times the largest eigenvalue
/// `lambda_max` of the input's symmetric part. Throws std::invalid_argument when a relative floor
/// meets lambda_max <= 0 (nothing to be relative to).
double resolve_floor(EigenvalueFloor floor, double lambda_max);

/// The option a floor came from, in backticks: `min_eig_rel` for a relative one, else `min_eig`.
const char* floor_option(EigenvalueFloor floor);

/// Throws std::invalid_argument when a variance (diagonal entry) is negative, or zero where
/// `zero_allowed` is false, listing every such entry (1-based, with its value) and naming
/// `min_diag`, the option that raises them; `why` says what needs them positive.
void check_variances(const Eigen::VectorXd& d, bool zero_allowed, const char* why);

/// A warning when the diagonal of the symmetric S is not 1 to 1e-6 (a covariance given for a
/// correlation: it is repaired to one all the same).
std::optional<Warning> unit_diagonal_warning(const Eigen::Ref<const Eigen::MatrixXd>& S);

/// Whether the floor's own change of the matrix (`floor_change`, in the distance's norm) calls for a
/// warning: more than the repair itself (`repair`) and more than rounding of `scale` (the input's
/// norm). The warning then names the floor and the largest eigenvalue of the matrix it applies to
/// (`of_correlation`: the correlation matrix D^-1/2 X D^-1/2 of a diagonal-keeping repair).
std::optional<Warning> floor_warning(double floor, double floor_change, double repair, double scale,
                                         double lambda_max, bool of_correlation = false);

}  // namespace spdfit::detail
