#include "physical/cone.hpp"

#include <cmath>

namespace spdfit::physical::detail {

namespace {

const double kRoot2 = std::sqrt(2.0);

// phi (URDF order) of a symmetric P at length L: J = D P D, D = diag(L, L, L, 1).
Eigen::Matrix<double, 10, 1> urdf_of(const Eigen::Matrix4d& P, double L) {
  const Eigen::Matrix3d sigma = L * L * P.topLeftCorner<3, 3>();
  const Eigen::Matrix3d I = sigma.trace() * Eigen::Matrix3d::Identity() - sigma;
  Eigen::Matrix<double, 10, 1> phi;
  phi << P(3, 3), L * P(0, 3), L * P(1, 3), L * P(2, 3), I(0, 0), I(0, 1), I(0, 2), I(1, 1), I(1, 2), I(2, 2);
  return phi;
}

}  // namespace

Eigen::Matrix4d basis_matrix(int a) {
  Eigen::Matrix4d E = Eigen::Matrix4d::Zero();
  const int i = kPairs[a][0], j = kPairs[a][1];
  if (i == j) {
    E(i, i) = 1.0;
  } else {
    E(i, j) = E(j, i) = 1.0 / kRoot2;
  }
  return E;
}

double coordinate(const Eigen::Matrix4d& S, int a) {
  const int i = kPairs[a][0], j = kPairs[a][1];
  return i == j ? S(i, i) : kRoot2 * S(i, j);
}

Eigen::Matrix4d body_matrix(const Eigen::Ref<const Eigen::VectorXd>& theta, int k) {
  Eigen::Matrix4d P;
  const int base = kBodyCoordinates * k;
  for (int a = 0; a < kBodyCoordinates; ++a) {
    const int i = kPairs[a][0], j = kPairs[a][1];
    if (i == j) {
      P(i, i) = theta(base + a);
    } else {
      P(i, j) = P(j, i) = theta(base + a) / kRoot2;
    }
  }
  return P;
}

void set_body_matrix(const Eigen::Matrix4d& P, Eigen::Ref<Eigen::VectorXd> theta, int k) {
  const int base = kBodyCoordinates * k;
  for (int a = 0; a < kBodyCoordinates; ++a) {
    const int i = kPairs[a][0], j = kPairs[a][1];
    theta(base + a) = i == j ? P(i, i) : 0.5 * (P(i, j) + P(j, i)) * kRoot2;
  }
}

Eigen::Matrix4d scaled_pseudo_inertia(const RigidBodyInertia& body, double length) {
  const Eigen::Vector4d scale(1.0 / length, 1.0 / length, 1.0 / length, 1.0);
  return scale.asDiagonal() * pseudo_inertia(body) * scale.asDiagonal();
}

Eigen::Matrix<double, 10, 10> urdf_from_coordinates(double length) {
  Eigen::Matrix<double, 10, 10> T;
  for (int a = 0; a < kBodyCoordinates; ++a) T.col(a) = urdf_of(basis_matrix(a), length);
  return T;
}

Eigen::Matrix<double, 10, 10> coordinates_from_urdf(double length) {
  // The inverse map in closed form: Sigma_o = (1/2) tr(I) 1 - I, P = D^-1 J D^-1.
  Eigen::Matrix<double, 10, 10> out;
  for (int a = 0; a < kBodyCoordinates; ++a) {
    Eigen::Matrix<double, 10, 1> phi = Eigen::Matrix<double, 10, 1>::Zero();
    phi(a) = 1.0;
    const Eigen::Matrix3d I = inertia_of_urdf(phi);
    const Eigen::Matrix3d sigma = 0.5 * I.trace() * Eigen::Matrix3d::Identity() - I;
    Eigen::Matrix4d P;
    P.topLeftCorner<3, 3>() = sigma / (length * length);
    P.topRightCorner<3, 1>() = phi.segment<3>(1) / length;
    P.bottomLeftCorner<1, 3>() = phi.segment<3>(1).transpose() / length;
    P(3, 3) = phi(0);
    for (int b = 0; b < kBodyCoordinates; ++b) out(b, a) = coordinate(P, b);
  }
  return out;
}

}  // namespace spdfit::physical::detail
