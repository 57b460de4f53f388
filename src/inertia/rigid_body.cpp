#include "spdfit/rigid_body.hpp"

#include <Eigen/Eigenvalues>
#include <cmath>
#include <stdexcept>
#include <string>

#include "estimators/diagnostics.hpp"

namespace spdfit {

namespace {

// A user's inertia tensor is symmetric when written from six numbers (URDF) or with 17 digits;
// anything beyond rounding is a mistake in the input, not something to symmetrize silently.
constexpr double kSymmetryTolerance = 1e-12;

}  // namespace

Eigen::Matrix3d second_moment(const Eigen::Matrix3d& inertia) {
  return 0.5 * inertia.trace() * Eigen::Matrix3d::Identity() - inertia;
}

Eigen::Matrix3d inertia_from_second_moment(const Eigen::Matrix3d& sigma) {
  return sigma.trace() * Eigen::Matrix3d::Identity() - sigma;
}

Eigen::Matrix4d pseudo_inertia(const RigidBodyInertia& body) {
  const double m = body.mass;
  const Eigen::Vector3d& c = body.center_of_mass;
  Eigen::Matrix4d J;
  J.topLeftCorner<3, 3>() = second_moment(body.inertia) + m * c * c.transpose();
  J.topRightCorner<3, 1>() = m * c;
  J.bottomLeftCorner<1, 3>() = m * c.transpose();
  J(3, 3) = m;
  return J;
}

RigidBodyInertia rigid_body_from_pseudo_inertia(const Eigen::Matrix4d& J) {
  if (!(J(3, 3) > 0.0) || !J.allFinite()) {
    throw std::invalid_argument("a pseudo-inertia needs a finite positive mass J(3,3)");
  }
  RigidBodyInertia body;
  body.mass = J(3, 3);
  const Eigen::Matrix4d S = 0.5 * (J + J.transpose());
  body.center_of_mass = S.topRightCorner<3, 1>() / body.mass;
  const Eigen::Matrix3d sigma_c =
      S.topLeftCorner<3, 3>() - body.mass * body.center_of_mass * body.center_of_mass.transpose();
  body.inertia = inertia_from_second_moment(sigma_c);
  return body;
}

PrincipalInertia principal_inertia(const Eigen::Matrix3d& inertia) {
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(0.5 * (inertia + inertia.transpose()));
  PrincipalInertia out;
  out.moments = solver.eigenvalues();
  out.axes = solver.eigenvectors();
  if (out.axes.determinant() < 0.0) out.axes.col(2) *= -1.0;  // right-handed
  return out;
}

bool is_well_formed(const RigidBodyInertia& body, std::string* error) {
  auto fail = [error](const std::string& message) {
    if (error) *error = message;
    return false;
  };
  if (!std::isfinite(body.mass)) return fail("mass must be a finite number");
  if (!(body.mass > 0.0)) return fail("mass must be positive (kg), not " + detail::format_number(body.mass));
  if (!body.center_of_mass.allFinite()) return fail("center_of_mass must be 3 finite numbers");
  if (!body.inertia.allFinite()) return fail("inertia must be a 3x3 matrix of finite numbers");
  const double largest = body.inertia.cwiseAbs().maxCoeff();
  for (int i = 0; i < 3; ++i)
    for (int j = i + 1; j < 3; ++j) {
      if (std::abs(body.inertia(i, j) - body.inertia(j, i)) > kSymmetryTolerance * largest) {
        return fail("inertia is not symmetric: [" + std::to_string(i) + "][" + std::to_string(j) +
                    "] differs from [" + std::to_string(j) + "][" + std::to_string(i) + "]");
      }
    }
  return true;
}

}  // namespace spdfit
