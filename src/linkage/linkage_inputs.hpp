// Checks of the prescribed positions shared by the synthesis functions (internal).
#pragma once

#include <cmath>
#include <stdexcept>
#include <string>

#include <Eigen/Core>

namespace spdfit::linkage::detail {

/// Throws std::invalid_argument unless psi and phi have equal length >= min_positions with finite
/// entries and the weights are empty or as many positive finite numbers.
inline void check_positions(const Eigen::Ref<const Eigen::VectorXd>& psi, const Eigen::Ref<const Eigen::VectorXd>& phi,
                            const Eigen::Ref<const Eigen::VectorXd>& weights, Eigen::Index min_positions,
                            const std::string& who) {
  if (psi.size() != phi.size()) {
    throw std::invalid_argument(who + ": " + std::to_string(psi.size()) + " input angles but " +
                                std::to_string(phi.size()) + " output angles");
  }
  if (psi.size() < min_positions) {
    throw std::invalid_argument(who + ": " + std::to_string(psi.size()) + " input-output pair(s) given; at least " +
                                std::to_string(min_positions) + " are needed (" + std::to_string(min_positions) +
                                " for exact precision-point synthesis)");
  }
  if (!psi.allFinite() || !phi.allFinite()) throw std::invalid_argument(who + ": an angle is NaN or infinite");
  if (weights.size() != 0) {
    if (weights.size() != psi.size()) {
      throw std::invalid_argument(who + ": " + std::to_string(weights.size()) + " weights for " +
                                  std::to_string(psi.size()) + " pairs");
    }
    for (Eigen::Index i = 0; i < weights.size(); ++i) {
      if (!(weights(i) > 0.0) || !std::isfinite(weights(i))) {
        throw std::invalid_argument(who + ": weight " + std::to_string(i + 1) + " is not a positive finite number");
      }
    }
  }
}

/// W^(1/2) as a vector: the square roots of the weights, or ones when there are none.
inline Eigen::VectorXd root_weights(const Eigen::Ref<const Eigen::VectorXd>& weights, Eigen::Index m) {
  if (weights.size() == 0) return Eigen::VectorXd::Ones(m);
  return weights.cwiseSqrt();
}

}  // namespace spdfit::linkage::detail
