// Symmetric Procrustes: the Lyapunov normal equation (thesis eq. 3.15), exact symmetry,
// Theorem 3.2 (3), and the minimum-norm minimizer for rank-deficient A.
#include <gtest/gtest.h>

#include <Eigen/QR>

#include "spdfit/symmetric_procrustes.hpp"
#include "test_support.hpp"

namespace spdfit {
namespace {

using test::Generator;
using test::kEps;
using test::relative_error;

// min ||A X - B||_F over symmetric X as an ordinary least-squares problem in the n(n+1)/2
// parameters p, with off-diagonal parameters sqrt(2) x_ij so that ||p|| = ||X||_F: the
// minimum-norm p (complete orthogonal decomposition) is then the minimum-norm X.
MatrixXd kronecker_reference(const MatrixXd& A, const MatrixXd& B) {
  const Index m = A.rows(), n = A.cols(), k = n * (n + 1) / 2;
  MatrixXd K = MatrixXd::Zero(m * n, k);
  VectorXd rhs(m * n);
  for (Index j = 0; j < n; ++j) rhs.segment(j * m, m) = B.col(j);
  Index p = 0;
  for (Index j = 0; j < n; ++j) {
    for (Index i = j; i < n; ++i, ++p) {
      // X = sum_p x_p E_p; column j of A E_ij is A e_i when j matches.
      const double w = i == j ? 1.0 : 1.0 / std::sqrt(2.0);
      K.block(j * m, p, m, 1) += w * A.col(i);
      if (i != j) K.block(i * m, p, m, 1) += w * A.col(j);
    }
  }
  Eigen::CompleteOrthogonalDecomposition<MatrixXd> cod(K);
  cod.setThreshold(1e-10);
  const VectorXd params = cod.solve(rhs);
  MatrixXd X(n, n);
  p = 0;
  for (Index j = 0; j < n; ++j) {
    for (Index i = j; i < n; ++i, ++p) {
      const double value = i == j ? params(p) : params(p) / std::sqrt(2.0);
      X(i, j) = value;
      X(j, i) = value;
    }
  }
  return X;
}

TEST(SymmetricProcrustes, SolvesTheLyapunovNormalEquation) {
  Generator g(21);
  const MatrixXd A = g.gaussian(25, 6), B = g.gaussian(25, 6);
  const FitResult r = symmetric_procrustes(A, B);
  ASSERT_TRUE(r.ok());
  EXPECT_TRUE(r.X == r.X.transpose());
  EXPECT_TRUE(r.diagnostics.symmetric);
  const MatrixXd P = A.transpose() * A, C = A.transpose() * B + B.transpose() * A;
  const MatrixXd lyapunov = P * r.X + r.X * P - C;
  EXPECT_LT(lyapunov.norm(), 100 * kEps * (2 * P.norm() * r.X.norm() + C.norm()));
  EXPECT_LT(relative_error(r.X, kronecker_reference(A, B)), 1e-12);
}

TEST(SymmetricProcrustes, IsNoWorseThanAnyOtherSymmetricMatrix) {
  Generator g(22);
  const MatrixXd A = g.gaussian(15, 4), B = g.gaussian(15, 4);
  const FitResult r = symmetric_procrustes(A, B);
  ASSERT_TRUE(r.ok());
  const double best = (A * r.X - B).norm();
  for (int trial = 0; trial < 200; ++trial) {
    const MatrixXd E = Generator::symmetrize(g.gaussian(4, 4)) * 1e-3;
    EXPECT_GE((A * (r.X + E) - B).norm(), best * (1 - 1e-14));
  }
}

TEST(SymmetricProcrustes, PositiveDefiniteCrossTermGivesPositiveDefiniteEstimate) {
  Generator g(23);
  for (int trial = 0; trial < 20; ++trial) {
    const MatrixXd A = g.gaussian(20, 5), X = g.spd(5, 50.0);
    const MatrixXd B = A * X + 0.05 * g.gaussian(20, 5);
    const FitResult r = symmetric_procrustes(A, B);
    ASSERT_TRUE(r.ok());
    ASSERT_TRUE(r.diagnostics.cross_term_positive_definite.has_value());
    if (*r.diagnostics.cross_term_positive_definite) {
      EXPECT_TRUE(r.diagnostics.positive_definite);  // thesis Theorem 3.2 (3)
    }
  }
}

TEST(SymmetricProcrustes, WarnsWhenTheEstimateIsIndefinite) {
  Generator g(24);
  const MatrixXd A = g.gaussian(12, 3);
  MatrixXd X = MatrixXd::Identity(3, 3);
  X(2, 2) = -1.0;
  const FitResult r = symmetric_procrustes(A, A * X);
  ASSERT_TRUE(r.ok());
  EXPECT_FALSE(r.diagnostics.positive_definite);
  EXPECT_FALSE(*r.diagnostics.cross_term_positive_definite);
  ASSERT_FALSE(r.warnings.empty());
  EXPECT_NE(r.warnings.back().text.find("not positive definite"), std::string::npos);
}

TEST(SymmetricProcrustes, RankDeficientAGivesTheMinimumNormMinimizer) {
  Generator g(25);
  VectorXd s(4);
  s << 2.0, 1.0, 0.5, 0.0;
  const MatrixXd A = g.with_singular_values(12, s), B = g.gaussian(12, 4);
  const FitResult r = symmetric_procrustes(A, B);
  ASSERT_TRUE(r.ok());
  EXPECT_EQ(r.diagnostics.rank_a, 3);
  EXPECT_LT(relative_error(r.X, kronecker_reference(A, B)), 1e-10);
  ASSERT_FALSE(r.warnings.empty());
  EXPECT_NE(r.warnings.front().text.find("minimum norm"), std::string::npos);
}

TEST(SymmetricProcrustes, OneByOneIsLeastSquares) {
  const MatrixXd a = (MatrixXd(3, 1) << 1, -2, 2).finished();
  const MatrixXd b = (MatrixXd(3, 1) << 2, -3.5, 4.5).finished();
  const FitResult r = symmetric_procrustes(a, b);
  ASSERT_TRUE(r.ok());
  EXPECT_NEAR(r.X(0, 0), a.col(0).dot(b.col(0)) / a.col(0).squaredNorm(), 1e-15);
}

}  // namespace
}  // namespace spdfit
