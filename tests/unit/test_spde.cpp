// SPDE: X P X = Q (Chen & McInroy eq. 10), symmetric positive definite by construction, at the
// closed-form minimum of the area criterion (Corollary III.4), rank-r for rank-r B (III.7).
#include <gtest/gtest.h>

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>

#include "spdfit/area_criterion.hpp"
#include "spdfit/spde.hpp"
#include "test_support.hpp"

namespace spdfit {
namespace {

using test::Generator;
using test::kEps;
using test::relative_error;

struct Noisy {
  MatrixXd A, B, X0;
};

Noisy noisy_problem(Generator& g, Index m, Index n, double noise) {
  Noisy p;
  p.X0 = g.spd(n, 20.0);
  const MatrixXd A0 = g.gaussian(m, n);
  p.A = A0 + noise * g.gaussian(m, n);
  p.B = A0 * p.X0 + noise * g.gaussian(m, n);
  return p;
}

// ||A Y - B Y^-T||_F^2 from the data directly, Y the Cholesky factor (Definition II.1).
double area_from_data(const MatrixXd& A, const MatrixXd& B, const MatrixXd& X) {
  Eigen::LLT<MatrixXd> llt(X);
  const MatrixXd Y = llt.matrixL();
  const MatrixXd Y_inv_t =  // Y^-T = (Y^T)^-1
      Y.transpose().triangularView<Eigen::Upper>().solve(MatrixXd::Identity(X.rows(), X.cols()));
  return (A * Y - B * Y_inv_t).squaredNorm();
}

TEST(Spde, SatisfiesXPXEqualsQAndIsSymmetricPositiveDefinite) {
  Generator g(41);
  for (Index n : {1, 2, 3, 6, 10}) {
    const Noisy p = noisy_problem(g, 3 * n + 2, n, 0.3);
    const FitResult r = spde(p.A, p.B);
    ASSERT_TRUE(r.ok()) << r.message;
    EXPECT_TRUE(r.X == r.X.transpose());
    Eigen::LLT<MatrixXd> llt(r.X);
    EXPECT_EQ(llt.info(), Eigen::Success);
    EXPECT_TRUE(r.diagnostics.positive_definite);
    const MatrixXd P = p.A.transpose() * p.A, Q = p.B.transpose() * p.B;
    EXPECT_LT((r.X * P * r.X - Q).norm(), 1e-12 * Q.norm()) << "n = " << n;
  }
}

TEST(Spde, AchievesTheClosedFormMinimumOfTheAreaCriterion) {
  Generator g(42);
  const Noisy p = noisy_problem(g, 12, 6, 0.5);
  const FitResult r = spde(p.A, p.B);
  ASSERT_TRUE(r.ok());
  ASSERT_TRUE(r.diagnostics.area_criterion && r.diagnostics.area_criterion_minimum);
  const double achieved = *r.diagnostics.area_criterion, minimum = *r.diagnostics.area_criterion_minimum;
  // The closed form subtracts two traces of size ~||A|| ||B||: compare relative to that.
  const double scale = p.A.norm() * p.B.norm();
  EXPECT_NEAR(achieved, minimum, 1e-12 * scale);
  EXPECT_NEAR(achieved, area_from_data(p.A, p.B, r.X), 1e-12 * scale);
  EXPECT_NEAR(achieved, *area_criterion(p.A, p.B, r.X), 1e-12 * scale);
}

TEST(Spde, NoRandomSpdPerturbationBeatsIt) {
  Generator g(43);
  const Noisy p = noisy_problem(g, 12, 6, 0.5);
  const FitResult r = spde(p.A, p.B);
  ASSERT_TRUE(r.ok());
  const double best = area_from_data(p.A, p.B, r.X);
  int tried = 0;
  for (int trial = 0; trial < 400; ++trial) {
    const double size = trial % 2 ? 1e-3 : 1e-1;
    const MatrixXd candidate = r.X + size * Generator::symmetrize(g.gaussian(6, 6));
    Eigen::LLT<MatrixXd> llt(candidate);
    if (llt.info() != Eigen::Success) continue;  // the criterion is defined on SPD matrices only
    ++tried;
    EXPECT_GE(area_from_data(p.A, p.B, candidate), best * (1 - 1e-12));
  }
  EXPECT_GT(tried, 300);
}

TEST(Spde, OneByOneIsTheRatioOfNorms) {
  // n = 1: x^2 a^T a = b^T b, so x = ||b|| / ||a|| (the geometric mean of the two LS slopes).
  const MatrixXd a = (MatrixXd(4, 1) << 1, 2, -1, 3).finished();
  const MatrixXd b = (MatrixXd(4, 1) << 2.2, 3.9, -2.1, 6.3).finished();
  const FitResult r = spde(a, b);
  ASSERT_TRUE(r.ok());
  EXPECT_NEAR(r.X(0, 0), b.norm() / a.norm(), 1e-15);
}

TEST(Spde, SquareDataWorks) {
  // Remark III.5: m = n is allowed when A and B have full rank.
  Generator g(44);
  const Noisy p = noisy_problem(g, 5, 5, 0.2);
  const FitResult r = spde(p.A, p.B);
  ASSERT_TRUE(r.ok());
  const MatrixXd P = p.A.transpose() * p.A, Q = p.B.transpose() * p.B;
  EXPECT_LT((r.X * P * r.X - Q).norm(), 1e-11 * Q.norm());
}

TEST(Spde, RankDeficientBGivesASemidefiniteMinimizerOfThatRank) {
  Generator g(45);
  const Index m = 15, n = 5, r_b = 3;
  const MatrixXd A = g.gaussian(m, n);
  const MatrixXd B = g.gaussian(m, r_b) * g.gaussian(r_b, n);  // rank 3
  const FitResult r = spde(A, B);
  ASSERT_TRUE(r.ok()) << r.message;
  EXPECT_EQ(r.diagnostics.rank_b, r_b);
  EXPECT_TRUE(r.X == r.X.transpose());
  Eigen::SelfAdjointEigenSolver<MatrixXd> eig(r.X);
  const VectorXd lambda = eig.eigenvalues();
  // Numerical rank exactly r: n - r eigenvalues at rounding level, r clearly positive.
  EXPECT_LT(lambda.head(n - r_b).cwiseAbs().maxCoeff(), 100 * n * kEps * lambda(n - 1));
  EXPECT_GT(lambda(n - r_b), 1e-6 * lambda(n - 1));
  const MatrixXd P = A.transpose() * A, Q = B.transpose() * B;
  EXPECT_LT((r.X * P * r.X - Q).norm(), 1e-12 * Q.norm());
  // Corollary III.7: the minimum of tr(P X + X^+ Q) - 2 tr(A^T B) equals the closed form.
  ASSERT_TRUE(r.diagnostics.area_criterion && r.diagnostics.area_criterion_minimum);
  const MatrixXd Xpinv = eig.eigenvectors().rightCols(r_b) * lambda.tail(r_b).cwiseInverse().asDiagonal() *
                         eig.eigenvectors().rightCols(r_b).transpose();
  const double direct = (P * r.X + Xpinv * Q).trace() - 2 * (A.transpose() * B).trace();
  const double scale = A.norm() * B.norm();
  EXPECT_NEAR(*r.diagnostics.area_criterion, direct, 1e-10 * scale);
  EXPECT_NEAR(*r.diagnostics.area_criterion_minimum, direct, 1e-10 * scale);
  ASSERT_FALSE(r.warnings.empty());
  EXPECT_NE(r.warnings.front().text.find("Corollary III.7"), std::string::npos);
}

// Regression (found by UndefinedBehaviorSanitizer): B = 0 made the triangular solve for L run on
// an n x 0 right-hand side, which binds a reference to its (null) first entry.
TEST(SpdeRegression, ZeroBGivesTheZeroMatrixWithoutAnEmptySolve) {
  Generator g(46);
  for (const Index n : {1, 3}) {
    const FitResult r = spde(g.gaussian(2 * n, n), MatrixXd::Zero(2 * n, n));
    ASSERT_TRUE(r.ok()) << r.message;
    EXPECT_EQ(r.diagnostics.rank_b, 0);
    EXPECT_EQ(r.X, MatrixXd::Zero(n, n));
    EXPECT_TRUE(r.diagnostics.positive_semidefinite);
  }
}

TEST(Spde, RankDeficientAIsANumericalFailure) {
  Generator g(46);
  MatrixXd A = g.gaussian(10, 3);
  A.col(2) = A.col(0) - A.col(1);
  const FitResult r = spde(A, g.gaussian(10, 3));
  EXPECT_EQ(r.status, Status::NumericalFailure);
  EXPECT_NE(r.message.find("A is rank-deficient"), std::string::npos);
  EXPECT_EQ(r.diagnostics.rank_a, 2);
}

}  // namespace
}  // namespace spdfit
