// A rigid body's mass properties (mass, centre of mass, inertia) and the pseudo-inertia matrix
// whose positive semidefiniteness says that a body with them can exist.
#pragma once

#include <Eigen/Core>
#include <string>

namespace spdfit {

/// A rigid body's mass properties in SI units, in some body-fixed frame {F}: its mass (kg), its
/// centre of mass c (m, in {F}), and its inertia tensor I_c about the centre of mass, in {F}'s
/// axes (kg m^2). A URDF <inertial> element and a CAD tool's mass report hold the same numbers.
struct RigidBodyInertia {
  double mass = 0.0;
  Eigen::Vector3d center_of_mass = Eigen::Vector3d::Zero();
  Eigen::Matrix3d inertia = Eigen::Matrix3d::Zero();
};

/// The second moment of the mass distribution about the centre of mass, Sigma_c = integral of
/// r r^T dm = (1/2) tr(I_c) 1 - I_c (kg m^2). Its eigenvalues sigma_i are the mass's spread along
/// the principal axes; the principal moments are I_i = sigma_j + sigma_k, so sigma_i >= 0 is the
/// triangle inequality I_i <= I_j + I_k. Cost O(1).
Eigen::Matrix3d second_moment(const Eigen::Matrix3d& inertia);

/// The inertia tensor tr(Sigma) 1 - Sigma of the second moment Sigma (the inverse of
/// second_moment). Cost O(1).
Eigen::Matrix3d inertia_from_second_moment(const Eigen::Matrix3d& sigma);

/// The 4 x 4 pseudo-inertia about {F}'s origin,
///
///     J = [ Sigma_o   m c ]      Sigma_o = Sigma_c + m c c^T = (1/2) tr(I_o) 1 - I_o,
///         [ m c^T     m   ]      I_o = I_c - m [c]x^2 (the inertia about the origin),
///
/// the integral of [r; 1][r; 1]^T dm. A density that is non-negative everywhere gives J >= 0,
/// and every J >= 0 is the pseudo-inertia of some such density (Wensing, Kim and Slotine 2017):
/// J >= 0 is physical consistency, and implies m >= 0 and the triangle inequalities. J is linear
/// in the ten inertial parameters (m, m c, I_o). Cost O(1).
Eigen::Matrix4d pseudo_inertia(const RigidBodyInertia& body);

/// The body whose pseudo-inertia is J (symmetric, J(3,3) = m > 0; otherwise
/// std::invalid_argument): c = J(0:3, 3) / m, Sigma_c = J(0:3, 0:3) - m c c^T. Cost O(1).
RigidBodyInertia rigid_body_from_pseudo_inertia(const Eigen::Matrix4d& J);

/// The principal moments of inertia (the eigenvalues of the symmetric part of I_c), ascending,
/// and the principal axes (unit columns, the eigenvectors, a right-handed frame). Cost O(1).
struct PrincipalInertia {
  Eigen::Vector3d moments = Eigen::Vector3d::Zero();
  Eigen::Matrix3d axes = Eigen::Matrix3d::Identity();
};
PrincipalInertia principal_inertia(const Eigen::Matrix3d& inertia);

/// True when the body's mass and centre of mass are finite, mass > 0, and the inertia is finite
/// and symmetric to rounding (relative 1e-12 of its largest entry); otherwise `error` names the
/// field ("mass", "center_of_mass", "inertia") and says what is wrong. Physical consistency is
/// not required (repair_inertia makes it).
bool is_well_formed(const RigidBodyInertia& body, std::string* error = nullptr);

}  // namespace spdfit
