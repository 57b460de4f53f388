// Least squares: the normal equations hold, the solution is A^+ B, and rank-deficient A gives
// the minimum-norm solution.
#include <gtest/gtest.h>

#include <Eigen/SVD>

#include "spdfit/least_squares.hpp"
#include "test_support.hpp"

namespace spdfit {
namespace {

using test::Generator;
using test::kEps;
using test::relative_error;

// A^+ B from the SVD of A itself (not of the triangular factor): an independent path.
MatrixXd pseudo_inverse_solution(const MatrixXd& A, const MatrixXd& B, double cutoff) {
  Eigen::JacobiSVD<MatrixXd> svd(A, Eigen::ComputeThinU | Eigen::ComputeThinV);
  VectorXd inv = svd.singularValues();
  for (Index i = 0; i < inv.size(); ++i) inv(i) = inv(i) > cutoff * inv(0) ? 1.0 / inv(i) : 0.0;
  return svd.matrixV() * inv.asDiagonal() * svd.matrixU().transpose() * B;
}

TEST(LeastSquares, SatisfiesTheNormalEquations) {
  Generator g(11);
  const MatrixXd A = g.gaussian(30, 6), B = g.gaussian(30, 6);
  const FitResult r = least_squares(A, B);
  ASSERT_TRUE(r.ok());
  const MatrixXd normal = A.transpose() * (A * r.X - B);
  // A^T (A X - B) = 0 up to eps ||A|| (||A|| ||X|| + ||B||): the backward-stable bound.
  EXPECT_LT(normal.norm(), 100 * kEps * A.norm() * (A.norm() * r.X.norm() + B.norm()));
  EXPECT_LT(relative_error(r.X, pseudo_inverse_solution(A, B, 0.0)), 1e-13);
  EXPECT_NEAR(r.diagnostics.residual_norm, (A * r.X - B).norm(), 1e-12 * B.norm());
  EXPECT_EQ(r.diagnostics.rank_a, 6);
  EXPECT_TRUE(r.warnings.empty());
}

TEST(LeastSquares, RankDeficientAGivesTheMinimumNormSolution) {
  Generator g(12);
  VectorXd s(5);
  s << 3.0, 2.0, 1.0, 0.0, 0.0;
  const MatrixXd A = g.with_singular_values(20, s), B = g.gaussian(20, 5);
  const FitResult r = least_squares(A, B);
  ASSERT_TRUE(r.ok());
  EXPECT_EQ(r.diagnostics.rank_a, 3);
  EXPECT_LT(relative_error(r.X, pseudo_inverse_solution(A, B, 20 * kEps)), 1e-12);
  ASSERT_EQ(r.warnings.size(), 1u);
  EXPECT_NE(r.warnings[0].text.find("rank-deficient"), std::string::npos);
  EXPECT_EQ(r.warnings[0].code, Code::RankDeficient);
  // Minimum norm: X has no component in the null space of A.
  Eigen::JacobiSVD<MatrixXd> svd(A, Eigen::ComputeFullV);
  EXPECT_LT((svd.matrixV().rightCols(2).transpose() * r.X).norm(), 1e-12 * r.X.norm());
}

TEST(LeastSquares, OneByOneIsTheRatioOfInnerProducts) {
  const MatrixXd a = (MatrixXd(4, 1) << 1, 2, 3, 4).finished();
  const MatrixXd b = (MatrixXd(4, 1) << 2.1, 3.9, 6.2, 7.8).finished();
  const FitResult r = least_squares(a, b);
  ASSERT_TRUE(r.ok());
  EXPECT_NEAR(r.X(0, 0), a.col(0).dot(b.col(0)) / a.col(0).squaredNorm(), 1e-15);  // thesis eq. 4.3
}

TEST(LeastSquares, SquareSystemIsSolvedExactly) {
  Generator g(13);
  const MatrixXd A = g.gaussian(4, 4), X = g.gaussian(4, 4);
  const FitResult r = least_squares(A, A * X);
  ASSERT_TRUE(r.ok());
  EXPECT_LT(relative_error(r.X, X), 1e-12);
  EXPECT_LT(r.diagnostics.residual_norm, 1e-12 * (A * X).norm());
}

TEST(LeastSquares, RejectsFewerRowsThanColumns) {
  Generator g(14);
  EXPECT_THROW(least_squares(g.gaussian(3, 4), g.gaussian(3, 4)), std::invalid_argument);
}

}  // namespace
}  // namespace spdfit
