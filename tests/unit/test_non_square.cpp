// A X ~= B with B of d != n columns (issue 17): ls and tls fit the n x d X, checked against
// independent computations (Eigen's column-pivoting QR and complete orthogonal decomposition for
// least squares, a direct SVD of the m x (n + d) matrix [A B] for total least squares) and the
// optimality conditions; the other methods are refused, and the noise estimate stays unbiased.
#include <gtest/gtest.h>

#include <Eigen/LU>
#include <Eigen/QR>
#include <Eigen/SVD>
#include <cmath>
#include <stdexcept>
#include <string>

#include "spdfit/fit.hpp"
#include "spdfit/least_squares.hpp"
#include "spdfit/total_least_squares.hpp"
#include "test_support.hpp"

namespace spdfit {
namespace {

using test::Generator;

struct Problem {
  MatrixXd A, B, X;
};

// A_true X = B_true with noise of standard deviation sigma in every entry of A and B.
Problem noisy(Generator& g, Index m, Index n, Index d, double sigma) {
  Problem p;
  const MatrixXd A_true = g.gaussian(m, n);
  p.X = g.gaussian(n, d);
  p.A = A_true + sigma * g.gaussian(m, n);
  p.B = A_true * p.X + sigma * g.gaussian(m, d);
  return p;
}

// The TLS solution straight from the SVD of the m x (n + d) matrix [A B] (thesis eq. 4.37),
// with no triangular factor: -V12 V22^-1 for the d smallest singular values' right vectors.
MatrixXd tls_by_direct_svd(const MatrixXd& A, const MatrixXd& B) {
  const Index n = A.cols(), d = B.cols();
  MatrixXd Z(A.rows(), n + d);
  Z << A, B;
  const Eigen::JacobiSVD<MatrixXd> svd(Z, Eigen::ComputeFullV);
  const MatrixXd V12 = svd.matrixV().topRightCorner(n, d);
  const MatrixXd V22 = svd.matrixV().bottomRightCorner(d, d);
  return -V12 * V22.inverse();
}

class NonSquare : public ::testing::TestWithParam<std::pair<int, int>> {};

TEST_P(NonSquare, LeastSquaresIsTheNormalEquationsSolution) {
  const auto [n, d] = GetParam();
  Generator g(static_cast<unsigned>(10 * n + d));
  const Problem p = noisy(g, 40, n, d, 0.05);
  const FitResult r = fit(p.A, p.B, Method::LeastSquares);
  ASSERT_TRUE(r.ok()) << r.message;
  ASSERT_EQ(r.X.rows(), n);
  ASSERT_EQ(r.X.cols(), d);
  const MatrixXd reference = p.A.colPivHouseholderQr().solve(p.B);
  EXPECT_LT(test::relative_error(r.X, reference), 1e-13);
  // The gradient of ||A X - B||_F^2 vanishes: A^T (A X - B) = 0, to rounding.
  const MatrixXd gradient = p.A.transpose() * (p.A * r.X - p.B);
  EXPECT_LT(gradient.norm(), 1e-12 * p.A.norm() * p.B.norm());
  EXPECT_EQ(r.diagnostics.n, n);
  EXPECT_EQ(r.diagnostics.d, d);
  EXPECT_NEAR(r.diagnostics.residual_norm, (p.A * r.X - p.B).norm(), 1e-12 * p.B.norm());
  EXPECT_FALSE(r.diagnostics.symmetric);
  EXPECT_FALSE(r.diagnostics.min_eigenvalue.has_value());
  EXPECT_FALSE(r.diagnostics.area_criterion.has_value());
}

TEST_P(NonSquare, TotalLeastSquaresIsTheDirectSvdSolution) {
  const auto [n, d] = GetParam();
  Generator g(static_cast<unsigned>(100 + 10 * n + d));
  const Problem p = noisy(g, 40, n, d, 0.05);
  const FitResult r = fit(p.A, p.B, Method::TotalLeastSquares);
  ASSERT_TRUE(r.ok()) << r.message;
  ASSERT_EQ(r.X.rows(), n);
  ASSERT_EQ(r.X.cols(), d);
  EXPECT_LT(test::relative_error(r.X, tls_by_direct_svd(p.A, p.B)), 1e-12);
  // The correction [dA dB] = -[A B] V2 V2^T makes the corrected system exactly consistent:
  // (A + dA) X = B + dB, and its norm is the reported sqrt(sum_{i>n} sigma_i^2).
  MatrixXd Z(p.A.rows(), n + d);
  Z << p.A, p.B;
  const Eigen::JacobiSVD<MatrixXd> svd(Z, Eigen::ComputeThinV);
  const MatrixXd V2 = svd.matrixV().rightCols(d);
  const MatrixXd corrected = Z - Z * V2 * V2.transpose();
  const MatrixXd mismatch = corrected.leftCols(n) * r.X - corrected.rightCols(d);
  EXPECT_LT(mismatch.norm(), 1e-12 * Z.norm() * (1.0 + r.X.norm()));
  ASSERT_TRUE(r.diagnostics.tls_correction_norm);
  EXPECT_NEAR(*r.diagnostics.tls_correction_norm, svd.singularValues().tail(d).norm(),
              1e-12 * svd.singularValues()(0));
  ASSERT_TRUE(r.diagnostics.tls_sigma_n && r.diagnostics.tls_sigma_n1);
  EXPECT_NEAR(*r.diagnostics.tls_sigma_n, svd.singularValues()(n - 1), 1e-12 * svd.singularValues()(0));
  EXPECT_NEAR(*r.diagnostics.tls_sigma_n1, svd.singularValues()(n), 1e-12 * svd.singularValues()(0));
}

// d < n (fewer outputs than inputs, as a regression of d responses on n regressors), d > n,
// and one column (ordinary errors-in-variables regression).
INSTANTIATE_TEST_SUITE_P(Shapes, NonSquare,
                         ::testing::Values(std::pair{4, 2}, std::pair{2, 5}, std::pair{3, 1}, std::pair{1, 3}));

TEST(NonSquareFit, RankDeficientAGivesTheMinimumNormSolution) {
  Generator g(5);
  MatrixXd A = g.gaussian(30, 4);
  A.col(3) = A.col(0) - 2.0 * A.col(1);  // rank 3
  const MatrixXd B = g.gaussian(30, 2);
  const FitResult r = fit(A, B, Method::LeastSquares);
  ASSERT_TRUE(r.ok()) << r.message;
  EXPECT_EQ(r.diagnostics.rank_a, 3);
  const MatrixXd reference = A.completeOrthogonalDecomposition().solve(B);
  EXPECT_LT(test::relative_error(r.X, reference), 1e-12);
}

TEST(NonSquareFit, SymmetricMethodsAreRefusedNamingLsAndTls) {
  Generator g(6);
  const Problem p = noisy(g, 30, 3, 2, 0.01);
  for (Method method : kSelectableMethods) {
    if (fits_non_square(method)) continue;
    try {
      fit(p.A, p.B, method);
      ADD_FAILURE() << to_string(method) << " accepted a 3x2 X";
    } catch (const std::invalid_argument& e) {
      const std::string what = e.what();
      EXPECT_NE(what.find(std::string(to_string(method)) + " estimates a symmetric X"), std::string::npos) << what;
      EXPECT_NE(what.find("use ls or tls"), std::string::npos) << what;
    }
  }
  // fit_all runs the two that apply, in report order.
  const std::vector<FitResult> all = fit_all(p.A, p.B);
  ASSERT_EQ(all.size(), 2u);
  EXPECT_EQ(all[0].method, Method::LeastSquares);
  EXPECT_EQ(all[1].method, Method::TotalLeastSquares);
  EXPECT_EQ(all[1].X, fit(p.A, p.B, Method::TotalLeastSquares).X);
}

TEST(NonSquareFit, RowsNeeded) {
  // ls needs m >= n; tls with a non-square X needs m >= n + d.
  Generator g(7);
  const MatrixXd A = g.gaussian(5, 3), B = g.gaussian(5, 3).leftCols(2);
  EXPECT_TRUE(fit(A, B, Method::LeastSquares).ok());
  EXPECT_TRUE(fit(A, B, Method::TotalLeastSquares).ok());  // m = n + d = 5
  EXPECT_TRUE(fit(A.topRows(3), B.topRows(3), Method::LeastSquares).ok());
  try {
    fit(A.topRows(4), B.topRows(4), Method::TotalLeastSquares);
    ADD_FAILURE() << "tls accepted 4 rows for n + d = 5";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("n + d = 5"), std::string::npos) << e.what();
  }
  EXPECT_THROW(fit(A.topRows(2), B.topRows(2), Method::LeastSquares), std::invalid_argument);
}

TEST(NonSquareFit, PowerOfTwoUnitsChangeTheSolutionExactly) {
  // Scaling column j of A by 2^k divides row j of X by 2^k exactly; scaling column l of B by 2^k
  // multiplies column l of X by it (ls; the factor's scaling and the rank decision are unit-free).
  Generator g(8);
  const Problem p = noisy(g, 25, 3, 2, 0.1);
  const MatrixXd X = fit(p.A, p.B, Method::LeastSquares).X;
  MatrixXd A = p.A, B = p.B;
  A.col(1) *= std::ldexp(1.0, 40);
  B.col(0) *= std::ldexp(1.0, -30);
  MatrixXd expected = X;
  expected.row(1) *= std::ldexp(1.0, -40);
  expected.col(0) *= std::ldexp(1.0, -30);
  const MatrixXd scaled = fit(A, B, Method::LeastSquares).X;
  EXPECT_LT(test::relative_error(scaled, expected), 1e-15);
}

TEST(NonSquareFit, NoiseEstimateIsUnbiased) {
  // sigma^2 = sum of the d smallest squared singular values of [A B] / (d (m - n)): its mean over
  // trials matches sigma^2 within four standard errors of that mean (at a signal-to-noise ratio
  // where the estimate's second-order bias is far below the standard error).
  constexpr int kTrials = 400;
  constexpr double kSigma = 0.01;
  Generator g(9);
  std::vector<double> ratios;
  for (int t = 0; t < kTrials; ++t) {
    const Problem p = noisy(g, 30, 3, 2, kSigma);
    const FitResult r = fit(p.A, p.B, Method::LeastSquares);
    ASSERT_TRUE(r.diagnostics.noise_sigma);
    ratios.push_back(std::pow(*r.diagnostics.noise_sigma / kSigma, 2));
  }
  double mean = 0.0;
  for (double x : ratios) mean += x;
  mean /= kTrials;
  double var = 0.0;
  for (double x : ratios) var += (x - mean) * (x - mean);
  const double standard_error = std::sqrt(var / (kTrials - 1) / kTrials);
  EXPECT_NEAR(mean, 1.0, 4.0 * standard_error);
  // The dispersion is that of a chi-squared with d (m - n) = 54 degrees of freedom: sqrt(2 / 54).
  EXPECT_NEAR(std::sqrt(var / (kTrials - 1)), std::sqrt(2.0 / 54.0), 0.25 * std::sqrt(2.0 / 54.0));
}

TEST(NonSquareFit, BootstrapHasTheShapeOfX) {
  Generator g(10);
  const Problem p = noisy(g, 60, 3, 2, 0.02);
  FitOptions options;
  options.bootstrap = 50;
  for (Method method : {Method::LeastSquares, Method::TotalLeastSquares}) {
    const FitResult r = fit(p.A, p.B, method, options);
    ASSERT_TRUE(r.ok()) << r.message;
    ASSERT_TRUE(r.bootstrap);
    EXPECT_EQ(r.bootstrap->standard_errors.rows(), 3);
    EXPECT_EQ(r.bootstrap->standard_errors.cols(), 2);
    EXPECT_EQ(r.bootstrap->failed, 0);
    EXPECT_FALSE(r.bootstrap->eigenvalues);  // no spectrum for a non-square X
    EXPECT_TRUE((r.bootstrap->standard_errors.array() > 0.0).all());
  }
}

}  // namespace
}  // namespace spdfit
