#include "payload/wrench_model.hpp"

#include "physical/cone.hpp"

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

// The regressor into any 6 x p matrix expression (dynamic, or fixed for the per-sample kernels).
template <class Derived>
void fill_regressor(const Kinematics& kin, Eigen::Index k, const ParameterLayout& layout,
                    Eigen::MatrixBase<Derived>& X) {
  const double sign = kin.sign;
  const Eigen::Vector3d s = kin.specific_force.col(k);
  X.setZero();
  // f = m s + alpha x h + omega x (omega x h); tau = I alpha + omega x (I omega) + h x s.
  X.template block<3, 1>(0, 0) = sign * s;
  X.template block<3, 3>(3, 1) = -sign * skew(s);
  if (layout.moving) {
    const Eigen::Vector3d w = kin.omega.col(k), a = kin.alpha.col(k);
    const Eigen::Matrix3d W = skew(w);
    X.template block<3, 3>(0, 1) = sign * (skew(a) + W * W);
    X.template block<3, 6>(3, 4) = sign * (inertia_map(a) + W * inertia_map(w));
  }
  X.template block<6, 6>(0, layout.inertial()).setIdentity();
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
  fill_regressor(kin, k, layout, X);
}

template <int P>
void sample_regressor(const Kinematics& kin, Eigen::Index k, const ParameterLayout& layout,
                      Eigen::Matrix<double, 6, P>& X) {
  fill_regressor(kin, k, layout, X);
}

template void sample_regressor<10>(const Kinematics&, Eigen::Index, const ParameterLayout&,
                                   Eigen::Matrix<double, 6, 10>&);
template void sample_regressor<16>(const Kinematics&, Eigen::Index, const ParameterLayout&,
                                   Eigen::Matrix<double, 6, 16>&);

Matrix69 model_jacobian(const Kinematics& kin, Eigen::Index k, const ParameterLayout& layout,
                        const Eigen::Ref<const Eigen::VectorXd>& phi) {
  const double sign = kin.sign;
  // Columns: s (0..2), omega (3..5), alpha (6..8); rows f (0..2), tau (3..5).
  Matrix69 J = Matrix69::Zero();
  const Eigen::Vector3d h = phi.segment<3>(1);
  J.block<3, 3>(0, 0).diagonal().setConstant(sign * phi(0));  // df/ds = m 1
  J.block<3, 3>(3, 0) = sign * skew(h);                       // dtau/ds = [h]x
  if (!layout.moving) return J;
  const Eigen::Vector3d w = kin.omega.col(k);
  const Eigen::Matrix3d I = physical::detail::inertia_of_urdf(phi);
  // df/domega = (omega . h) 1 + omega h^T - 2 h omega^T; df/dalpha = -[h]x.
  J.block<3, 3>(0, 3) =
      sign * (w.dot(h) * Eigen::Matrix3d::Identity() + w * h.transpose() - 2.0 * h * w.transpose());
  J.block<3, 3>(0, 6) = -sign * skew(h);
  // dtau/domega = [omega]x I - [I omega]x; dtau/dalpha = I.
  J.block<3, 3>(3, 3) = sign * (skew(w) * I - skew(I * w));
  J.block<3, 3>(3, 6) = sign * I;
  return J;
}

void jacobian_products(const Kinematics& kin, Eigen::Index k, const ParameterLayout& layout,
                       const Eigen::Matrix<double, 6, 1>& u, const Eigen::Matrix<double, 9, 1>& v,
                       Eigen::Matrix<double, 9, 10>& Jt_u, Eigen::Matrix<double, 6, 10>& J_v) {
  const double sign = kin.sign;
  const Eigen::Vector3d u_f = u.head<3>(), u_t = u.tail<3>();
  const Eigen::Vector3d v_s = v.head<3>(), v_w = v.segment<3>(3), v_a = v.tail<3>();
  const int q = layout.inertial();
  Jt_u.leftCols(q).setZero();
  J_v.leftCols(q).setZero();
  // m: J_m = [1 0 0; 0 0 0].
  Jt_u.block<3, 1>(0, 0) = sign * u_f;
  J_v.block<3, 1>(0, 0) = sign * v_s;
  // h: column j of each block below is J_{h_j}'s product (h x s in tau; alpha x h and
  // omega x (omega x h) in f).
  Jt_u.block<3, 3>(0, 1) = sign * skew(u_t);
  J_v.block<3, 3>(3, 1) = -sign * skew(v_s);
  if (!layout.moving) return;
  const Eigen::Vector3d w = kin.omega.col(k);
  const Eigen::Matrix3d W = skew(w);
  Jt_u.block<3, 3>(3, 1) =
      sign * (u_f * w.transpose() + w.dot(u_f) * Eigen::Matrix3d::Identity() - 2.0 * w * u_f.transpose());
  Jt_u.block<3, 3>(6, 1) = -sign * skew(u_f);
  J_v.block<3, 3>(0, 1) = sign * (skew(v_a) + v_w * w.transpose() + w * v_w.transpose() -
                                  2.0 * w.dot(v_w) * Eigen::Matrix3d::Identity());
  // I (URDF order): tau = I alpha + omega x (I omega), I x = L(x) (xx, xy, xz, yy, yz, zz).
  const Eigen::Matrix<double, 3, 6> Lw = inertia_map(w);
  Jt_u.block<3, 6>(3, 4) = -sign * (inertia_map(w.cross(u_t)) + skew(u_t) * Lw);
  Jt_u.block<3, 6>(6, 4) = sign * inertia_map(u_t);
  J_v.block<3, 6>(3, 4) = sign * (inertia_map(v_a) + W * inertia_map(v_w) + skew(v_w) * Lw);
}

}  // namespace spdfit::payload::detail
