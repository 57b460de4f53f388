// The hexapod model: J against finite differences of the strut lengths, M_p as the kinetic-energy
// metric (thesis eq. 2.12-2.13), the built-in cubic geometry against thesis eq. 6.1, and the modes.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>

#include "hexapod_support.hpp"
#include "spdfit/hexapod/geometry.hpp"
#include "spdfit/hexapod/model.hpp"
#include "spdfit/hexapod/simulate.hpp"
#include "test_support.hpp"

namespace spdfit {
namespace {

using hexapod::Geometry;
using hexapod::Matrix6d;
using hexapod::Vector6d;
using test::Generator;
using test::kEps;

constexpr double kTwoPi = 6.283185307179586476925286766559;

// Strut lengths after the payload moves from its home pose by dx = [dv; dw] (dw a rotation
// vector in {B} axes, applied about the centre of mass): the exact nonlinear kinematics.
Vector6d lengths_after(const Geometry& g, const Vector6d& dx) {
  const Eigen::Vector3d dw = dx.tail<3>();
  const Eigen::Matrix3d turn = dw.norm() > 0
                                   ? Eigen::AngleAxisd(dw.norm(), dw.normalized()).toRotationMatrix()
                                   : Eigen::Matrix3d::Identity();
  Vector6d l;
  for (int i = 0; i < 6; ++i) {
    const Eigen::Vector3d joint =
        g.payload_origin + dx.head<3>() + turn * g.payload_rotation * g.payload_points.col(i);
    l(i) = (joint - g.base_points.col(i)).norm();
  }
  return l;
}

TEST(HexapodModel, JacobianIsTheDerivativeOfTheStrutLengths) {
  Generator g(301);
  for (int repeat = 0; repeat < 10; ++repeat) {
    const Geometry geometry = test::random_geometry(g);
    const Matrix6d J = hexapod::jacobian(geometry);
    // Central differences: truncation error h^2 |l'''| / 6 with |l'''| ~ 1/L^2 (L ~ 0.2 m) is
    // ~1e-10 at h = 1e-6, rounding eps L / h ~ 4e-11: 1e-8 covers both with margin.
    constexpr double kStep = 1e-6;
    constexpr double kTolerance = 1e-8;
    for (int k = 0; k < 6; ++k) {
      const Vector6d dx = kStep * Vector6d::Unit(k);
      const Vector6d derivative = (lengths_after(geometry, dx) - lengths_after(geometry, -dx)) / (2 * kStep);
      EXPECT_LT((derivative - J.col(k)).norm(), kTolerance) << "column " << k << ", repeat " << repeat;
    }
  }
}

TEST(HexapodModel, MassMatrixIsTheKineticEnergyMetricInStrutRates) {
  // With M_s = 0, (1/2) l_dot^T M_p l_dot must equal the payload's kinetic energy
  // (1/2) (m |v|^2 + w_P^T I w_P), w_P = R^T w its angular velocity in {P} axes, for every
  // twist x_dot = [v; w] and l_dot = J x_dot.
  Generator g(302);
  for (int repeat = 0; repeat < 10; ++repeat) {
    Geometry geometry = test::random_geometry(g);
    geometry.strut_mass.setZero();
    const Matrix6d J = hexapod::jacobian(geometry);
    const Matrix6d Mp = hexapod::joint_space_mass_matrix(geometry);
    const double cond_j = J.jacobiSvd().singularValues()(0) / J.jacobiSvd().singularValues()(5);
    for (int t = 0; t < 5; ++t) {
      const Vector6d x_dot = Vector6d(g.gaussian(6, 1));
      const Vector6d l_dot = J * x_dot;
      const Eigen::Vector3d v = x_dot.head<3>();
      const Eigen::Vector3d w_p = geometry.payload_rotation.transpose() * x_dot.tail<3>();
      const double expected =
          0.5 * (geometry.payload_mass * v.squaredNorm() + w_p.dot(geometry.payload_inertia * w_p));
      const double actual = 0.5 * l_dot.dot(Mp * l_dot);
      // M_p comes from solves with J: relative error ~ cond(J)^2 eps; 100 for the constants.
      EXPECT_NEAR(actual, expected, 100 * cond_j * cond_j * kEps * expected) << "repeat " << repeat;
    }
  }
}

TEST(HexapodModel, MassMatrixIsSymmetricPositiveDefiniteAndAddsTheStrutMasses) {
  Generator g(303);
  for (int repeat = 0; repeat < 10; ++repeat) {
    const Geometry geometry = test::random_geometry(g);
    const Matrix6d Mp = hexapod::joint_space_mass_matrix(geometry);
    EXPECT_TRUE(Mp == Mp.transpose());
    EXPECT_EQ(Eigen::LLT<Matrix6d>(Mp).info(), Eigen::Success);
    Geometry massless = geometry;
    massless.strut_mass.setZero();
    const Matrix6d difference = Mp - hexapod::joint_space_mass_matrix(massless);
    const Matrix6d expected = geometry.strut_mass.asDiagonal();
    EXPECT_LT((difference - expected).norm(), 1e-12 * Mp.norm());
  }
}

TEST(HexapodModel, BuiltInCubicGeometryReproducesTheThesisMassMatrix) {
  // The defaults of CubicGeometryParameters are calibrated to eq. 6.1, which is printed to 4
  // decimals, and entries that its three-fold symmetry makes equal differ by up to 4e-4 in
  // print ((1,6) = 0.6110 but (4,5) = 0.6114): agreement to 5e-4 is agreement to the print.
  const Matrix6d Mp = hexapod::joint_space_mass_matrix(hexapod::cubic_geometry());
  const Eigen::MatrixXd thesis = hexapod::thesis_mass_matrix();
  EXPECT_LT((Mp - thesis).cwiseAbs().maxCoeff(), 5e-4) << "M_p =\n" << Mp;
}

TEST(HexapodModel, BuiltInCubicStrutsAreMutuallyOrthogonal) {
  const Geometry geometry = hexapod::cubic_geometry();
  const hexapod::Points u = hexapod::strut_directions(geometry);
  constexpr double kTolerance = 1e-14;  // a few rounding errors of unit vectors
  for (int i = 0; i < 6; ++i) {
    const int next = (i + 1) % 6, opposite = (i + 3) % 6;
    EXPECT_NEAR(u.col(i).dot(u.col(next)), 0.0, kTolerance) << "struts " << i + 1 << ", " << next + 1;
    EXPECT_NEAR(std::abs(u.col(i).dot(u.col(opposite))), 1.0, kTolerance)
        << "struts " << i + 1 << ", " << opposite + 1;
  }
  // All struts equally long, and every joint distinct.
  const Vector6d l = hexapod::strut_lengths(geometry);
  const hexapod::CubicGeometryParameters defaults;
  EXPECT_NEAR(l.maxCoeff(), defaults.edge - 2 * defaults.joint_inset, 1e-15);
  EXPECT_NEAR(l.minCoeff(), defaults.edge - 2 * defaults.joint_inset, 1e-15);
  for (int i = 0; i < 6; ++i) {
    for (int j = i + 1; j < 6; ++j) {
      EXPECT_GT((geometry.base_points.col(i) - geometry.base_points.col(j)).norm(), 0.01);
      EXPECT_GT((geometry.payload_points.col(i) - geometry.payload_points.col(j)).norm(), 0.01);
    }
  }
  // Base joints in the plane z = 0 of {B}.
  EXPECT_LT(geometry.base_points.row(2).cwiseAbs().maxCoeff(), 1e-15);
}

TEST(HexapodModel, ModesAreTheEigenvaluesOfMInverseK) {
  Generator g(304);
  for (int repeat = 0; repeat < 5; ++repeat) {
    const Geometry geometry = repeat == 0 ? hexapod::cubic_geometry() : test::random_geometry(g);
    const Vector6d hz = hexapod::modal_frequencies_hz(geometry);
    // Independently: the (real) eigenvalues of the nonsymmetric M_p^-1 K.
    const Matrix6d Mp = hexapod::joint_space_mass_matrix(geometry);
    const Matrix6d MinvK = Mp.inverse() * Matrix6d(geometry.strut_stiffness.asDiagonal());
    Eigen::VectorXd lambda = Eigen::EigenSolver<Matrix6d>(MinvK).eigenvalues().real();
    std::sort(lambda.data(), lambda.data() + lambda.size());
    for (int i = 0; i < 6; ++i) {
      const double expected = std::sqrt(lambda(i)) / kTwoPi;
      EXPECT_NEAR(hz(i), expected, 1e-9 * expected) << "mode " << i;
    }
    EXPECT_TRUE(std::is_sorted(hz.data(), hz.data() + 6));
  }
}

TEST(HexapodModel, ModesOfASingleMassOnASpring) {
  // 1x1: f = sqrt(k / m) / 2 pi.
  const Eigen::MatrixXd M = Eigen::MatrixXd::Constant(1, 1, 2.0), K = Eigen::MatrixXd::Constant(1, 1, 800.0);
  EXPECT_NEAR(hexapod::modal_frequencies_hz(M, K)(0), 20.0 / kTwoPi, 1e-14);
}

TEST(HexapodModel, ModesRejectAnIndefiniteMassMatrix) {
  Eigen::MatrixXd M = Eigen::MatrixXd::Identity(2, 2);
  M(1, 1) = -1.0;
  EXPECT_THROW(hexapod::modal_frequencies_hz(M, Eigen::MatrixXd::Identity(2, 2)), std::invalid_argument);
  EXPECT_THROW(
      hexapod::modal_frequencies_hz(Eigen::MatrixXd::Identity(2, 2), Eigen::MatrixXd::Identity(3, 3)),
      std::invalid_argument);
}

TEST(HexapodModel, ModelFunctionsRejectAnInvalidGeometry) {
  Geometry geometry = hexapod::cubic_geometry();
  geometry.payload_mass = -1.0;
  EXPECT_THROW(hexapod::jacobian(geometry), std::invalid_argument);
  EXPECT_THROW(hexapod::joint_space_mass_matrix(geometry), std::invalid_argument);
  EXPECT_THROW(hexapod::modal_frequencies_hz(geometry), std::invalid_argument);
}

}  // namespace
}  // namespace spdfit
