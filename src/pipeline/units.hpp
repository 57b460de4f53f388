// Internal: FitOptions::scale_a and scale_b, the units the data are fitted in, applied the same
// way to rows in memory, to a streamed factor and to the bootstrap's resampled factors.
#pragma once

#include <Eigen/Core>
#include <optional>

#include "spdfit/fit_options.hpp"
#include "spdfit/triangular_factor.hpp"

namespace spdfit::detail {

/// The factors of A's n columns and B's d columns.
struct Units {
  Eigen::VectorXd a, b;
};

/// FitOptions::scale_a and scale_b for data with n and d columns, or nothing when neither is
/// given. OptionError (Code::OptionValue, naming `scale_a` or `scale_b`) for a count other than 1
/// or the columns', or a factor that is not a finite number > 0.
std::optional<Units> units_of(const FitOptions& options, Eigen::Index n, Eigen::Index d);

/// The options for the data in those units: the noise model (in the data's units as given)
/// resolved to n and d and scaled with them (NoiseModel::scaled), scale_a and scale_b cleared.
FitOptions options_in_units(const FitOptions& options, const Units& units);

/// A and B multiplied column by column, in place.
void apply_units(const Units& units, Eigen::Ref<Eigen::MatrixXd> A, Eigen::Ref<Eigen::MatrixXd> B);

/// The factor of [A D_a, B D_b] from that of [A B]: R diag(D_a, D_b), as exact as the products.
TriangularFactor factor_in_units(const TriangularFactor& factor, const Units& units);

}  // namespace spdfit::detail
