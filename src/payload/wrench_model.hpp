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

/// J_a (a < layout.inertial()): the derivative of the model wrench's Jacobian in x = (s, omega,
/// alpha) along parameter a; the Jacobian is sum_a phi_a J_a (linear in phi).
void jacobian_basis(const Kinematics& kin, Eigen::Index k, const ParameterLayout& layout, Matrix69* J);

}  // namespace spdfit::payload::detail
