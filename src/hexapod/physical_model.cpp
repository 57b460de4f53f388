#include "hexapod/physical_model.hpp"

#include <Eigen/LU>
#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>

#include "hexapod/kinematics.hpp"
#include "physical/cone.hpp"

namespace spdfit::hexapod::detail {

namespace {

// A null-space component counts as reaching a parameter group above this fraction of the
// vector's largest component (null-space bases from an SVD are exact to about 1e-15 relative).
constexpr double kReachFraction = 1e-6;

Eigen::Matrix3d cross_matrix(const Eigen::Vector3d& c) {
  Eigen::Matrix3d C;
  C << 0.0, -c.z(), c.y(), c.z(), 0.0, -c.x(), -c.y(), c.x(), 0.0;
  return C;
}

// The payload's mass matrix in {P}'s twist coordinates with the angular part scaled by L
// (S ^P M_x S = this, S = diag(1, 1, 1, L, L, L)), from the scaled pseudo-inertia P.
Matrix6d scaled_payload_matrix(const Eigen::Matrix4d& P) {
  const double m = P(3, 3);
  const Eigen::Vector3d h = P.topRightCorner<3, 1>();  // m c / L
  const Eigen::Matrix3d sigma = P.topLeftCorner<3, 3>();  // Sigma_o / L^2
  Matrix6d Mx;
  Mx.topLeftCorner<3, 3>() = m * Eigen::Matrix3d::Identity();
  Mx.topRightCorner<3, 3>() = -cross_matrix(h);
  Mx.bottomLeftCorner<3, 3>() = cross_matrix(h);
  Mx.bottomRightCorner<3, 3>() = sigma.trace() * Eigen::Matrix3d::Identity() - sigma;  // I_o / L^2
  return Mx;
}

std::string format(double value) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.4g", std::abs(value) < 1e-12 ? 0.0 : value);
  return buffer;
}

std::string vector_text(const Eigen::VectorXd& v) {
  std::string out = "(";
  for (Eigen::Index i = 0; i < v.size(); ++i) out += (i ? ", " : "") + format(v(i));
  return out + ")";
}

}  // namespace

PhysicalModel physical_model(const Geometry& geometry, StrutMasses strut_masses) {
  require_valid(geometry);
  PhysicalModel model;
  model.strut_masses = strut_masses;
  model.length = characteristic_length(geometry);
  const int struts = strut_masses == StrutMasses::Each ? 6 : strut_masses == StrutMasses::Common ? 1 : 0;
  model.parameters = kPayloadParameters + struts;

  // T = J^-T R_b S, so that M_p - M_s = T (S^-1 ^P M_x S^-1) T^T.
  Matrix6d RS = Matrix6d::Zero();
  RS.topLeftCorner<3, 3>() = geometry.payload_rotation;
  RS.bottomRightCorner<3, 3>() = model.length * geometry.payload_rotation;
  const Eigen::PartialPivLU<Matrix6d> lu(jacobian_unchecked(geometry).transpose());
  const Matrix6d T = lu.solve(RS);
  for (int a = 0; a < kPayloadParameters; ++a) {
    ParamVector unit = ParamVector::Zero(kPayloadParameters);
    unit(a) = 1.0;
    Matrix6d Da = T * scaled_payload_matrix(scaled_pseudo_inertia(unit)) * T.transpose();
    model.D.push_back(0.5 * (Da + Da.transpose()));
  }
  if (strut_masses == StrutMasses::Common) {
    model.D.push_back(Matrix6d::Identity());
  } else if (strut_masses == StrutMasses::Each) {
    for (int j = 0; j < 6; ++j) {
      Matrix6d Dj = Matrix6d::Zero();
      Dj(j, j) = 1.0;
      model.D.push_back(Dj);
    }
  } else {
    model.M0 = geometry.strut_mass.asDiagonal();
  }
  return model;
}

Eigen::Matrix4d scaled_pseudo_inertia(const ParamVector& theta) {
  return physical::detail::body_matrix(Eigen::VectorXd(theta.head(kPayloadParameters)), 0);
}

void set_pseudo_inertia(const Eigen::Matrix4d& P, ParamVector& theta) {
  Eigen::VectorXd coordinates(kPayloadParameters);
  physical::detail::set_body_matrix(P, coordinates, 0);
  theta.head(kPayloadParameters) = coordinates;
}

Matrix6d model_mass_matrix(const PhysicalModel& model, const ParamVector& theta) {
  Matrix6d M = model.M0;
  for (int a = 0; a < model.parameters; ++a) M += theta(a) * model.D[static_cast<std::size_t>(a)];
  return 0.5 * (M + M.transpose());
}

ParamVector parameters_of(const PhysicalModel& model, const RigidBodyInertia& payload,
                          const Eigen::VectorXd& strut_mass) {
  ParamVector theta = ParamVector::Zero(model.parameters);
  const Eigen::Vector4d scale(1.0 / model.length, 1.0 / model.length, 1.0 / model.length, 1.0);
  set_pseudo_inertia(scale.asDiagonal() * pseudo_inertia(payload) * scale.asDiagonal(), theta);
  const int struts = model.parameters - kPayloadParameters;
  if (struts > 0) {
    if (strut_mass.size() != struts) {
      throw std::invalid_argument("parameters_of: expected " + std::to_string(struts) + " strut masses");
    }
    theta.tail(struts) = strut_mass;
  }
  return theta;
}

RigidBodyInertia payload_of(const PhysicalModel& model, const ParamVector& theta) {
  const Eigen::Vector4d unscale(model.length, model.length, model.length, 1.0);
  const Eigen::Matrix4d J = unscale.asDiagonal() * scaled_pseudo_inertia(theta) * unscale.asDiagonal();
  if (J(3, 3) > 0.0 && J.allFinite()) return rigid_body_from_pseudo_inertia(J);
  RigidBodyInertia body;
  body.mass = J(3, 3);
  body.center_of_mass.setConstant(std::numeric_limits<double>::quiet_NaN());
  body.inertia.setConstant(std::numeric_limits<double>::quiet_NaN());
  return body;
}

Eigen::MatrixXd design_matrix(const PhysicalModel& model) {
  Eigen::MatrixXd out(21, model.parameters);
  for (int a = 0; a < model.parameters; ++a) {
    const Matrix6d& D = model.D[static_cast<std::size_t>(a)];
    int k = 0;
    for (int j = 0; j < 6; ++j)
      for (int i = j; i < 6; ++i) out(k++, a) = i == j ? D(i, j) : std::sqrt(2.0) * D(i, j);
  }
  return out;
}

std::string describe_combination(const PhysicalModel& model, const Eigen::VectorXd& v_in) {
  const int struts = model.parameters - kPayloadParameters;
  Eigen::VectorXd v = v_in;
  const bool per_strut =
      struts > 0 && v.tail(struts).cwiseAbs().maxCoeff() > kReachFraction * v.cwiseAbs().maxCoeff();
  if (per_strut) {
    // Per 1 kg of strut mass (the largest one's), with a positive sign.
    Eigen::Index largest = 0;
    v.tail(struts).cwiseAbs().maxCoeff(&largest);
    v /= v(kPayloadParameters + largest);
  } else {
    v /= v.cwiseAbs().maxCoeff();
  }
  // With the strut part normalized, the payload part is minus the payload change that the strut
  // change is equivalent to (their sum leaves M_p unchanged).
  const double sign = per_strut ? -1.0 : 1.0;
  const ParamVector theta = sign * v;
  const Eigen::Matrix4d P = scaled_pseudo_inertia(theta);
  const double L = model.length;
  const Eigen::Vector3d dh = L * P.topRightCorner<3, 1>();
  const Eigen::Matrix3d dsigma = L * L * P.topLeftCorner<3, 3>();
  const Eigen::Matrix3d dI = dsigma.trace() * Eigen::Matrix3d::Identity() - dsigma;
  const std::string payload = "mass " + format(P(3, 3)) + " kg, first moment m c " + vector_text(dh) +
                              " kg m, inertia about {P}'s origin [" + vector_text(dI.row(0).transpose()) + ", " +
                              vector_text(dI.row(1).transpose()) + ", " + vector_text(dI.row(2).transpose()) +
                              "] kg m^2";
  if (!per_strut) return "the payload change (" + payload + ") leaves M_p unchanged";
  const std::string strut_text = struts == 1 ? "adding 1 kg to every strut's moving mass"
                                             : "changing the strut masses by " + vector_text(v.tail(struts)) + " kg";
  return strut_text + " changes M_p exactly as adding to the payload " + payload;
}

std::string reached_groups(const PhysicalModel& model, const Eigen::MatrixXd& null_space) {
  std::string out;
  auto add = [&out](const char* name) { out += (out.empty() ? "" : ", ") + std::string(name); };
  auto reaches = [&](std::initializer_list<int> rows) {
    for (Eigen::Index c = 0; c < null_space.cols(); ++c) {
      const double largest = null_space.col(c).cwiseAbs().maxCoeff();
      for (int r : rows) {
        if (r < null_space.rows() && std::abs(null_space(r, c)) > kReachFraction * largest) return true;
      }
    }
    return false;
  };
  if (reaches({3})) add("mass");
  if (reaches({7, 8, 9})) add("centre of mass");
  if (reaches({0, 1, 2, 4, 5, 6})) add("inertia");
  if (model.parameters > kPayloadParameters) {
    if (reaches({10, 11, 12, 13, 14, 15})) add(model.parameters == 11 ? "strut mass" : "strut masses");
  }
  return out;
}

}  // namespace spdfit::hexapod::detail
