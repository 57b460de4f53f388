// The linearized joint-space dynamics of a flexure-jointed hexapod: the Jacobian, the
// joint-space mass-inertia matrix M_p (thesis 000 eq. 2.10/2.12) and the modes of M_p^-1 K.
#pragma once

#include <Eigen/Core>

#include "spdfit/hexapod/geometry.hpp"
#include "spdfit/rigid_body.hpp"

namespace spdfit::hexapod {

/// Conventions (docs/hexapod.md, "Conventions"):
///
///  * The payload twist is x_dot = [v; w]: v the velocity of {P}'s origin (the payload's centre
///    of mass) and w the payload's angular velocity, both with components along {B}'s axes.
///  * Strut i runs from the base joint q_i to the payload joint b_i = o + R p_i (o =
///    payload_origin, R = payload_rotation), all in {B}; its unit vector is
///    u_i = (b_i - q_i) / |b_i - q_i| and r_i = R p_i is the payload joint relative to the
///    centre of mass.
///  * Row i of J is [u_i^T, (r_i x u_i)^T], so that the strut extension rates are
///    l_dot = J x_dot (l_dot_i = u_i . (v + w x r_i)), for a fixed base.
///
/// With this J, ^B M_x = R ^P M_x R^T (eq. 2.13) is the payload's kinetic-energy metric in the
/// same twist coordinates, (1/2) x_dot^T ^B M_x x_dot, and M_p of eq. (2.12) is that metric
/// pulled back to strut rates plus the struts' own moving masses. This is the reading of the
/// thesis' "J relating payload Cartesian movements, expressed in the {P} frame, to strut length
/// changes" under which eq. (2.12) holds with the rotation written out; at the usual home pose
/// R = I and the two readings coincide.
///
/// Every function requires geometry.is_valid() and throws std::invalid_argument with its
/// message otherwise. Cost: O(1) (6x6 matrices).

/// The unit strut vectors u_i (columns), in {B}.
Points strut_directions(const Geometry& geometry);

/// The strut lengths |b_i - q_i| at the home pose (m).
Vector6d strut_lengths(const Geometry& geometry);

/// The hexapod Jacobian J with l_dot = J x_dot (conventions above).
Matrix6d jacobian(const Geometry& geometry);

/// ^B M_x = R diag(m_p I_3, ^cI) R^T, the payload's mass-inertia matrix in {B} axes about its
/// centre of mass (thesis eq. 2.13; R the 6x6 block-diagonal rotation).
Matrix6d payload_mass_matrix(const Geometry& geometry);

/// M_p = J^-T ^B_P R ^P M_x ^B_P R^T J^-1 + M_s (thesis eq. 2.10/2.12), the joint-space
/// mass-inertia matrix relating strut-direction payload accelerations to base forces,
/// f_b = M_p p_ddot (eq. 3.1/6.2). Symmetric positive definite for a valid geometry; made
/// exactly symmetric. Computed by solving with J's LU factorization, not by inverting it.
Matrix6d joint_space_mass_matrix(const Geometry& geometry);

/// The geometry's nominal payload as a rigid body in {P}: payload_mass, centre of mass at {P}'s
/// origin, payload_inertia.
RigidBodyInertia nominal_payload(const Geometry& geometry);

/// ^B M_x of a payload that differs from the geometry's nominal one: mass m, centre of mass c
/// (in {P}'s axes, relative to {P}'s origin, the nominal centre of mass) and inertia I_c about
/// its centre of mass ({P} axes), in the twist coordinates of {P}'s origin:
///
///     ^P M_x = [ m 1       -m [c]x          ]     ^B M_x = R ^P M_x R^T,
///              [ m [c]x    I_c - m [c]x^2   ]
///
/// ([c]x the cross-product matrix; I_c - m [c]x^2 is the inertia about {P}'s origin), so that
/// (1/2) x_dot^T ^B M_x x_dot is the payload's kinetic energy for the twist x_dot of {P}'s origin.
/// With c = 0 this is payload_mass_matrix(geometry) for that mass and inertia. The payload must be
/// well formed (is_well_formed; else std::invalid_argument); it need not be physically
/// consistent (the unconstrained estimates that are not still have a matrix).
Matrix6d payload_mass_matrix(const Geometry& geometry, const RigidBodyInertia& payload);

/// M_p = J^-T ^B M_x J^-1 + M_s for that payload (^B M_x as above, M_s the geometry's strut
/// masses): joint_space_mass_matrix(geometry) when the payload is nominal_payload(geometry).
Matrix6d joint_space_mass_matrix(const Geometry& geometry, const RigidBodyInertia& payload);

/// The modal frequencies sqrt(lambda_i) / (2 pi) in Hz, ascending, where lambda_i are the
/// eigenvalues of M_p^-1 K (thesis section 2.2), K = diag(strut_stiffness). Undamped.
Vector6d modal_frequencies_hz(const Geometry& geometry);

/// The same for any mass matrix M (n x n, symmetric positive definite) and stiffness K (n x n,
/// symmetric positive semidefinite), from the generalized symmetric eigenproblem
/// K phi = lambda M phi (no M^-1 K is formed). Throws std::invalid_argument when the shapes
/// differ, M is not symmetric positive definite, or K is not symmetric. Eigenvalues that are
/// negative by rounding give 0 Hz. Cost O(n^3).
Eigen::VectorXd modal_frequencies_hz(const Eigen::MatrixXd& M, const Eigen::MatrixXd& K);

/// Everything a description of the hexapod reports, computed once (what `spdfit hexapod model` and
/// Python's spdfit.hexapod.model() format).
struct ModelDescription {
  Matrix6d jacobian;                  ///< J, l_dot = J x_dot
  double jacobian_condition = 0.0;    ///< sigma_max(J) / sigma_min(J)
  Matrix6d payload_mass_matrix;       ///< ^B M_x (thesis eq. 2.13)
  Matrix6d mass_matrix;               ///< M_p (thesis eq. 2.12)
  Vector6d mass_matrix_eigenvalues;   ///< of M_p, ascending (kg)
  Vector6d modes_hz;                  ///< modal frequencies, ascending (Hz), K = diag(strut_stiffness)
  Vector6d strut_lengths;             ///< at the home pose (m)
  Points strut_directions;            ///< unit strut vectors u_i (columns), in {B}
};

/// The hexapod's Jacobian and its condition number, the payload's and the joint-space mass
/// matrices, M_p's eigenvalues, the modes and the struts, by the functions above. Throws
/// std::invalid_argument unless geometry.is_valid(). Cost O(1) (6x6 matrices).
ModelDescription describe(const Geometry& geometry);

}  // namespace spdfit::hexapod
