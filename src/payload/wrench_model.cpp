#include "payload/wrench_model.hpp"

namespace spdfit::payload::detail {

namespace {

Eigen::Matrix3d skew(const Eigen::Vector3d& v) {
  Eigen::Matrix3d S;
  S << 0.0, -v.z(), v.y(), v.z(), 0.0, -v.x(), -v.y(), v.x(), 0.0;
  return S;
}

// L(v): I v = L(v) (xx, xy, xz, yy, yz, zz).
Eigen::Matrix<double, 3, 6> inertia_map(const Eigen::Vector3d& v) {
  Eigen::Matrix<double, 3, 6> L;
  L << v.x(), v.y(), v.z(), 0.0, 0.0, 0.0,  //
      0.0, v.x(), 0.0, v.y(), v.z(), 0.0,   //
      0.0, 0.0, v.x(), 0.0, v.y(), v.z();
  return L;
}

// E_j: the symmetric matrix of inertia entry j (xx, xy, xz, yy, yz, zz).
Eigen::Matrix3d inertia_basis(int j) {
  static const int pairs[6][2] = {{0, 0}, {0, 1}, {0, 2}, {1, 1}, {1, 2}, {2, 2}};
  Eigen::Matrix3d E = Eigen::Matrix3d::Zero();
  E(pairs[j][0], pairs[j][1]) = 1.0;
  E(pairs[j][1], pairs[j][0]) = 1.0;
  return E;
}

}  // namespace

std::vector<std::string> ParameterLayout::names() const {
  std::vector<std::string> out = {"m", "mc_x", "mc_y", "mc_z"};
  if (moving) out.insert(out.end(), {"I_xx", "I_xy", "I_xz", "I_yy", "I_yz", "I_zz"});
  out.insert(out.end(), {"b_fx", "b_fy", "b_fz", "b_tx", "b_ty", "b_tz"});
  return out;
}

void sample_regressor(const Kinematics& kin, Eigen::Index k, const ParameterLayout& layout,
                      Eigen::Ref<Eigen::MatrixXd> X) {
  const double sign = kin.sign;
  const Eigen::Vector3d s = kin.specific_force.col(k);
  X.setZero();
  // f = m s + alpha x h + omega x (omega x h); tau = I alpha + omega x (I omega) + h x s.
  X.block<3, 1>(0, 0) = sign * s;
  X.block<3, 3>(3, 1) = -sign * skew(s);
  if (layout.moving) {
    const Eigen::Vector3d w = kin.omega.col(k), a = kin.alpha.col(k);
    const Eigen::Matrix3d W = skew(w);
    X.block<3, 3>(0, 1) = sign * (skew(a) + W * W);
    X.block<3, 6>(3, 4) = sign * (inertia_map(a) + W * inertia_map(w));
  }
  X.block<6, 6>(0, layout.inertial()).setIdentity();
}

void jacobian_basis(const Kinematics& kin, Eigen::Index k, const ParameterLayout& layout, Matrix69* J) {
  const double sign = kin.sign;
  // Columns: s (0..2), omega (3..5), alpha (6..8); rows f (0..2), tau (3..5).
  J[0].setZero();
  J[0].block<3, 3>(0, 0) = sign * Eigen::Matrix3d::Identity();  // df/ds = m 1
  const Eigen::Vector3d w = kin.omega.col(k);
  for (int j = 0; j < 3; ++j) {
    Matrix69& Jh = J[1 + j];
    Jh.setZero();
    const Eigen::Vector3d e = Eigen::Vector3d::Unit(j);
    Jh.block<3, 3>(3, 0) = sign * skew(e);  // dtau/ds = [h]x
    if (layout.moving) {
      Jh.block<3, 3>(0, 6) = -sign * skew(e);  // df/dalpha = -[h]x
      // df/domega = (omega . h) 1 + omega h^T - 2 h omega^T.
      Jh.block<3, 3>(0, 3) = sign * (w(j) * Eigen::Matrix3d::Identity() + w * e.transpose() - 2.0 * e * w.transpose());
    }
  }
  if (!layout.moving) return;
  const Eigen::Matrix3d W = skew(w);
  for (int j = 0; j < 6; ++j) {
    Matrix69& JI = J[4 + j];
    JI.setZero();
    const Eigen::Matrix3d E = inertia_basis(j);
    JI.block<3, 3>(3, 6) = sign * E;                      // dtau/dalpha = I
    JI.block<3, 3>(3, 3) = sign * (W * E - skew(E * w));  // dtau/domega = [omega]x I - [I omega]x
  }
}

}  // namespace spdfit::payload::detail
