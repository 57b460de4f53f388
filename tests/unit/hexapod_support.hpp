// Random hexapod geometries with known properties, for the model tests.
#pragma once

#include <cmath>

#include <Eigen/Geometry>

#include "spdfit/hexapod/geometry.hpp"
#include "test_support.hpp"

namespace spdfit::test {

/// A random rotation matrix (Haar, with determinant +1).
inline Eigen::Matrix3d random_rotation(Generator& g) {
  Eigen::Matrix3d Q = g.orthonormal(3, 3);
  if (Q.determinant() < 0) Q.col(0) *= -1.0;
  return Q;
}

/// The inertia tensor of a solid box of mass m and sides a, b, c, turned by R: positive
/// definite and physically realizable by construction.
inline Eigen::Matrix3d box_inertia(double m, double a, double b, double c, const Eigen::Matrix3d& R) {
  const Eigen::Vector3d moments(b * b + c * c, a * a + c * c, a * a + b * b);
  const Eigen::Matrix3d I = R * (m / 12.0 * moments).asDiagonal() * R.transpose();
  return 0.5 * (I + I.transpose());
}

/// A random, well-conditioned Stewart platform: base joints in pairs on a circle of radius
/// ~0.2 m, payload joints in pairs on a circle of radius ~0.1 m about 0.2 m higher and turned
/// by 60 degrees (the classic 6-6 layout), all jittered by a few millimetres; a random payload
/// orientation at the home pose, a box-shaped payload, and random strut properties.
inline hexapod::Geometry random_geometry(Generator& g) {
  constexpr double kPi = 3.14159265358979323846;
  hexapod::Geometry geometry;
  geometry.payload_rotation = random_rotation(g);
  geometry.payload_origin =
      Eigen::Vector3d(g.uniform(-0.01, 0.01), g.uniform(-0.01, 0.01), g.uniform(0.18, 0.22));
  for (int i = 0; i < 6; ++i) {
    const int pair = i / 2;
    const double side = (i % 2 == 0) ? -1.0 : 1.0;
    // Base pair k at 120k deg +- 15 deg; its struts lean to payload joints at 120k +- 45 deg.
    const double base_angle = 2.0 * kPi * pair / 3.0 + side * kPi / 12.0;
    const double payload_angle = 2.0 * kPi * pair / 3.0 + side * kPi / 4.0;
    const Eigen::Vector3d base(0.2 * std::cos(base_angle), 0.2 * std::sin(base_angle), 0.0);
    const Eigen::Vector3d payload_in_base(0.1 * std::cos(payload_angle), 0.1 * std::sin(payload_angle), 0.0);
    geometry.base_points.col(i) = base + 0.003 * Eigen::Vector3d(g.normal(), g.normal(), g.normal());
    // Payload joints are given in {P}: undo the payload's rotation.
    const Eigen::Vector3d jitter = 0.003 * Eigen::Vector3d(g.normal(), g.normal(), g.normal());
    geometry.payload_points.col(i) = geometry.payload_rotation.transpose() * (payload_in_base + jitter);
  }
  geometry.payload_mass = g.uniform(2.0, 20.0);
  geometry.payload_inertia = box_inertia(geometry.payload_mass, g.uniform(0.1, 0.3), g.uniform(0.1, 0.3),
                                         g.uniform(0.02, 0.1), random_rotation(g));
  for (int i = 0; i < 6; ++i) {
    geometry.strut_mass(i) = g.uniform(0.1, 1.0);
    geometry.strut_stiffness(i) = g.uniform(5e3, 5e4);
    geometry.strut_damping(i) = g.uniform(0.0, 50.0);
  }
  return geometry;
}

}  // namespace spdfit::test
