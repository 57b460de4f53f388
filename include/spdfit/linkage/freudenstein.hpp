// The Freudenstein equation of a planar 4R four-bar function generator and its parameters
// (lecture notes shared/seeds/002_fe976fdf53be9def.txt, section 3.3.3, eq. 3.3-3.4).
#pragma once

#include <optional>
#include <string>

#include <Eigen/Core>

namespace spdfit::linkage {

/// Link lengths of a planar 4R four-bar (notes 002, figure 3.18): a1 the ground link from the
/// input pivot to the output pivot, a2 the input link (angle psi), a3 the coupler, a4 the
/// output link (angle phi). Both angles are measured counter-clockwise from the ground line.
struct FourBar {
  double a1 = 1.0, a2 = 1.0, a3 = 1.0, a4 = 1.0;
};

/// The Freudenstein parameters k = [k1, k2, k3] of a four-bar (eq. 3.4):
/// k1 = (a1^2 + a2^2 + a4^2 - a3^2) / (2 a2 a4), k2 = a1 / a2, k3 = a1 / a4.
/// Preconditions: positive, finite lengths (else std::invalid_argument). Cost: O(1).
Eigen::Vector3d freudenstein_parameters(const FourBar& bar);

/// The link lengths of k, scaled to a1 = 1 (eq. 3.4): a2 = 1/k2, a4 = 1/k3,
/// a3 = (1 + a2^2 + a4^2 - 2 a2 a4 k1)^(1/2). Nothing when no real linkage has these
/// parameters: k2 <= 0 or k3 <= 0 (a negative or infinite length) or a3^2 <= 0; `problem`
/// then says which, in words a designer can act on. Cost: O(1).
std::optional<FourBar> link_lengths(const Eigen::Vector3d& k, std::string* problem = nullptr);

/// The left side minus the right side of the Freudenstein equation (eq. 3.3):
/// f = k1 + k2 cos(phi) - k3 cos(psi) - cos(psi - phi). Angles in radians.
double freudenstein_residual(const Eigen::Vector3d& k, double psi, double phi);

/// The synthesis matrix S (m x 3) with rows [1, cos(phi_i), -cos(psi_i)] and the right side
/// b (m) with b_i = cos(psi_i - phi_i) (eq. 3.8-3.9), so that the design error is d = b - S k.
/// Preconditions: psi and phi of equal length (else std::invalid_argument).
Eigen::MatrixXd synthesis_matrix(const Eigen::Ref<const Eigen::VectorXd>& psi,
                                 const Eigen::Ref<const Eigen::VectorXd>& phi);
Eigen::VectorXd synthesis_rhs(const Eigen::Ref<const Eigen::VectorXd>& psi, const Eigen::Ref<const Eigen::VectorXd>& phi);

/// The output angle phi of the linkage with parameters k at input angle psi on assembly branch
/// `branch` (+1 or -1). Eq. 3.3 is (k2 - cos psi) cos phi - sin psi sin phi + (k1 - k3 cos psi)
/// = 0, i.e. R cos(phi - theta) = -c with theta = atan2(-sin psi, k2 - cos psi), so
/// phi = theta + branch * arccos(-c / R), returned in [-pi, pi]. The two branches are the two ways
/// of closing the triangle of the coupler and the output link over the diagonal from the crank
/// tip to the output pivot (mirror images in that diagonal); they meet at the dead points
/// (|c| = R), where the output link and the coupler are in line. Nothing when the linkage cannot
/// be assembled at psi (|c| > R). Cost: O(1).
std::optional<double> output_angle(const Eigen::Vector3d& k, double psi, int branch);

/// df/dphi = -k2 sin(phi) - sin(psi - phi): the diagonal entries of D (notes section 3.6.1).
/// Zero exactly at a dead point of the input (output link and coupler in line).
double freudenstein_dphi(const Eigen::Vector3d& k, double psi, double phi);

/// df/dpsi = k3 sin(psi) + sin(psi - phi), so that dphi/dpsi = -(df/dpsi) / (df/dphi).
double freudenstein_dpsi(const Eigen::Vector3d& k, double psi, double phi);

/// x - 2 pi round(x / 2 pi): an angle difference in [-pi, pi].
double wrap_angle(double x);

}  // namespace spdfit::linkage
