// nearest_correlation: Higham's (2002) published example, the optimality conditions of the
// correlation problem, the unit diagonal, the floor alpha, weights, and the input checks.
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>

#include "spdfit/nearest_correlation.hpp"
#include "test_support.hpp"

namespace spdfit {
namespace {

using test::Generator;

// Higham, "Computing the nearest correlation matrix - a problem from finance", IMA J. Numer.
// Anal. 22 (2002), section 4: the tridiagonal matrix and its nearest correlation matrix (4 decimals).
TEST(NearestCorrelation, HighamsExample) {
  MatrixXd C(4, 4);
  C << 2, -1, 0, 0, -1, 2, -1, 0, 0, -1, 2, -1, 0, 0, -1, 2;
  MatrixXd expected(4, 4);
  expected << 1, -0.8084, 0.1916, 0.1068, -0.8084, 1, -0.6562, 0.1916, 0.1916, -0.6562, 1, -0.8084, 0.1068,
      0.1916, -0.8084, 1;
  const NearestCorrelationResult r = nearest_correlation(C);
  EXPECT_TRUE(r.converged);
  EXPECT_LT((r.X - expected).cwiseAbs().maxCoeff(), 6e-5);
  EXPECT_LT(r.iterations, 20);
}

// Optimality: the feasible set (PSD, unit diagonal) is convex, so X minimizes ||X - C||_F^2 / 2
// exactly when the variational inequality <X - C, K - X> >= 0 holds for every correlation matrix
// K; checked on random ones, of low rank so that they reach the boundary.
TEST(NearestCorrelation, OptimalityAndUnitDiagonal) {
  Generator g(7);
  for (Index n : {5, 30, 80}) {
    // A correlation-like matrix with noise that makes it indefinite.
    const MatrixXd M = g.gaussian(n, n);
    MatrixXd C = (M + M.transpose()) / (2.0 * std::sqrt(static_cast<double>(n)));
    C.diagonal().setOnes();
    const NearestCorrelationResult r = nearest_correlation(C);
    ASSERT_TRUE(r.converged) << n;
    EXPECT_TRUE(r.warnings.empty());
    EXPECT_LT((r.X.diagonal().array() - 1.0).abs().maxCoeff(), 1e-14);
    EXPECT_EQ(r.X, r.X.transpose());
    EXPECT_GT(Eigen::SelfAdjointEigenSolver<MatrixXd>(r.X).eigenvalues()(0), -1e-12);
    if (Eigen::SelfAdjointEigenSolver<MatrixXd>(C).eigenvalues()(0) < 0.0) EXPECT_GT(r.clipped, 0) << n;
    const MatrixXd D = r.X - C;
    for (int k = 0; k < 20; ++k) {
      const MatrixXd F = g.gaussian(n, 3);
      MatrixXd K = F * F.transpose();
      const VectorXd s = K.diagonal().cwiseSqrt().cwiseInverse();
      K = (s.asDiagonal() * K * s.asDiagonal()).eval();
      EXPECT_GT(D.cwiseProduct(K - r.X).sum(), -1e-9 * static_cast<double>(n)) << n;
    }
    EXPECT_NEAR(r.distance, D.norm(), 1e-12 * D.norm());
  }
}

// An asymmetric input is repaired through its symmetric part, with a warning.
TEST(NearestCorrelation, WarnsWhenCIsNotSymmetric) {
  MatrixXd C = MatrixXd::Identity(3, 3);
  C(0, 1) = 0.5;
  const NearestCorrelationResult r = nearest_correlation(C);
  ASSERT_EQ(r.warnings.size(), 1u);
  EXPECT_NE(r.warnings[0].find("not symmetric"), std::string::npos);
  EXPECT_NEAR(r.X(0, 1), 0.25, 1e-12);
}

TEST(NearestCorrelation, AlphaIsAFloorThatKeepsTheUnitDiagonal) {
  MatrixXd C(4, 4);
  C << 2, -1, 0, 0, -1, 2, -1, 0, 0, -1, 2, -1, 0, 0, -1, 2;
  NearestCorrelationOptions o;
  o.alpha = 0.1;
  const NearestCorrelationResult r = nearest_correlation(C, o);
  EXPECT_TRUE(r.cholesky_ok);
  EXPECT_LT((r.X.diagonal().array() - 1.0).abs().maxCoeff(), 1e-15);
  EXPECT_GT(Eigen::SelfAdjointEigenSolver<MatrixXd>(r.X).eigenvalues()(0), 0.1 - 1e-10);
}

TEST(NearestCorrelation, AValidCorrelationMatrixIsItsOwnAnswer) {
  Generator g(3);
  MatrixXd F = g.gaussian(10, 10);
  MatrixXd K = F * F.transpose();
  const VectorXd s = K.diagonal().cwiseSqrt().cwiseInverse();
  K = s.asDiagonal() * K * s.asDiagonal();
  const NearestCorrelationResult r = nearest_correlation(K);
  EXPECT_LT((r.X - K).norm(), 1e-12);
  EXPECT_EQ(r.clipped, 0);
}

TEST(NearestCorrelation, InputChecks) {
  EXPECT_THROW(nearest_correlation(MatrixXd(2, 3)), std::invalid_argument);
  MatrixXd C = MatrixXd::Identity(3, 3);
  C(0, 1) = std::nan("");
  EXPECT_THROW(nearest_correlation(C), std::invalid_argument);
  NearestCorrelationOptions o;
  o.weights = VectorXd::Ones(2);
  EXPECT_THROW(nearest_correlation(MatrixXd::Identity(3, 3), o), std::invalid_argument);
  o.weights = VectorXd::Constant(3, -1.0);
  EXPECT_THROW(nearest_correlation(MatrixXd::Identity(3, 3), o), std::invalid_argument);
  o = {};
  o.alpha = 1.0;
  EXPECT_THROW(nearest_correlation(MatrixXd::Identity(3, 3), o), std::invalid_argument);
}

}  // namespace
}  // namespace spdfit
