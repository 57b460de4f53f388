#include "spdfit/linkage/design_error.hpp"

#include <stdexcept>

#include "spdfit/linkage/freudenstein.hpp"
#include "linkage_inputs.hpp"
#include "small_least_squares.hpp"

namespace spdfit::linkage {

using Eigen::VectorXd;

DesignErrorSolution design_error_synthesis(const Eigen::Ref<const VectorXd>& psi, const Eigen::Ref<const VectorXd>& phi,
                                           const Eigen::Ref<const VectorXd>& weights, double threshold) {
  detail::check_positions(psi, phi, weights, 3, "design_error_synthesis");
  const VectorXd root_w = detail::root_weights(weights, psi.size());
  // min 1/2 d^T W d = min 1/2 ||W^(1/2) (b - S k)||^2 (eq. 3.10), by QR of W^(1/2) S.
  const Eigen::MatrixXd Sw = root_w.asDiagonal() * synthesis_matrix(psi, phi);
  const VectorXd bw = root_w.asDiagonal() * synthesis_rhs(psi, phi);
  const detail::SmallLeastSquares ls = detail::small_least_squares(Sw, bw, threshold);
  DesignErrorSolution out;
  out.k = ls.x;
  out.design_error_norm = (bw - Sw * out.k).norm();
  out.rank = ls.rank;
  out.condition_number = ls.condition_number;
  out.scaled_condition_number = ls.scaled_condition_number;
  out.used_svd = ls.used_svd;
  return out;
}

}  // namespace spdfit::linkage
