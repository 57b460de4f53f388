// Fitting the dial zeros alpha, beta together with k (notes 002 eq. 3.6-3.7), internal.
#pragma once

#include <optional>
#include <string>

#include <Eigen/Core>

#include "spdfit/linkage/prescribed_function.hpp"
#include "gauss_newton.hpp"

namespace spdfit::linkage::detail {

/// Parameters and dial zeros: a point of the 5-unknown problem.
struct DialZeroPoint {
  Eigen::Vector3d k = Eigen::Vector3d::Zero();
  DialZeros zeros;
};

/// The start of the dial-zero fit: every (alpha, beta) on a 5-degree grid, each with its
/// design-error k (design_error_synthesis at psi = alpha + delta_psi, phi = beta + delta_phi);
/// among those that give a real linkage assemblable at every input, the one with the smallest
/// weighted structural error on its nearest branch, preferring linkages without a dead point in
/// the swept input range. Nothing when no grid point gives a real, assemblable linkage.
std::optional<DialZeroPoint> dial_zero_grid_start(const Eigen::VectorXd& delta_psi, const Eigen::VectorXd& delta_phi,
                                                  const Eigen::VectorXd& weights, double threshold);

/// The 5-unknown outcome.
struct DialZeroFit {
  DialZeroPoint point;
  GaussNewtonOutcome gauss_newton;
};

/// Minimizes the weighted design error of eq. 3.7 over (k, alpha, beta) by Gauss-Newton: the
/// residual is W^(1/2) f with f = k1 + k2 cos(phi) - k3 cos(psi) - cos(psi - phi) and the Jacobian
/// W^(1/2) [S, df/dpsi, df/dphi] (psi = alpha + delta_psi, phi = beta + delta_phi).
DialZeroFit fit_design_dial_zeros(const Eigen::VectorXd& delta_psi, const Eigen::VectorXd& delta_phi,
                                  const Eigen::VectorXd& weights, const DialZeroPoint& start,
                                  const GaussNewtonSettings& settings);

/// Minimizes the weighted structural error over (k, alpha, beta) on `branch` by Gauss-Newton: the
/// residual is W^(1/2) s, s_i = beta + delta_phi_i - phi_gen(alpha + delta_psi_i), with the
/// Jacobian W^(1/2) [D^-1 S, (df/dpsi) / (df/dphi), 1] (eq. 3.16 extended by ds/dalpha =
/// -dphi_gen/dpsi and ds/dbeta = 1). Steps that leave the linkage unreal or unassemblable are
/// halved. Preconditions: start real and assemblable on branch.
DialZeroFit fit_structural_dial_zeros(const Eigen::VectorXd& delta_psi, const Eigen::VectorXd& delta_phi,
                                      const Eigen::VectorXd& weights, const DialZeroPoint& start, int branch,
                                      const GaussNewtonSettings& settings);

/// The weighted structural error ||W^(1/2) s||^2 of a point on its nearest branch, with the branch;
/// nothing when it is not a real linkage assemblable at every input.
std::optional<std::pair<double, int>> structural_objective(const Eigen::VectorXd& delta_psi,
                                                           const Eigen::VectorXd& delta_phi,
                                                           const Eigen::VectorXd& weights, const DialZeroPoint& point);

}  // namespace spdfit::linkage::detail
