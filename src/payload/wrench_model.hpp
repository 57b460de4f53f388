// Internal: the wrench model of payload/identify.hpp row by row: the regressor of a sample (the
// readings as a linear function of the parameters phi = (m, h, [I_S], b_f, b_tau)) and the
// derivatives of the model wrench in the pose signals x = (s, omega, alpha) that the
// errors-in-variables criterion weighs the noise with.
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>

#include "payload/kinematics.hpp"

namespace spdfit::payload::detail {

using Matrix69 = Eigen::Matrix<double, 6, 9>;

/// The parameters: m, h (3), then for moving poses the inertia about S's origin in URDF order (6),
/// then the force and torque biases (3 + 3).
struct ParameterLayout {
  bool moving = false;
  int inertial() const { return moving ? 10 : 4; }
  int size() const { return inertial() + 6; }
  std::vector<std::string> names() const;
};

/// The 6 x p regressor of sample k: w_k = X phi + noise (the sign of the readings applied to the
/// inertial columns; the identity on the biases').
void sample_regressor(const Kinematics& kin, Eigen::Index k, const ParameterLayout& layout,
                      Eigen::Ref<Eigen::MatrixXd> X);
/// The same into a matrix of fixed size: P = layout.size() (10 static, 16 moving).
template <int P>
void sample_regressor(const Kinematics& kin, Eigen::Index k, const ParameterLayout& layout,
                      Eigen::Matrix<double, 6, P>& X);

/// The model wrench's Jacobian in x = (s, omega, alpha) at sample k and parameters phi (only the
/// inertial ones are read): J(phi) = sum_a phi_a J_a, linear in phi, assembled from m, h and I.
Matrix69 model_jacobian(const Kinematics& kin, Eigen::Index k, const ParameterLayout& layout,
                        const Eigen::Ref<const Eigen::VectorXd>& phi);

/// The products of a wrench-space u (6) and a signal-space v (9) with each J_a = dJ/dphi_a
/// (a < layout.inertial()): column a of `Jt_u` is J_a^T u, of `J_v` J_a v (the columns from
/// layout.inertial() on are left as they are). Formed from u, v and the sample's omega without
/// the J_a themselves.
void jacobian_products(const Kinematics& kin, Eigen::Index k, const ParameterLayout& layout,
                       const Eigen::Matrix<double, 6, 1>& u, const Eigen::Matrix<double, 9, 1>& v,
                       Eigen::Matrix<double, 9, 10>& Jt_u, Eigen::Matrix<double, 6, 10>& J_v);

}  // namespace spdfit::payload::detail
