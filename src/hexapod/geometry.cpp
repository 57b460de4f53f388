#include "spdfit/hexapod/geometry.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <Eigen/SVD>

#include "kinematics.hpp"
#include "spdfit/format.hpp"

namespace spdfit::hexapod {

namespace {

// Relative tolerance for exact properties of hand-typed data: symmetry of the inertia tensor
// and the triangle inequality of its principal moments. Loose enough for values printed with
// 12 significant digits, tight enough to catch a wrong entry.
constexpr double kTypedDataTolerance = 1e-9;
// Orthonormality of payload_rotation: users type rotations with limited digits (a 7-digit
// cos 45 deg is off by 5e-8); 1e-6 accepts 7 digits and rejects a wrong matrix.
constexpr double kRotationTolerance = 1e-6;
// A strut shorter than this fraction of the hexapod's size has coincident joints; two struts
// whose Plucker coordinates agree to this fraction lie on the same line.
constexpr double kCoincidenceTolerance = 1e-9;

std::string number(double value) { return format_number(value, Precision::Full); }

std::string vector_text(const Eigen::Vector3d& v) {
  return "(" + number(v.x()) + ", " + number(v.y()) + ", " + number(v.z()) + ")";
}

bool fail(std::string* error, const std::string& message) {
  if (error) *error = message;
  return false;
}

// The strut properties: non-negative, one per strut.
bool check_strut_property(const Vector6d& values, const char* key, const char* unit, std::string* error) {
  for (int i = 0; i < 6; ++i) {
    if (values(i) < 0.0) {
      return fail(error, std::string(key) + ": strut " + std::to_string(i + 1) + " has a negative value (" +
                             number(values(i)) + " " + unit + "); it must be zero or positive");
    }
  }
  return true;
}

bool check_inertia(const Eigen::Matrix3d& I, std::string* error) {
  const double scale = I.cwiseAbs().maxCoeff();
  if (!((I - I.transpose()).cwiseAbs().maxCoeff() <= kTypedDataTolerance * scale)) {
    return fail(error, "payload_inertia is not symmetric (an inertia tensor always is): entry [0][1] = " +
                           number(I(0, 1)) + " but [1][0] = " + number(I(1, 0)) +
                           ", [0][2] = " + number(I(0, 2)) + " but [2][0] = " + number(I(2, 0)) +
                           ", [1][2] = " + number(I(1, 2)) + " but [2][1] = " + number(I(2, 1)));
  }
  const Eigen::Vector3d moments =
      Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(I, Eigen::EigenvaluesOnly).eigenvalues();
  if (!(moments(0) > 0.0)) {
    return fail(error, "payload_inertia is not positive definite: its principal moments are " +
                           number(moments(0)) + ", " + number(moments(1)) + ", " + number(moments(2)) +
                           " kg m^2, and a rigid body's are all positive (is it in kg m^2, about the centre "
                           "of mass?)");
  }
  // Each principal moment of a real body is at most the sum of the other two (equality for a
  // flat plate), since I_zz = sum m (x^2 + y^2) <= sum m (x^2 + z^2) + sum m (y^2 + z^2).
  if (moments(2) > (moments(0) + moments(1)) * (1.0 + kTypedDataTolerance)) {
    return fail(error, "payload_inertia is not physically realizable: its largest principal moment " +
                           number(moments(2)) + " kg m^2 exceeds the sum of the other two (" +
                           number(moments(0)) + " + " + number(moments(1)) + ")");
  }
  return true;
}

bool check_rotation(const Eigen::Matrix3d& R, std::string* error) {
  const double orthogonality = (R.transpose() * R - Eigen::Matrix3d::Identity()).norm();
  const double det = R.determinant();
  if (!(orthogonality <= kRotationTolerance) || !(std::abs(det - 1.0) <= kRotationTolerance)) {
    return fail(error,
                "payload_rotation is not a rotation matrix (||R^T R - I|| = " + number(orthogonality) +
                    ", det R = " + number(det) +
                    "); give an orthonormal matrix with determinant +1, to at least 7 significant digits");
  }
  return true;
}

bool check_struts(const Geometry& g, std::string* error) {
  const Points s = detail::strut_vectors(g);
  const Points r = detail::lever_arms(g);
  const Points b = r.colwise() + g.payload_origin;
  const double size = std::max({g.base_points.cwiseAbs().maxCoeff(), b.cwiseAbs().maxCoeff(), 0.0});
  for (int i = 0; i < 6; ++i) {
    if (!(s.col(i).norm() > kCoincidenceTolerance * size)) {
      return fail(error, "base_points[" + std::to_string(i) + "] and payload_points[" + std::to_string(i) +
                             "]: strut " + std::to_string(i + 1) +
                             " has zero length at the home pose (its base joint " +
                             vector_text(g.base_points.col(i)) + " and payload joint " +
                             vector_text(b.col(i)) + " coincide in {B})");
    }
  }
  // Plucker coordinates (u_i, r_i x u_i) with the moment taken about the centre of mass: two
  // struts lie on one line when their directions agree up to sign and their moments agree with
  // the same sign.
  const double length = detail::characteristic_length(g);
  for (int i = 0; i < 6; ++i) {
    const Eigen::Vector3d ui = s.col(i).normalized();
    for (int j = i + 1; j < 6; ++j) {
      const Eigen::Vector3d uj = s.col(j).normalized();
      const double sign = ui.dot(uj) < 0 ? -1.0 : 1.0;
      const Eigen::Vector3d moment_difference = r.col(i).cross(ui) - sign * r.col(j).cross(uj);
      if (ui.cross(uj).norm() <= kCoincidenceTolerance &&
          moment_difference.norm() <= kCoincidenceTolerance * length) {
        return fail(error, "base_points/payload_points: struts " + std::to_string(i + 1) + " and " +
                               std::to_string(j + 1) +
                               " lie on the same line, so the struts cannot hold the payload in all six "
                               "directions (the Jacobian is singular)");
      }
    }
  }
  // J with its angular columns scaled by the payload's size, so the condition number does not
  // depend on the length unit.
  Matrix6d J = detail::jacobian_unchecked(g);
  J.rightCols<3>() /= length;
  const Eigen::JacobiSVD<Matrix6d> svd(J, Eigen::ComputeFullV);
  const Vector6d sigma = svd.singularValues();
  if (!(sigma(5) * kMaxJacobianCondition > sigma(0))) {
    const Vector6d free_twist = svd.matrixV().col(5);
    return fail(error, "base_points/payload_points: the Jacobian is singular (condition number " +
                           (sigma(5) > 0 ? number(sigma(0) / sigma(5)) : std::string("infinite")) +
                           "): the struts do not hold the payload in all six directions; it can move freely "
                           "along v = " +
                           vector_text(free_twist.head<3>()) +
                           ", w = " + vector_text(free_twist.tail<3>() / length) +
                           " (all struts parallel, or all meeting one line, do this)");
  }
  return true;
}

}  // namespace

bool Geometry::is_valid(std::string* error) const {
  struct Field {
    const char* key;
    bool finite;
  };
  const Field fields[] = {
      {"base_points", base_points.allFinite()},       {"payload_points", payload_points.allFinite()},
      {"payload_origin", payload_origin.allFinite()}, {"payload_rotation", payload_rotation.allFinite()},
      {"payload_mass", std::isfinite(payload_mass)},  {"payload_inertia", payload_inertia.allFinite()},
      {"strut_mass", strut_mass.allFinite()},         {"strut_stiffness", strut_stiffness.allFinite()},
      {"strut_damping", strut_damping.allFinite()},
  };
  for (const Field& field : fields) {
    if (!field.finite) return fail(error, std::string(field.key) + ": every value must be a finite number");
  }
  if (!(payload_mass > 0.0)) {
    return fail(error, "payload_mass must be positive (got " + number(payload_mass) + " kg)");
  }
  return check_strut_property(strut_mass, "strut_mass", "kg", error) &&
         check_strut_property(strut_stiffness, "strut_stiffness", "N/m", error) &&
         check_strut_property(strut_damping, "strut_damping", "N s/m", error) &&
         check_inertia(payload_inertia, error) && check_rotation(payload_rotation, error) &&
         check_struts(*this, error);
}

Geometry cubic_geometry(const CubicGeometryParameters& c) {
  if (!(c.edge > 0.0) || !(c.joint_inset >= 0.0) || !(c.joint_inset < 0.5 * c.edge)) {
    throw std::invalid_argument("cubic_geometry: need edge > 0 and 0 <= joint_inset < edge / 2");
  }
  // Cube corners in units of the edge, in cube coordinates; the struts run from a corner of
  // the lower horizontal triangle (one coordinate 1) to one of the upper triangle (two
  // coordinates 1), along a cube axis, in the zigzag order described in the header.
  static const double kStruts[6][2][3] = {
      {{1, 0, 0}, {1, 1, 0}}, {{1, 0, 0}, {1, 0, 1}}, {{0, 0, 1}, {1, 0, 1}},
      {{0, 0, 1}, {0, 1, 1}}, {{0, 1, 0}, {0, 1, 1}}, {{0, 1, 0}, {1, 1, 0}},
  };
  // Rotation taking the cube's diagonal (1, 1, 1)/sqrt(3) to z; x along (1, -1, 0)/sqrt(2).
  const Eigen::Vector3d diagonal = Eigen::Vector3d::Ones().normalized();
  const Eigen::Vector3d x_axis = Eigen::Vector3d(1.0, -1.0, 0.0).normalized();
  Eigen::Matrix3d to_frame;
  to_frame.row(0) = x_axis.transpose();
  to_frame.row(1) = diagonal.cross(x_axis).transpose();
  to_frame.row(2) = diagonal.transpose();

  // Every cube axis makes the same angle with the diagonal: its z component is 1/sqrt(3). The
  // lower triangle's corners lie edge/(2 sqrt 3) below the cube's centre; the base joints
  // lie joint_inset further along their struts, which sets the height of {B}'s origin.
  const double base_height = (-0.5 * c.edge + c.joint_inset) / std::sqrt(3.0);
  const Eigen::Vector3d centre = Eigen::Vector3d::Constant(0.5);
  const Eigen::Vector3d com(0.0, 0.0, c.com_offset);  // relative to the cube's centre

  Geometry g;
  for (int i = 0; i < 6; ++i) {
    const Eigen::Vector3d low = to_frame * (Eigen::Vector3d(kStruts[i][0]) - centre) * c.edge;
    const Eigen::Vector3d high = to_frame * (Eigen::Vector3d(kStruts[i][1]) - centre) * c.edge;
    const Eigen::Vector3d u = (high - low).normalized();
    g.base_points.col(i) = low + c.joint_inset * u - Eigen::Vector3d(0.0, 0.0, base_height);
    g.payload_points.col(i) = high - c.joint_inset * u - com;
  }
  g.payload_origin = com - Eigen::Vector3d(0.0, 0.0, base_height);
  g.payload_rotation.setIdentity();
  g.payload_mass = c.payload_mass;
  g.payload_inertia =
      Eigen::Vector3d(c.inertia_transverse, c.inertia_transverse, c.inertia_axial).asDiagonal();
  g.strut_mass.setConstant(c.strut_mass);
  g.strut_stiffness.setConstant(c.strut_stiffness);
  g.strut_damping.setConstant(c.strut_damping);
  detail::require_valid(g);
  return g;
}

}  // namespace spdfit::hexapod
