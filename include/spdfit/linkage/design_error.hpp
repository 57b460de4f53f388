// Approximate synthesis of a function generator by minimizing the design error (notes 002,
// section 3.4).
#pragma once

#include <Eigen/Core>

namespace spdfit::linkage {

/// The Freudenstein parameters that minimize the weighted design error, with the evidence.
struct DesignErrorSolution {
  Eigen::Vector3d k = Eigen::Vector3d::Zero();
  double design_error_norm = 0.0;  ///< (d^T W d)^(1/2), d = b - S k (eq. 3.8, 3.10)
  Eigen::Index rank = 0;           ///< numerical rank of W^(1/2) S (cut-off as in notes 3.8)
  double condition_number = 0.0;   ///< sigma_max / sigma_min of W^(1/2) S; +inf when singular
  /// The same for W^(1/2) S with its columns scaled to unit norm: the rank is decided on it.
  double scaled_condition_number = 0.0;
  bool used_svd = false;           ///< rank-deficient: the edited-SVD minimum-norm k (eq. 3.21)
};

/// Minimizes z = 1/2 d^T W d over k, d = b - S k (eq. 3.8-3.10), for prescribed angles psi, phi
/// (radians; psi_i, phi_i already include the dial zeros) and diagonal weights w (empty: W = I).
/// Solved as min ||W^(1/2) (S k - b)|| by the Householder QR of W^(1/2) S, never through the
/// normal equations S^T W S (which square the condition number, notes 3.4 and 3.6.2); when
/// W^(1/2) S is rank-deficient under the cut-off `rank_tolerance` (relative; negative: max(m, 3) eps)
/// k is the minimum-norm solution of the edited SVD. With exactly 3 positions and a
/// nonsingular S this is the precision-point synthesis of section 3.3.3: d = 0.
///
/// Preconditions: equal lengths >= 3, finite angles, weights empty or positive finite of the same
/// length (else std::invalid_argument). Cost: O(m) (S has 3 columns).
DesignErrorSolution design_error_synthesis(const Eigen::Ref<const Eigen::VectorXd>& psi,
                                           const Eigen::Ref<const Eigen::VectorXd>& phi,
                                           const Eigen::Ref<const Eigen::VectorXd>& weights, double rank_tolerance = -1.0);

}  // namespace spdfit::linkage
