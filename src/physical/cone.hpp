// Internal: the cone of physically consistent inertial parameters of K rigid bodies, in the
// coordinates the shared solver (cone_solver.hpp) works in. Each body's 4 x 4 pseudo-inertia,
// scaled to kg,
//
//     P = diag(1/L, 1/L, 1/L, 1) J diag(1/L, 1/L, 1/L, 1),   J = [Sigma_o  m c; m c^T  m]
//
// (Wensing, Kim and Slotine 2017; L a length that makes the entries comparable), is held as its
// 10 coordinates in the orthonormal basis E_a of the symmetric 4 x 4 matrices (pairs (0,0) (1,1)
// (2,2) (3,3) (0,1) (0,2) (1,2) (0,3) (1,3) (2,3); an off-diagonal E_a = (e_i e_j^T + e_j e_i^T) /
// sqrt 2), so that the Euclidean norm of the coordinates is ||P||_F. A parameter vector theta is
//
//     [P_1 coordinates (10) | ... | P_K coordinates (10) | s (nonnegative) | u (free)],
//
// the cone being P_k >= 0 for every body and s >= 0. Physical consistency of a body is P_k >= 0.
#pragma once

#include <Eigen/Core>

#include "spdfit/rigid_body.hpp"

namespace spdfit::physical::detail {

inline constexpr int kBodyCoordinates = 10;

/// The (row, column) of coordinate a of a body's pseudo-inertia.
inline constexpr int kPairs[kBodyCoordinates][2] = {{0, 0}, {1, 1}, {2, 2}, {3, 3}, {0, 1},
                                                     {0, 2}, {1, 2}, {0, 3}, {1, 3}, {2, 3}};

/// Where each part of theta lies.
struct ConeLayout {
  int bodies = 1;       ///< K pseudo-inertias, 10 coordinates each, first
  int nonnegative = 0;  ///< scalars >= 0 after them (a hexapod's strut masses, a static payload's mass)
  int free = 0;         ///< unconstrained parameters last (sensor biases, friction)

  int size() const { return kBodyCoordinates * bodies + nonnegative + free; }
  int nonnegative_begin() const { return kBodyCoordinates * bodies; }
  int free_begin() const { return nonnegative_begin() + nonnegative; }
  /// nu, the barrier's parameter: 4 per body, 1 per nonnegative scalar.
  double barrier_parameter() const { return 4.0 * bodies + nonnegative; }
};

/// The inertia about the body's origin from a body's parameters in URDF order (m, m c, xx, xy, xz,
/// yy, yz, zz): its entries 4..9 as the symmetric 3 x 3 matrix.
inline Eigen::Matrix3d inertia_of_urdf(const Eigen::Ref<const Eigen::VectorXd>& phi) {
  Eigen::Matrix3d I;
  I << phi(4), phi(5), phi(6), phi(5), phi(7), phi(8), phi(6), phi(8), phi(9);
  return I;
}

/// The basis matrix E_a, and <S, E_a> for a symmetric S (a coordinate of S).
Eigen::Matrix4d basis_matrix(int a);
double coordinate(const Eigen::Matrix4d& S, int a);

/// Body k's P from theta.
Eigen::Matrix4d body_matrix(const Eigen::Ref<const Eigen::VectorXd>& theta, int k);

/// Sets body k's coordinates of theta from a symmetric P.
void set_body_matrix(const Eigen::Matrix4d& P, Eigen::Ref<Eigen::VectorXd> theta, int k);

/// The scaled pseudo-inertia of a body: diag(1/L, 1/L, 1/L, 1) J diag(1/L, 1/L, 1/L, 1).
Eigen::Matrix4d scaled_pseudo_inertia(const RigidBodyInertia& body, double length);

/// The 10 x 10 matrix T with phi = T p: phi = (m, m c_x, m c_y, m c_z, I_xx, I_xy, I_xz, I_yy, I_yz,
/// I_zz) (URDF order; I about the frame's origin) from p, the 10 coordinates of the scaled
/// pseudo-inertia at length L. Cost O(1).
Eigen::Matrix<double, 10, 10> urdf_from_coordinates(double length);

/// Its inverse: p = T^-1 phi.
Eigen::Matrix<double, 10, 10> coordinates_from_urdf(double length);

}  // namespace spdfit::physical::detail
