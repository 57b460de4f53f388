// Internal: the linear parametrization theta -> M_p(theta) of physical identification
// (hexapod/physical.hpp) and the conversions between theta and the payload's mass properties.
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

#include "spdfit/hexapod/physical.hpp"

namespace spdfit::hexapod::detail {

/// At most 10 payload parameters and 6 strut masses.
inline constexpr int kMaxPhysicalParameters = 16;
inline constexpr int kPayloadParameters = 10;

using ParamVector = Eigen::Matrix<double, Eigen::Dynamic, 1, Eigen::ColMajor, kMaxPhysicalParameters, 1>;
using ParamMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::ColMajor, kMaxPhysicalParameters,
                                  kMaxPhysicalParameters>;

/// The pseudo-inertia's coordinates: theta_0..9 hold the scaled pseudo-inertia
/// P = diag(1/L, 1/L, 1/L, 1) J diag(1/L, 1/L, 1/L, 1) (every entry in kg) in the orthonormal basis
/// of the symmetric 4 x 4 matrices that the shared solver uses (physical/cone.hpp), so that
/// ||theta|| = ||P||_F; theta_10.. are the estimated strut masses (kg).

/// M_p(theta) = M0 + sum_a theta_a D_a.
struct PhysicalModel {
  StrutMasses strut_masses = StrutMasses::Geometry;
  int parameters = kPayloadParameters;
  double length = 1.0;    ///< L: the RMS payload-joint radius (m)
  std::vector<Matrix6d> D;  ///< the design matrices, one per parameter
  Matrix6d M0 = Matrix6d::Zero();  ///< the geometry's strut masses when they are not estimated
};

/// The model for `geometry` (valid; else std::invalid_argument). Cost O(1).
PhysicalModel physical_model(const Geometry& geometry, StrutMasses strut_masses);

/// The scaled pseudo-inertia of theta's first 10 entries.
Eigen::Matrix4d scaled_pseudo_inertia(const ParamVector& theta);

/// theta_0..9 of a scaled pseudo-inertia (symmetric).
void set_pseudo_inertia(const Eigen::Matrix4d& P, ParamVector& theta);

/// M_p(theta) (symmetric).
Matrix6d model_mass_matrix(const PhysicalModel& model, const ParamVector& theta);

/// theta of a payload (in {P}) and strut masses (1 or 6 entries, those the model estimates).
ParamVector parameters_of(const PhysicalModel& model, const RigidBodyInertia& payload,
                          const Eigen::VectorXd& strut_mass);

/// The payload of theta: mass P33, centre of mass L P(0:3, 3) / m, inertia from the second moment
/// about the centre of mass. A mass <= 0 (an unconstrained fit) gives NaN centre and inertia.
RigidBodyInertia payload_of(const PhysicalModel& model, const ParamVector& theta);

/// The 21 x p design: column a is the packed lower triangle of D_a (off-diagonal entries times
/// sqrt 2, so that the Frobenius norm is kept).
Eigen::MatrixXd design_matrix(const PhysicalModel& model);

/// A combination of the parameters (a null-space vector of some design) in words: the parameter
/// groups it changes, and for a strut mass the payload change it is equivalent to.
std::string describe_combination(const PhysicalModel& model, const Eigen::VectorXd& v);

/// The names of the parameter groups a null-space basis reaches ("mass", "centre of mass",
/// "inertia", "strut mass"), comma-separated.
std::string reached_groups(const PhysicalModel& model, const Eigen::MatrixXd& null_space);

}  // namespace spdfit::hexapod::detail
