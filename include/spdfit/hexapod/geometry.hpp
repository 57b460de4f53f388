// A flexure-jointed hexapod (Stewart platform) at its home pose: joint positions, payload mass
// properties and strut properties (thesis 000, chapter 2; see docs/hexapod.md).
#pragma once

#include <string>

#include <Eigen/Core>

namespace spdfit::hexapod {

using Vector6d = Eigen::Matrix<double, 6, 1>;
using Matrix6d = Eigen::Matrix<double, 6, 6>;
using Points = Eigen::Matrix<double, 3, 6>;  ///< six points, one per column

/// The data the joint-space model of thesis eq. (2.12) needs, in SI units. Frames (thesis
/// Figure 2.1): {B} is fixed to the base; {P} is fixed to the payload with its origin at the
/// payload's centre of mass. Strut i runs from base joint q_i to payload joint p_i.
///
/// The field names are the keys of the geometry file (read_geometry), so that a message about
/// a field names the key a user has to fix.
struct Geometry {
  Points base_points = Points::Zero();     ///< q_i in {B} (m)
  Points payload_points = Points::Zero();  ///< p_i in {P} (m), relative to the centre of mass
  Eigen::Vector3d payload_origin = Eigen::Vector3d::Zero();        ///< {P}'s origin in {B} (m)
  Eigen::Matrix3d payload_rotation = Eigen::Matrix3d::Identity();  ///< B_P R: {P}'s axes in {B}
  double payload_mass = 0.0;                                       ///< m_p (kg)
  Eigen::Matrix3d payload_inertia =
      Eigen::Matrix3d::Zero();                  ///< ^cI about the centre of mass, {P} axes (kg m^2)
  Vector6d strut_mass = Vector6d::Zero();       ///< moving mass of each strut, M_s = diag (kg)
  Vector6d strut_stiffness = Vector6d::Zero();  ///< K = diag (N/m)
  Vector6d strut_damping = Vector6d::Zero();    ///< B = diag (N s/m); not used by M_p

  /// True when the model is defined and physical; otherwise `error` says why, starting with
  /// the offending key. Checks: finite entries; payload_mass > 0; strut masses, stiffnesses and
  /// dampings >= 0; payload_inertia symmetric, positive definite and physically realizable
  /// (each principal moment at most the sum of the other two); payload_rotation a rotation;
  /// no strut of zero length; no two struts on one line; a Jacobian that is not singular
  /// (condition number below kMaxJacobianCondition after scaling the angular columns by the
  /// payload's size). Cost: a few 6x6 decompositions.
  bool is_valid(std::string* error = nullptr) const;
};

/// The largest condition number of J (angular columns scaled by the RMS joint radius, so that
/// it is independent of units) for which a geometry is accepted. Beyond it, M_p's condition
/// number (about its square) would exceed 1e16: the struts no longer hold the payload in all
/// six directions, and M_p is meaningless in double precision.
inline constexpr double kMaxJacobianCondition = 1e8;

/// Parameters of the built-in cubic-configuration hexapod (cubic_geometry). The defaults are
/// calibrated so that its M_p reproduces the UW hexapod's matrix of thesis eq. (6.1) to the
/// printed digits (largest entry difference 2.7e-4 kg; entries that the three-fold symmetry
/// makes equal differ by up to 4e-4 in print). The thesis gives M_p but not the design parameters behind it:
/// these are a geometry consistent with it, not UW's drawings. M_p depends on the size only through inertia /
/// edge^2 and com_offset / edge, so other sizes can be had with M_p unchanged.
struct CubicGeometryParameters {
  double edge = 0.254;                  ///< cube edge (m), 10 in; the struts lie on six edges
  double joint_inset = 0.025;           ///< joint distance from the cube vertex along the strut (m)
  double payload_mass = 11.973;         ///< kg
  double inertia_transverse = 0.10249;  ///< about the horizontal axes through the centre of mass (kg m^2)
  double inertia_axial = 0.09968;       ///< about the vertical axis (the cube's diagonal) (kg m^2)
  double com_offset = -0.007598;        ///< centre of mass above the cube's centre, along the diagonal (m)
  double strut_mass = 0.5;              ///< moving mass of each strut (kg)
  double strut_stiffness = 1.0e4;       ///< N/m; illustrative (the thesis gives none)
  double strut_damping = 10.0;          ///< N s/m; illustrative
};

/// A cubic-configuration hexapod: the six struts lie on six edges of a cube whose diagonal is
/// vertical, forming the zigzag between the cube's two horizontal vertex triangles, so that
/// adjacent struts are mutually orthogonal and struts i and i+3 are parallel. Struts 1 and 2
/// share a base corner, 2 and 3 a payload corner, and so on around; each joint is moved
/// `joint_inset` from its cube vertex along the strut, so that no two joints coincide (this
/// leaves J unchanged: a joint slid along its strut's line keeps the same Plucker line).
/// Frames: {B} has z up along the cube's diagonal and its origin at the centre of the base
/// joints' plane; {P} is parallel to {B} at the home pose, at the centre of mass.
/// Throws std::invalid_argument when the parameters give an invalid geometry.
Geometry cubic_geometry(const CubicGeometryParameters& parameters = {});

/// Reads a geometry file (JSON, SI units):
///
///     { "base_points": [[x,y,z] x 6], "payload_points": [[x,y,z] x 6],
///       "payload_origin": [x,y,z], "payload_rotation": [[3x3]] (optional, identity),
///       "payload_mass": m, "payload_inertia": [[3x3]],
///       "strut_mass": number or [6], "strut_stiffness": number or [6],
///       "strut_damping": number or [6] (optional, 0) }
///
/// Keys starting with '_' are ignored (for comments); any other unknown key is an error, so
/// that a misspelt optional key is not silently dropped. Throws io::DataError naming the file
/// and the key on malformed JSON (with line and column), a missing key, a wrong array size, a
/// value that is not a number, or a geometry that fails Geometry::is_valid; and naming the file
/// when it is not a readable regular file (a directory, a FIFO, a device: see io::read_table),
/// is over 1 MiB (a geometry file is about 2 kB), or nests JSON more than 64 levels deep (with
/// line and column). The last two are checked before parsing, so that memory stays bounded.
Geometry read_geometry(const std::string& path);

/// The same, from JSON text; `source` names it in errors.
Geometry parse_geometry(const std::string& text, const std::string& source);

/// The geometry as JSON text in the file format above (numbers round-trip exactly).
std::string geometry_json(const Geometry& geometry);

}  // namespace spdfit::hexapod
