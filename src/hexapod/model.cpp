#include "spdfit/hexapod/model.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <Eigen/LU>
#include <Eigen/SVD>

#include "kinematics.hpp"

namespace spdfit::hexapod {

namespace {

constexpr double kTwoPi = 6.283185307179586476925286766559;

// Symmetry tolerance for a user's mass or stiffness matrix (relative to its largest entry):
// estimates from spdfit are exactly symmetric; files written with 17 digits are too.
constexpr double kSymmetryTolerance = 1e-12;

}  // namespace

Points strut_directions(const Geometry& geometry) {
  detail::require_valid(geometry);
  return detail::strut_vectors(geometry).colwise().normalized();
}

Vector6d strut_lengths(const Geometry& geometry) {
  detail::require_valid(geometry);
  return detail::strut_vectors(geometry).colwise().norm().transpose();
}

Matrix6d jacobian(const Geometry& geometry) {
  detail::require_valid(geometry);
  return detail::jacobian_unchecked(geometry);
}

Matrix6d payload_mass_matrix(const Geometry& geometry) {
  detail::require_valid(geometry);
  const Eigen::Matrix3d& R = geometry.payload_rotation;
  Matrix6d Mx = Matrix6d::Zero();
  Mx.topLeftCorner<3, 3>() = geometry.payload_mass * Eigen::Matrix3d::Identity();  // R m I R^T = m I
  Mx.bottomRightCorner<3, 3>() = R * geometry.payload_inertia * R.transpose();     // eq. 2.13
  return Mx;
}

Matrix6d joint_space_mass_matrix(const Geometry& geometry) {
  const Matrix6d Mx = payload_mass_matrix(geometry);  // checks validity
  const Matrix6d J = detail::jacobian_unchecked(geometry);
  // M_p = J^-T Mx J^-1 + M_s (eq. 2.12): with Y = J^-T Mx (J^T Y = Mx), M_p = (J^-T Y^T)^T.
  const Eigen::PartialPivLU<Matrix6d> lu(J.transpose());
  const Matrix6d Y = lu.solve(Mx);
  Matrix6d Mp = lu.solve(Y.transpose());  // = (Y J^-1)^T = M_p^T, and M_p is symmetric
  Mp = 0.5 * (Mp + Mp.transpose()).eval();
  Mp.diagonal() += geometry.strut_mass;
  return Mp;
}

RigidBodyInertia nominal_payload(const Geometry& geometry) {
  RigidBodyInertia payload;
  payload.mass = geometry.payload_mass;
  payload.inertia = geometry.payload_inertia;
  return payload;
}

Matrix6d payload_mass_matrix(const Geometry& geometry, const RigidBodyInertia& payload) {
  detail::require_valid(geometry);
  std::string error;
  if (!is_well_formed(payload, &error)) throw std::invalid_argument("invalid payload: " + error);
  const double m = payload.mass;
  Eigen::Matrix3d cx;  // [c]x
  cx << 0.0, -payload.center_of_mass.z(), payload.center_of_mass.y(),  //
      payload.center_of_mass.z(), 0.0, -payload.center_of_mass.x(),    //
      -payload.center_of_mass.y(), payload.center_of_mass.x(), 0.0;
  Matrix6d Px;
  Px.topLeftCorner<3, 3>() = m * Eigen::Matrix3d::Identity();
  Px.topRightCorner<3, 3>() = -m * cx;
  Px.bottomLeftCorner<3, 3>() = m * cx;
  Px.bottomRightCorner<3, 3>() = 0.5 * (payload.inertia + payload.inertia.transpose()) - m * cx * cx;
  Matrix6d R = Matrix6d::Zero();
  R.topLeftCorner<3, 3>() = geometry.payload_rotation;
  R.bottomRightCorner<3, 3>() = geometry.payload_rotation;
  Matrix6d Bx = R * Px * R.transpose();
  return 0.5 * (Bx + Bx.transpose());
}

Matrix6d joint_space_mass_matrix(const Geometry& geometry, const RigidBodyInertia& payload) {
  const Matrix6d Mx = payload_mass_matrix(geometry, payload);  // checks validity
  const Eigen::PartialPivLU<Matrix6d> lu(detail::jacobian_unchecked(geometry).transpose());
  const Matrix6d Y = lu.solve(Mx);
  Matrix6d Mp = lu.solve(Y.transpose());
  Mp = 0.5 * (Mp + Mp.transpose()).eval();
  Mp.diagonal() += geometry.strut_mass;
  return Mp;
}

Vector6d modal_frequencies_hz(const Geometry& geometry) {
  const Matrix6d Mp = joint_space_mass_matrix(geometry);
  const Matrix6d K = geometry.strut_stiffness.asDiagonal();
  return modal_frequencies_hz(Eigen::MatrixXd(Mp), Eigen::MatrixXd(K));
}

Eigen::VectorXd modal_frequencies_hz(const Eigen::MatrixXd& M, const Eigen::MatrixXd& K) {
  if (M.rows() != M.cols() || K.rows() != K.cols() || M.rows() != K.rows() || M.rows() == 0) {
    throw std::invalid_argument("modal_frequencies_hz: M and K must be square and of the same size");
  }
  if (!M.allFinite() || !K.allFinite()) {
    throw std::invalid_argument("modal_frequencies_hz: M and K must have finite entries");
  }
  if ((M - M.transpose()).cwiseAbs().maxCoeff() > kSymmetryTolerance * M.cwiseAbs().maxCoeff() ||
      (K - K.transpose()).cwiseAbs().maxCoeff() > kSymmetryTolerance * K.cwiseAbs().maxCoeff()) {
    throw std::invalid_argument("modal_frequencies_hz: M and K must be symmetric");
  }
  // K phi = lambda M phi with M = L L^T becomes the symmetric problem C psi = lambda psi,
  // C = L^-1 K L^-T. (Eigen's GeneralizedSelfAdjointEigenSolver does not report a failed
  // Cholesky factorization, so it is done here.)
  const Eigen::LLT<Eigen::MatrixXd> llt(M);
  if (llt.info() != Eigen::Success) {
    throw std::invalid_argument("modal_frequencies_hz: the mass matrix is not positive definite");
  }
  Eigen::MatrixXd C = K;
  llt.matrixL().solveInPlace(C);  // L^-1 K
  C.transposeInPlace();           // K L^-T (K symmetric)
  llt.matrixL().solveInPlace(C);  // L^-1 K L^-T
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> solver(C, Eigen::EigenvaluesOnly);
  Eigen::VectorXd hz = solver.eigenvalues();  // ascending
  for (Eigen::Index i = 0; i < hz.size(); ++i) hz(i) = std::sqrt(std::max(hz(i), 0.0)) / kTwoPi;
  return hz;
}

ModelDescription describe(const Geometry& geometry) {
  ModelDescription d;
  d.jacobian = jacobian(geometry);
  // Dynamic-size decompositions: the numbers the CLI printed before this function existed.
  const Eigen::VectorXd sigma = Eigen::JacobiSVD<Eigen::MatrixXd>(Eigen::MatrixXd(d.jacobian)).singularValues();
  d.jacobian_condition = sigma(0) / sigma(5);
  d.payload_mass_matrix = payload_mass_matrix(geometry);
  d.mass_matrix = joint_space_mass_matrix(geometry);
  d.mass_matrix_eigenvalues =
      Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(Eigen::MatrixXd(d.mass_matrix), Eigen::EigenvaluesOnly)
          .eigenvalues();
  d.modes_hz = modal_frequencies_hz(geometry);
  d.strut_lengths = strut_lengths(geometry);
  d.strut_directions = strut_directions(geometry);
  return d;
}

}  // namespace spdfit::hexapod
