// Total least squares: the estimate solves the nearest rank-n problem (Eckart-Young-Mirsky),
// its correction norm is the root sum of squares of the discarded singular values (thesis eq.
// 4.33), and singular or non-unique cases are reported.
#include <gtest/gtest.h>

#include <Eigen/LU>
#include <Eigen/SVD>

#include "spdfit/nearest_spd.hpp"
#include "spdfit/total_least_squares.hpp"
#include "test_support.hpp"

namespace spdfit {
namespace {

using test::Generator;
using test::kEps;
using test::relative_error;

MatrixXd stack(const MatrixXd& A, const MatrixXd& B) {
  MatrixXd C(A.rows(), A.cols() + B.cols());
  C << A, B;
  return C;
}

TEST(TotalLeastSquares, SolvesTheNearestRankNProblem) {
  Generator g(31);
  const Index m = 30, n = 5;
  const MatrixXd X0 = g.gaussian(n, n);
  const MatrixXd A0 = g.gaussian(m, n);
  const MatrixXd A = A0 + 0.1 * g.gaussian(m, n), B = A0 * X0 + 0.1 * g.gaussian(m, n);
  const FitResult r = total_least_squares(A, B);
  ASSERT_TRUE(r.ok());

  // Independent path: the full SVD of [A B] itself, truncated to rank n (thesis eq. 4.31).
  Eigen::JacobiSVD<MatrixXd> svd(stack(A, B), Eigen::ComputeThinU | Eigen::ComputeThinV);
  VectorXd kept = svd.singularValues();
  kept.tail(n).setZero();
  const MatrixXd approx = svd.matrixU() * kept.asDiagonal() * svd.matrixV().transpose();
  const MatrixXd Ahat = approx.leftCols(n), Bhat = approx.rightCols(n);
  EXPECT_LT((Ahat * r.X - Bhat).norm(), 1e-12 * Bhat.norm());  // A^ X = B^ (eq. 4.27)

  const double correction = svd.singularValues().tail(n).norm();
  ASSERT_TRUE(r.diagnostics.tls_correction_norm.has_value());
  EXPECT_NEAR(*r.diagnostics.tls_correction_norm, correction, 1e-12 * correction);
  EXPECT_NEAR((stack(A, B) - approx).norm(), correction, 1e-12 * correction);
  EXPECT_NEAR(*r.diagnostics.tls_sigma_n, svd.singularValues()(n - 1), 1e-12 * svd.singularValues()(0));
  EXPECT_NEAR(*r.diagnostics.tls_sigma_n1, svd.singularValues()(n), 1e-12 * svd.singularValues()(0));
}

TEST(TotalLeastSquares, OneByOneMinimizesOrthogonalDistances) {
  // Thesis eq. 4.2-4.21: x minimizes sum (b_i - a_i x)^2 / (1 + x^2).
  const MatrixXd a = (MatrixXd(5, 1) << 1, 2, 3, 4, 5).finished();
  const MatrixXd b = (MatrixXd(5, 1) << 1.2, 1.8, 3.3, 3.9, 5.2).finished();
  const FitResult r = total_least_squares(a, b);
  ASSERT_TRUE(r.ok());
  auto cost = [&](double x) { return (b - a * x).squaredNorm() / (1 + x * x); };
  const double x = r.X(0, 0);
  EXPECT_LE(cost(x), cost(x + 1e-6));
  EXPECT_LE(cost(x), cost(x - 1e-6));
}

TEST(TotalLeastSquares, SymmetricAndPsdVariantsRepairTheEstimate) {
  Generator g(32);
  const MatrixXd A0 = g.gaussian(12, 4), X0 = g.spd(4, 20.0);
  const MatrixXd A = A0 + 0.3 * g.gaussian(12, 4), B = A0 * X0 + 0.3 * g.gaussian(12, 4);
  const FitResult plain = total_least_squares(A, B);
  const FitResult sym = total_least_squares_symmetric(A, B);
  const FitResult psd = total_least_squares_psd(A, B);
  ASSERT_TRUE(plain.ok() && sym.ok() && psd.ok());
  EXPECT_TRUE(sym.X == sym.X.transpose());
  EXPECT_LT(relative_error(sym.X, 0.5 * (plain.X + plain.X.transpose())), 1e-15);  // eq. 4.38
  EXPECT_TRUE(psd.X == psd.X.transpose());
  EXPECT_TRUE(psd.diagnostics.positive_semidefinite);
  EXPECT_LT(relative_error(psd.X, nearest_spd(plain.X).X), 1e-14);  // eq. 4.39
}

TEST(TotalLeastSquares, ZeroColumnInAMakesV22SingularAndFails) {
  Generator g(33);
  MatrixXd A = g.gaussian(10, 3);
  A.col(1).setZero();
  const MatrixXd B = g.gaussian(10, 3);
  const FitResult r = total_least_squares(A, B);
  EXPECT_EQ(r.status, Status::NumericalFailure);
  EXPECT_NE(r.message.find("V22 is singular"), std::string::npos);
  EXPECT_EQ(r.X.size(), 0);
  EXPECT_FALSE(total_least_squares_psd(A, B).ok());
}

TEST(TotalLeastSquares, EqualSingularValuesWarnOrFail) {
  // [A B] with orthonormal columns: every singular value is 1, so sigma_n = sigma_{n+1}.
  Generator g(34);
  const MatrixXd C = g.orthonormal(12, 6);
  const FitResult r = total_least_squares(C.leftCols(3), C.rightCols(3));
  if (r.ok()) {
    ASSERT_FALSE(r.warnings.empty());
    EXPECT_NE(r.warnings.front().text.find("not unique"), std::string::npos);
  } else {
    EXPECT_NE(r.message.find("V22"), std::string::npos);
  }
}

TEST(TotalLeastSquares, IsNotFooledByASeparateScaleOfAAndB) {
  // The factor scales A and B by different powers of two; TLS must undo that (it is only
  // invariant under a common scaling).
  Generator g(35);
  const MatrixXd A0 = g.gaussian(20, 3), X0 = g.gaussian(3, 3);
  const MatrixXd A = A0 + 0.05 * g.gaussian(20, 3), B = (A0 * X0 + 0.05 * g.gaussian(20, 3)) * 1024.0;
  const FitResult r = total_least_squares(A, B);
  Eigen::JacobiSVD<MatrixXd> svd(stack(A, B), Eigen::ComputeThinV);
  const MatrixXd V12 = svd.matrixV().topRightCorner(3, 3), V22 = svd.matrixV().bottomRightCorner(3, 3);
  const MatrixXd reference = -V12 * V22.inverse();
  ASSERT_TRUE(r.ok());
  EXPECT_LT(relative_error(r.X, reference), 1e-11);
}

}  // namespace
}  // namespace spdfit
