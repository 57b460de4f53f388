// Internal: a rank-one downdate of a triangular factor (implemented in linalg.cpp).
#pragma once

#include <Eigen/Core>

namespace spdfit::detail {

/// The upper triangular Rc with Rc^T Rc = R^T R - x x^T (R upper triangular, k x k: its upper
/// triangle is read), by the plane rotations of LINPACK's dchdd (Golub and Van Loan, "Matrix
/// Computations", 4th ed., section 6.5.4): O(k^2), no Gram matrix formed. False (Rc unspecified)
/// when R is singular or R^T R - x x^T is not positive definite (||R^-T x|| >= 1). Digits are
/// lost as ||R^-T x|| nears 1: the callers check the columns' norms.
bool cholesky_downdate(const Eigen::Ref<const Eigen::MatrixXd>& R, const Eigen::Ref<const Eigen::VectorXd>& x,
                       Eigen::MatrixXd& Rc);

}  // namespace spdfit::detail
