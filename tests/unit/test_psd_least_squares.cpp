// psd-ls's semismooth Newton path (psd_ls_newton.hpp): that it is the path taken on full-rank
// data with the constraint active, that its answer satisfies the KKT conditions recomputed here
// from A, B and X, that it converges quadratically where the minimizer is strictly
// complementary, and that the projected-gradient fallback still answers where Newton does not
// run (rank-deficient A) or is not quadratic (a degenerate minimizer).
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <cmath>

#include "estimators/psd_ls_kernel.hpp"
#include "spdfit/experiment/monte_carlo.hpp"
#include "spdfit/psd_least_squares.hpp"
#include "spdfit/symmetric_procrustes.hpp"
#include "test_support.hpp"

namespace spdfit {
namespace {

using test::Generator;

// KKT of min ||A X - B||_F over X >= eps I recomputed from the data: Y = X - eps I >= 0, S =
// sym(A^T (A X - B)) >= 0, <Y, S> = 0, each relative to the natural scale of S.
struct Kkt {
  double primal = 0.0, dual = 0.0, complementarity = 0.0;
};
Kkt kkt_from_data(const MatrixXd& A, const MatrixXd& B, const MatrixXd& X, double eps) {
  const Index n = X.cols();
  const MatrixXd H = A.transpose() * A;
  const MatrixXd T = H * X - A.transpose() * B;
  const MatrixXd S = 0.5 * (T + T.transpose());
  const MatrixXd Y = X - eps * MatrixXd::Identity(n, n);
  const double scale = Eigen::SelfAdjointEigenSolver<MatrixXd>(H).eigenvalues().maxCoeff() * X.norm() +
                       (A.transpose() * B).norm();
  Kkt k;
  k.primal = Eigen::SelfAdjointEigenSolver<MatrixXd>(Y).eigenvalues()(0) / X.norm();
  k.dual = Eigen::SelfAdjointEigenSolver<MatrixXd>(S).eigenvalues()(0) / scale;
  k.complementarity = std::abs(Y.cwiseProduct(S).sum()) / (scale * X.norm());
  return k;
}

// Data whose symmetric Procrustes estimate is indefinite: the truth has eigenvalues `lambda`
// in a random basis, A has condition number `cond`.
struct Problem {
  MatrixXd A, B;
};
Problem indefinite(Generator& g, Index m, const VectorXd& lambda, double cond, double noise) {
  const Index n = lambda.size();
  const MatrixXd Q = g.orthonormal(n, n);
  const MatrixXd truth = Q * lambda.asDiagonal() * Q.transpose();
  Problem p;
  p.A = g.with_condition(m, n, cond);
  p.B = p.A * truth + noise * g.gaussian(m, n);
  return p;
}

detail::PsdLsKernel<Eigen::Dynamic> run_kernel(const Problem& p, double eps) {
  const Reduction reduction = reduce(TriangularFactor::from_data(p.A, p.B));
  const detail::DynamicReduction& data = detail::data_of(reduction);
  detail::PsdLsKernel<Eigen::Dynamic> k;
  EXPECT_TRUE(detail::psd_ls_kernel(data, std::ldexp(eps, data.exponent_a - data.exponent_b),
                                    FitOptions{}.max_iterations, k));
  return k;
}

// Bounds of the KKT test: the kernel's own tolerance (1e-12 relative) with room for the
// recomputation's rounding (an n x n eigendecomposition of H X, about n eps relative).
constexpr double kKktBound = 1e-11;

FitOptions options_with_floor(double eps) {
  FitOptions o;
  o.min_eig = eps;
  return o;
}

VectorXd spread(Index n, double low, double high) { return VectorXd::LinSpaced(n, low, high); }

TEST(PsdLeastSquaresNewton, IsThePathTakenAndSatisfiesKkt) {
  Generator g(11);
  for (const Index n : {2, 6, 8, 20, 60}) {
    for (const double eps : {0.0, 0.25}) {
      const Problem p = indefinite(g, 3 * n, spread(n, -1.0 - 0.4 * n, 1.0 + 0.6 * n), 10.0, 0.01);
      // The constraint is active: Procrustes is below the floor.
      const FitResult procrustes = symmetric_procrustes(p.A, p.B);
      ASSERT_LT(Eigen::SelfAdjointEigenSolver<MatrixXd>(procrustes.X).eigenvalues()(0), eps) << n;
      const auto k = run_kernel(p, eps);
      EXPECT_TRUE(k.newton_solved) << n;
      EXPECT_GT(k.newton.iterations, 0) << n;
      EXPECT_EQ(k.iterations, k.newton.iterations) << "no projected-gradient iteration ran, n = " << n;
      EXPECT_TRUE(k.converged);
      EXPECT_LE(k.kkt_residual, detail::kPsdLsTolerance);
      const FitResult r = psd_least_squares(p.A, p.B, options_with_floor(eps));
      ASSERT_TRUE(r.ok());
      const Kkt kkt = kkt_from_data(p.A, p.B, r.X, eps);
      EXPECT_GE(kkt.primal, -kKktBound) << n;
      EXPECT_GE(kkt.dual, -kKktBound) << n;
      EXPECT_LE(kkt.complementarity, kKktBound) << n;
      // The constraint is active: X's smallest eigenvalue sits at the floor.
      EXPECT_NEAR(Eigen::SelfAdjointEigenSolver<MatrixXd>(r.X).eigenvalues()(0), eps, 1e-9 * r.X.norm()) << n;
    }
  }
}

// Strict complementarity (the truth's eigenvalues well away from 0, so that rank(Y) +
// rank(S) = n at the minimizer): the residual falls quadratically once it is small. An inexact
// Newton step with the forcing term min(1e-2, r) has r_next <= K (r^2 + r min(1e-2, r)); with
// r_next <= 100 r^2 allowed for K, over every step from r <= 1e-2 down to the rounding level.
TEST(PsdLeastSquaresNewton, ConvergesQuadraticallyWhereStrictlyComplementary) {
  Generator g(12);
  constexpr double kRate = 100.0, kFast = 1e-2, kRounding = 1e-12;
  int checked = 0;
  for (const Index n : {6, 8, 30}) {
    VectorXd lambda = spread(n, 1.0, 3.0);
    lambda.head(n / 3).setConstant(-2.0);
    const Problem p = indefinite(g, 4 * n, lambda, 10.0, 0.05);
    const auto k = run_kernel(p, 0.0);
    ASSERT_TRUE(k.newton_solved) << n;
    for (int i = 0; i < k.newton.iterations; ++i) {
      const double r = k.newton.residual[i], next = k.newton.residual[i + 1];
      if (r > kFast || next < kRounding) continue;
      EXPECT_LE(next, kRate * r * r) << "n = " << n << ", step " << i << ": " << r << " -> " << next;
      ++checked;
    }
  }
  EXPECT_GE(checked, 3);  // the test is not vacuous: quadratic steps were observed
}

// A degenerate minimizer (not strictly complementary: the unconstrained minimizer has a zero
// eigenvalue, so the multiplier and Y are both singular there) is where the rate is not
// quadratic; the result must still be a certified minimizer, by Newton or by its fallback.
TEST(PsdLeastSquaresNewton, DegenerateMinimizerIsStillCertified) {
  Generator g(13);
  const Index n = 6;
  VectorXd lambda(n);
  lambda << -1.0, 0.0, 0.0, 1.0, 2.0, 3.0;
  const Problem p = indefinite(g, 40, lambda, 5.0, 0.0);  // noiseless: Procrustes is the truth
  const FitResult r = psd_least_squares(p.A, p.B);
  ASSERT_TRUE(r.ok());
  EXPECT_TRUE(r.diagnostics.converged);
  const Kkt kkt = kkt_from_data(p.A, p.B, r.X, 0.0);
  EXPECT_GE(kkt.primal, -kKktBound);
  EXPECT_GE(kkt.dual, -kKktBound);
  EXPECT_LE(kkt.complementarity, kKktBound);
}

// Rank-deficient A: the curvature vanishes on part of the cone, the Newton system is singular
// there, and Newton does not run; the projected-gradient path answers with a feasible X. (That
// path is slow to converge on such data, which the certificate and converged = false report.)
TEST(PsdLeastSquaresNewton, RankDeficientDataTakesTheProjectedGradientPath) {
  Generator g(14);
  const Index n = 6;
  Problem p = indefinite(g, 30, spread(n, -2.0, 3.0), 10.0, 0.1);
  p.A.col(5) = p.A.col(0) + p.A.col(1);  // rank 5
  const auto k = run_kernel(p, 0.0);
  EXPECT_EQ(k.newton.iterations, 0);
  EXPECT_FALSE(k.newton_solved);
  EXPECT_GT(k.iterations, 0);
  const FitResult r = psd_least_squares(p.A, p.B);
  ASSERT_TRUE(r.ok());
  EXPECT_GE(kkt_from_data(p.A, p.B, r.X, 0.0).primal, -kKktBound);
}

// The small-problem path (stack matrices, n <= 8; experiment::estimate) runs the same Newton
// code: the same X as the dynamic path, to rounding.
TEST(PsdLeastSquaresNewton, SmallAndDynamicPathsAgree) {
  Generator g(15);
  for (const Index n : {2, 6, 8}) {
    const Problem p = indefinite(g, 2 * n, spread(n, -0.5 * n, n), 10.0, 0.1);
    std::vector<MatrixXd> X;
    experiment::estimate(p.A, p.B, {Method::PsdLeastSquares}, X);
    const FitResult r = psd_least_squares(p.A, p.B);
    ASSERT_TRUE(r.ok());
    EXPECT_LE((X[0] - r.X).norm(), 1e-12 * r.X.norm()) << n;
  }
}

}  // namespace
}  // namespace spdfit
