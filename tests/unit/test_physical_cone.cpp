// The shared solver of physically consistent fits (physical/cone_solver.hpp) and the criteria on
// it: coordinate maps that invert each other, exact derivatives against central differences, a
// KKT point on the boundary of the cone, and the inertia metric's repair against an independent
// projected-gradient solution of the same QP.
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <Eigen/QR>
#include <cmath>
#include <random>

#include "payload/eiv.hpp"
#include "payload/kinematics.hpp"
#include "payload/wrench_model.hpp"
#include "physical/cone.hpp"
#include "physical/cone_solver.hpp"
#include "physical/linear_criterion.hpp"
#include "spdfit/inertia_repair.hpp"

namespace {

using namespace spdfit;
namespace shared = spdfit::physical::detail;

Eigen::VectorXd random_vector(std::mt19937_64& rng, Eigen::Index n, double scale = 1.0) {
  std::normal_distribution<double> normal(0.0, scale);
  Eigen::VectorXd v(n);
  for (Eigen::Index i = 0; i < n; ++i) v(i) = normal(rng);
  return v;
}

// Central differences of f's gradient and value, for the derivative checks.
void expect_derivatives(const shared::Criterion& f, const Eigen::VectorXd& theta, double tolerance) {
  shared::Evaluation ev, plus, minus;
  ASSERT_TRUE(f.evaluate(theta, 2, ev));
  const double h = 1e-6 * std::max(1.0, theta.norm());
  for (Eigen::Index a = 0; a < theta.size(); ++a) {
    Eigen::VectorXd step = Eigen::VectorXd::Zero(theta.size());
    step(a) = h;
    ASSERT_TRUE(f.evaluate(theta + step, 1, plus));
    ASSERT_TRUE(f.evaluate(theta - step, 1, minus));
    const double g = (plus.f - minus.f) / (2 * h);
    EXPECT_NEAR(ev.g(a), g, tolerance * std::max(1.0, std::abs(g))) << "gradient " << a;
    const Eigen::VectorXd column = (plus.g - minus.g) / (2 * h);
    EXPECT_LT((ev.H.col(a) - column).norm(), tolerance * std::max(1.0, column.norm())) << "Hessian column " << a;
  }
}

TEST(PhysicalCone, CoordinateMapsInvertEachOther) {
  for (double L : {0.05, 1.0, 3.0}) {
    const Eigen::Matrix<double, 10, 10> product = shared::urdf_from_coordinates(L) * shared::coordinates_from_urdf(L);
    EXPECT_LT((product - Eigen::Matrix<double, 10, 10>::Identity()).norm(), 1e-13);
  }
  // A body's coordinates are those of its scaled pseudo-inertia.
  RigidBodyInertia body;
  body.mass = 2.0;
  body.center_of_mass << 0.1, -0.2, 0.05;
  body.inertia << 0.03, 0.001, 0.0, 0.001, 0.04, 0.002, 0.0, 0.002, 0.05;
  const double L = 0.3;
  Eigen::VectorXd p(10);
  shared::set_body_matrix(shared::scaled_pseudo_inertia(body, L), p, 0);
  const Eigen::Matrix<double, 10, 1> phi = shared::urdf_from_coordinates(L) * p;
  const Eigen::Vector3d c = body.center_of_mass;
  const Eigen::Matrix3d I_o = body.inertia + body.mass * (c.squaredNorm() * Eigen::Matrix3d::Identity() - c * c.transpose());
  EXPECT_NEAR(phi(0), 2.0, 1e-15);
  EXPECT_LT((phi.segment<3>(1) - 2.0 * c).norm(), 1e-15);
  EXPECT_NEAR(phi(4), I_o(0, 0), 1e-15);
  EXPECT_NEAR(phi(5), I_o(0, 1), 1e-15);
  EXPECT_NEAR(phi(8), I_o(1, 2), 1e-15);
}

TEST(PhysicalCone, LinearCriterionWithPriorHasExactDerivatives) {
  std::mt19937_64 rng(7);
  const int K = 2, p = 10 * K + 1;
  const Eigen::MatrixXd X = Eigen::MatrixXd::NullaryExpr(p, p, [&] { return std::normal_distribution<double>()(rng); });
  shared::LinearCriterion f(X, random_vector(rng, p), 0.5, 3.0);
  shared::ConeLayout layout{K, 0, 1};
  std::vector<Eigen::Matrix4d> prior;
  Eigen::VectorXd theta(p);
  for (int k = 0; k < K; ++k) {
    const Eigen::Matrix4d A = Eigen::Matrix4d::Random();
    prior.push_back(A * A.transpose() + Eigen::Matrix4d::Identity());
    const Eigen::Matrix4d B = Eigen::Matrix4d::Random();
    shared::set_body_matrix(B * B.transpose() + Eigen::Matrix4d::Identity(), theta, k);
  }
  theta(p - 1) = 0.3;
  f.set_prior(layout, prior, 0.7);
  expect_derivatives(f, theta, 1e-6);
}

TEST(PhysicalCone, ConstrainedLeastSquaresEndsAtAKktPoint) {
  std::mt19937_64 rng(11);
  const int K = 2, p = 10 * K + 2;
  const Eigen::MatrixXd X = Eigen::MatrixXd::NullaryExpr(p, p, [&] { return std::normal_distribution<double>()(rng); });
  // A target whose least-squares solution is far outside the cone (negative masses).
  Eigen::VectorXd target = random_vector(rng, p);
  target(3) = -2.0;
  target(13) = -1.0;
  shared::LinearCriterion f(X, X * target, 0.0, (X * target).squaredNorm());
  const shared::ConeLayout layout{K, 0, 2};
  Eigen::VectorXd start = Eigen::VectorXd::Zero(p);
  for (int k = 0; k < K; ++k) shared::set_body_matrix(Eigen::Matrix4d::Identity(), start, k);
  const shared::SolveResult r = shared::solve_constrained(f, layout, start, 500);
  ASSERT_TRUE(r.converged) << r.message;
  const shared::ConeCertificate c = shared::kkt_certificate(f, layout, r.theta);
  EXPECT_GE(c.primal_min_eig, -1e-12);
  EXPECT_GE(c.dual_min_eig, -1e-9);
  EXPECT_LT(std::abs(c.complementarity), 1e-9);
  EXPECT_LT(c.stationarity, 1e-6);
  // No feasible point nearby does better: random feasible perturbations raise f.
  shared::Evaluation at, near;
  ASSERT_TRUE(f.evaluate(r.theta, 0, at));
  for (int trial = 0; trial < 200; ++trial) {
    Eigen::VectorXd candidate = r.theta + random_vector(rng, p, 1e-3);
    for (int k = 0; k < K; ++k) {
      const Eigen::SelfAdjointEigenSolver<Eigen::Matrix4d> eig(shared::body_matrix(candidate, k));
      shared::set_body_matrix(eig.eigenvectors() * eig.eigenvalues().cwiseMax(0.0).asDiagonal() *
                                  eig.eigenvectors().transpose(),
                              candidate, k);
    }
    ASSERT_TRUE(f.evaluate(candidate, 0, near));
    EXPECT_GE(near.f, at.f - 1e-12);
  }
}

TEST(PayloadEiv, ExactDerivativesAndLeastSquaresWithoutPoseNoise) {
  std::mt19937_64 rng(3);
  payload::detail::Kinematics kin;
  const Eigen::Index m = 30;
  kin.moving = true;
  kin.sign = -1.0;
  kin.wrench = Eigen::MatrixXd::NullaryExpr(6, m, [&] { return std::normal_distribution<double>()(rng); });
  kin.specific_force = Eigen::MatrixXd::NullaryExpr(3, m, [&] { return std::normal_distribution<double>(0, 5)(rng); });
  kin.omega = Eigen::MatrixXd::NullaryExpr(3, m, [&] { return std::normal_distribution<double>()(rng); });
  kin.alpha = Eigen::MatrixXd::NullaryExpr(3, m, [&] { return std::normal_distribution<double>()(rng); });
  payload::detail::ParameterLayout layout;
  layout.moving = true;
  Eigen::MatrixXd noise_x = Eigen::MatrixXd::Zero(9, 9);
  noise_x.diagonal() << 0.1, 0.1, 0.2, 0.01, 0.02, 0.01, 0.3, 0.3, 0.2;
  const Eigen::MatrixXd noise_w = Eigen::VectorXd::Constant(6, 0.04).asDiagonal();
  const Eigen::MatrixXd M = Eigen::MatrixXd::Identity(16, 16);
  payload::detail::EivCriterion eiv(kin, layout, M, noise_w, noise_x, 1);
  Eigen::VectorXd phi = random_vector(rng, 16, 0.5);
  phi(0) = 2.0;
  eiv.set_normalization(10.0);
  expect_derivatives(eiv, phi, 1e-5);
  // Without pose noise: sum_k r_k^T Sigma_w^-1 r_k, computed here from the regressor.
  payload::detail::EivCriterion plain(kin, layout, M, noise_w, Eigen::MatrixXd::Zero(9, 9), 1);
  double f = 0.0;
  ASSERT_TRUE(plain.evaluate_phi(phi, 0, f, nullptr, nullptr));
  double expected = 0.0;
  Eigen::MatrixXd X(6, 16);
  for (Eigen::Index k = 0; k < m; ++k) {
    payload::detail::sample_regressor(kin, k, layout, X);
    expected += (X * phi - kin.wrench.col(k)).squaredNorm() / 0.04;
  }
  EXPECT_NEAR(f, expected, 1e-12 * expected);
}

// The wrench model's Jacobian in the signals x = (s, omega, alpha) against central differences of
// the regressor's wrench X(x) phi (a polynomial of degree two in x: the differences are exact up
// to rounding), and the products with dJ/dphi_a against J at the unit vectors (J is linear in phi).
TEST(PayloadEiv, StructuredJacobianAndProductsMatchTheirDefinitions) {
  std::mt19937_64 rng(7);
  for (const bool moving : {false, true}) {
    for (const double sign : {-1.0, 1.0}) {
      payload::detail::Kinematics kin;
      kin.moving = moving;
      kin.sign = sign;
      kin.wrench = Eigen::MatrixXd::Zero(6, 1);
      kin.specific_force = random_vector(rng, 3, 5.0);
      kin.omega = moving ? random_vector(rng, 3) : Eigen::VectorXd::Zero(3);
      kin.alpha = moving ? random_vector(rng, 3) : Eigen::VectorXd::Zero(3);
      payload::detail::ParameterLayout layout;
      layout.moving = moving;
      const int p = layout.size(), q = layout.inertial();
      const Eigen::VectorXd phi = random_vector(rng, p);
      const payload::detail::Matrix69 J = payload::detail::model_jacobian(kin, 0, layout, phi);
      Eigen::MatrixXd X(6, p);
      const double h = 1e-3;
      for (int c = 0; c < 9; ++c) {
        if (!moving && c >= 3) {
          EXPECT_EQ(J.col(c).norm(), 0.0);
          continue;
        }
        Eigen::Matrix<double, 3, Eigen::Dynamic>& signal = c < 3   ? kin.specific_force
                                                           : c < 6 ? kin.omega
                                                                   : kin.alpha;
        const double saved = signal(c % 3, 0);
        signal(c % 3, 0) = saved + h;
        payload::detail::sample_regressor(kin, 0, layout, X);
        const Eigen::VectorXd plus = X * phi;
        signal(c % 3, 0) = saved - h;
        payload::detail::sample_regressor(kin, 0, layout, X);
        const Eigen::VectorXd minus = X * phi;
        signal(c % 3, 0) = saved;
        EXPECT_LT((J.col(c) - (plus - minus) / (2 * h)).norm(), 1e-9 * (1.0 + J.col(c).norm()))
            << "moving " << moving << " sign " << sign << " column " << c;
      }
      const Eigen::Matrix<double, 6, 1> u = random_vector(rng, 6);
      const Eigen::Matrix<double, 9, 1> v = random_vector(rng, 9);
      Eigen::Matrix<double, 9, 10> Jt_u;
      Eigen::Matrix<double, 6, 10> J_v;
      payload::detail::jacobian_products(kin, 0, layout, u, v, Jt_u, J_v);
      for (int a = 0; a < q; ++a) {
        const payload::detail::Matrix69 Ja =
            payload::detail::model_jacobian(kin, 0, layout, Eigen::VectorXd::Unit(p, a));
        EXPECT_LT((Jt_u.col(a) - Ja.transpose() * u).norm(), 1e-13 * (1.0 + Jt_u.col(a).norm())) << a;
        EXPECT_LT((J_v.col(a) - Ja * v).norm(), 1e-13 * (1.0 + J_v.col(a).norm())) << a;
      }
    }
  }
}

// The inertia metric's QP solved independently: projected gradient on min ||A d||^2, d >= lo.
Eigen::Vector3d projected_gradient(const Eigen::Vector3d& lo) {
  const Eigen::Matrix3d A = Eigen::Matrix3d::Ones() - Eigen::Matrix3d::Identity();
  const Eigen::Matrix3d G = A.transpose() * A;
  const double step = 1.0 / Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(G).eigenvalues().maxCoeff();
  Eigen::Vector3d d = lo.cwiseMax(0.0);
  for (int k = 0; k < 200000; ++k) d = (d - step * G * d).cwiseMax(lo);
  return d;
}

TEST(InertiaRepair, InertiaMetricIsTheNearestInTheInertiaNorm) {
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(0.02, 0.2);
  for (int trial = 0; trial < 20; ++trial) {
    const Eigen::Matrix3d Q = Eigen::Matrix3d::Random().householderQr().householderQ();
    Eigen::Vector3d moments(u(rng), u(rng), 0.0);
    moments(2) = moments(0) + moments(1) + u(rng) * 0.3;
    RigidBodyInertia body;
    body.mass = 1.0;
    body.inertia = Q * moments.asDiagonal() * Q.transpose();
    body.inertia = 0.5 * (body.inertia + body.inertia.transpose()).eval();
    InertiaRepairOptions options;
    const InertiaRepairResult r = repair_inertia(body, options);
    ASSERT_TRUE(r.changed);
    // The reference in the eigenbasis of the second moment.
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(second_moment(body.inertia));
    const Eigen::Vector3d lo = (r.floor - eig.eigenvalues().array()).matrix();
    const Eigen::Vector3d d = projected_gradient(lo);
    const Eigen::Matrix3d change = eig.eigenvectors() * d.asDiagonal() * eig.eigenvectors().transpose();
    const Eigen::Matrix3d reference = body.inertia + inertia_from_second_moment(change);
    EXPECT_LT((r.repaired.inertia - reference).norm(), 1e-9 * body.inertia.norm()) << trial;
    EXPECT_LE(r.distance, (reference - body.inertia).norm() * (1 + 1e-9));
    // Never farther than the clip.
    InertiaRepairOptions clip;
    clip.metric = InertiaMetric::SecondMoment;
    EXPECT_LE(r.distance, repair_inertia(body, clip).distance * (1 + 1e-12));
  }
}

}  // namespace
