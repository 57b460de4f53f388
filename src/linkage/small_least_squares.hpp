// Least squares for the few-column problems of linkage synthesis (internal).
#pragma once

#include <Eigen/Core>

namespace spdfit::linkage::detail {

/// The solution of min ||M x - rhs||_2 with its evidence.
struct SmallLeastSquares {
  Eigen::VectorXd x;
  Eigen::Index rank = 0;
  double condition_number = 0.0;  ///< sigma_max / sigma_min of M; +inf when singular
  bool used_svd = false;
};

/// Householder QR of M (notes 002 section 3.4: "k = S \ b") when M has full column rank under the
/// cut-off (sigma_i < threshold * sigma_max counts as zero; negative threshold: max(m, n) eps,
/// notes 3.8); otherwise the minimum-norm solution of the edited SVD (eq. 3.21). The singular
/// values come from the n x n triangular factor, which has those of M. M has few columns (3 or 5),
/// so the cost is O(m n^2).
SmallLeastSquares small_least_squares(const Eigen::Ref<const Eigen::MatrixXd>& M,
                                      const Eigen::Ref<const Eigen::VectorXd>& rhs, double threshold);

}  // namespace spdfit::linkage::detail
