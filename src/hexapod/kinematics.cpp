#include "kinematics.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

#include <Eigen/Geometry>

namespace spdfit::hexapod::detail {

Points lever_arms(const Geometry& geometry) { return geometry.payload_rotation * geometry.payload_points; }

Points strut_vectors(const Geometry& geometry) {
  return (lever_arms(geometry).colwise() + geometry.payload_origin) - geometry.base_points;
}

Matrix6d jacobian_unchecked(const Geometry& geometry) {
  const Points r = lever_arms(geometry);
  const Points s = strut_vectors(geometry);
  Matrix6d J;
  for (int i = 0; i < 6; ++i) {
    const Eigen::Vector3d u = s.col(i).normalized();
    J.row(i).head<3>() = u.transpose();
    // l_dot_i = u . (v + w x r) = u . v + (r x u) . w
    J.row(i).tail<3>() = r.col(i).cross(u).transpose();
  }
  return J;
}

double characteristic_length(const Geometry& geometry) {
  const double rms = std::sqrt(lever_arms(geometry).squaredNorm() / 6.0);
  return rms > 0.0 ? rms : 1.0;
}

void require_valid(const Geometry& geometry) {
  std::string error;
  if (!geometry.is_valid(&error)) throw std::invalid_argument("invalid hexapod geometry: " + error);
}

}  // namespace spdfit::hexapod::detail
