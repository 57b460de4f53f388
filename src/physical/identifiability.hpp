// Internal: the identifiability of a linear model's parameters from its regressor (or the
// triangular factor of it: the same column norms, rank-revealing pivots, singular values and null
// space), physical/identifiability.hpp's Identifiability.
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>

#include "spdfit/physical/identifiability.hpp"

namespace spdfit::physical::detail {

/// Identifiability of the parameters named `names` (one per column of R) from R (q x p, q >= p
/// after a QR; the data's rows otherwise), with the numerical rank cut-off `cutoff` relative to
/// the largest singular value of R with unit-norm columns. Cost O(q p^2 + p^3).
Identifiability identifiability(const Eigen::MatrixXd& R, const std::vector<std::string>& names, double cutoff);

/// A combination of named parameters in words: "m c_x - 0.5 b_tau_y", the largest coefficient
/// made 1 (the others to 4 significant digits; those below 1e-6 of the largest left out).
std::string combination_text(const Eigen::VectorXd& coefficients, const std::vector<std::string>& names);

}  // namespace spdfit::physical::detail
