// The area criterion of Chen & McInroy, evaluated for a given estimate.
#pragma once

#include <Eigen/Core>
#include <optional>

#include "spdfit/reduction.hpp"

namespace spdfit {

/// The area criterion f(Y) = ||A Y - B Y^-T||_F^2 for X = Y Y^T symmetric positive definite
/// (Chen & McInroy, Definition II.1, eq. 2), evaluated from the data as
/// ||R11 Y - R12 Y^-T||_F^2 + ||R22 Y^-T||_F^2. For X positive semidefinite of rank r < n it is
/// the criterion of Corollary III.7, tr(P X + X^+ Q) - 2 tr(A^T B).
///
/// `X` is in the data's units. Returns nothing when X is not symmetric positive semidefinite
/// (to within n eps ||X||). Cost O(n^3) from a Reduction, O(m n^2) from the data.
std::optional<double> area_criterion(const Reduction& data, const Eigen::Ref<const Eigen::MatrixXd>& X);
std::optional<double> area_criterion(const Eigen::Ref<const Eigen::MatrixXd>& A,
                                     const Eigen::Ref<const Eigen::MatrixXd>& B,
                                     const Eigen::Ref<const Eigen::MatrixXd>& X);

}  // namespace spdfit
