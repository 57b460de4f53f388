// Least squares for the few-column problems of linkage synthesis (internal).
#pragma once

#include <Eigen/Core>

namespace spdfit::linkage::detail {

/// The solution of min ||M x - rhs||_2 with its evidence.
struct SmallLeastSquares {
  Eigen::VectorXd x;
  Eigen::Index rank = 0;
  double condition_number = 0.0;         ///< sigma_max / sigma_min of M; +inf when singular
  double scaled_condition_number = 0.0;  ///< the same for M with unit-norm columns (decides the rank)
  bool used_svd = false;                 ///< rank-deficient: the edited SVD's minimum-norm x
};

/// The least-squares solution of M x ~= rhs by the one least-squares core
/// (spdfit::detail::equilibrated_least_squares): the rank decided on M with its columns scaled to
/// unit norm (sigma_i <= threshold * sigma_max counts as zero; negative threshold: max(m, n) eps,
/// notes 3.8); at full rank the solution refined with accurate residuals, else the minimum-norm
/// solution of the edited SVD (eq. 3.21). M has few columns (3 or 5): the cost is O(m n^2).
SmallLeastSquares small_least_squares(const Eigen::Ref<const Eigen::MatrixXd>& M,
                                      const Eigen::Ref<const Eigen::VectorXd>& rhs, double threshold);

}  // namespace spdfit::linkage::detail
