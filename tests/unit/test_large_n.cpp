// The large-n path: from 64 columns of [A B] the QR, and above n = 64 the SVDs, run on LAPACK
// (dgeqrf, dgesdd) when spdfit is built with SPDFIT_LAPACK, else on Eigen's HouseholderQR and
// BDCSVD. Checked against the estimators' defining equations and, for TLS, against Eigen's own
// SVD of [A B]. The diagnostics (on LAPACK's dsyevd and the BLAS at this size) against the
// same quantities computed from A, B and X with Eigen alone.
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <Eigen/LU>
#include <Eigen/SVD>

#include "spdfit/fit.hpp"
#include "test_support.hpp"

namespace spdfit {
namespace {

using test::kEps;

class LargeN : public ::testing::Test {
 protected:
  static constexpr Index kN = 70, kM = 180;
  void SetUp() override {
    test::Generator g(51);
    A_ = g.gaussian(kM, kN);
    B_ = A_ * g.spd(kN, 20.0) + 0.05 * g.gaussian(kM, kN);
  }
  MatrixXd A_, B_;
};

TEST_F(LargeN, LeastSquaresSolvesTheNormalEquations) {
  const FitResult r = fit(A_, B_, Method::LeastSquares);
  ASSERT_TRUE(r.ok()) << r.message;
  const MatrixXd residual = A_.transpose() * (A_ * r.X - B_);
  EXPECT_LE(residual.norm(), 1e3 * kEps * A_.norm() * (A_.norm() * r.X.norm() + B_.norm()));
}

TEST_F(LargeN, ProcrustesSolvesItsLyapunovEquation) {
  // Thesis eq. 3.15: A^T A X + X A^T A = A^T B + B^T A.
  const FitResult r = fit(A_, B_, Method::SymmetricProcrustes);
  ASSERT_TRUE(r.ok()) << r.message;
  const MatrixXd P = A_.transpose() * A_, C = A_.transpose() * B_;
  const MatrixXd lhs = P * r.X + r.X * P, rhs = C + C.transpose();
  EXPECT_LE((lhs - rhs).norm(), 1e3 * kEps * rhs.norm());
  EXPECT_EQ(r.X, r.X.transpose());
}

TEST_F(LargeN, SpdeSolvesXPXEqualsQ) {
  const FitResult r = fit(A_, B_, Method::Spde);
  ASSERT_TRUE(r.ok()) << r.message;
  const MatrixXd P = A_.transpose() * A_, Q = B_.transpose() * B_;
  EXPECT_LE((r.X * P * r.X - Q).norm(), 1e4 * kEps * Q.norm());
  EXPECT_TRUE(r.diagnostics.positive_definite);
}

TEST_F(LargeN, TlsMatchesEigensSvdOfTheData) {
  const FitResult r = fit(A_, B_, Method::TotalLeastSquares);
  ASSERT_TRUE(r.ok()) << r.message;
  MatrixXd AB(kM, 2 * kN);
  AB << A_, B_;
  const Eigen::BDCSVD<MatrixXd> svd(AB, Eigen::ComputeThinV);
  const MatrixXd V12 = svd.matrixV().topRightCorner(kN, kN);
  const MatrixXd V22 = svd.matrixV().bottomRightCorner(kN, kN);
  const MatrixXd X = -V12 * V22.inverse();  // thesis eq. 4.37
  EXPECT_LE((r.X - X).norm(), 1e-9 * X.norm());
}

// fit() reduces the data for the one method it runs: without R11's singular vectors for spde and
// the TLS family, which do not use them. Their estimates are those from the full reduction.
TEST_F(LargeN, FitReducesOnlyWhatTheMethodUses) {
  const Reduction full = reduce(TriangularFactor::from_data(A_, B_));
  for (Method method : {Method::Spde, Method::TotalLeastSquares, Method::SymmetricProcrustes,
                        Method::LeastSquares}) {
    const FitResult lean = fit(A_, B_, method), reference = fit(full, method);
    ASSERT_TRUE(lean.ok() && reference.ok()) << to_string(method);
    EXPECT_EQ(lean.X, reference.X) << to_string(method);
    EXPECT_EQ(lean.diagnostics.rank_a, reference.diagnostics.rank_a);
    // Singular values alone (dqds) or with their vectors (divide and conquer): equal to rounding.
    const Eigen::VectorXd& s = reference.diagnostics.singular_values_a;
    EXPECT_LE((lean.diagnostics.singular_values_a - s).cwiseAbs().maxCoeff(), 1e3 * kEps * s(0));
  }
}

// The area criterion ||A Y - B Y^-T||_F^2 for X = Y Y^T (Chen & McInroy, Definition II.1), from
// Eigen's eigendecomposition of X: Y = W sqrt(Lambda), Y^-T = W sqrt(Lambda)^-1.
double area_criterion_of(const MatrixXd& A, const MatrixXd& B, const MatrixXd& X) {
  const Eigen::SelfAdjointEigenSolver<MatrixXd> eig(X);
  const MatrixXd& W = eig.eigenvectors();
  const Eigen::VectorXd root = eig.eigenvalues().cwiseSqrt();
  return (A * W * root.asDiagonal() - B * W * root.cwiseInverse().asDiagonal()).squaredNorm();
}

TEST_F(LargeN, DiagnosticsMatchEigenOnTheData) {
  for (Method method : {Method::Spde, Method::SymmetricProcrustes}) {
    const FitResult r = fit(A_, B_, method);
    ASSERT_TRUE(r.ok()) << r.message;
    const Diagnostics& d = r.diagnostics;
    const Eigen::SelfAdjointEigenSolver<MatrixXd> eig(r.X, Eigen::EigenvaluesOnly);
    const double top = eig.eigenvalues()(kN - 1);
    EXPECT_NEAR(*d.min_eigenvalue, eig.eigenvalues()(0), 1e3 * kEps * top) << to_string(method);
    EXPECT_NEAR(*d.max_eigenvalue, top, 1e3 * kEps * top) << to_string(method);
    EXPECT_EQ(d.positive_definite, eig.eigenvalues()(0) > 0.0);
    EXPECT_NEAR(d.residual_norm, (A_ * r.X - B_).norm(), 1e-10 * (A_ * r.X - B_).norm());
    ASSERT_TRUE(d.area_criterion.has_value()) << to_string(method);
    const double f = area_criterion_of(A_, B_, r.X);
    EXPECT_NEAR(*d.area_criterion, f, 1e-9 * f) << to_string(method);
  }
  // Procrustes' A^T B + B^T A test (thesis Theorem 3.2).
  const FitResult r = fit(A_, B_, Method::SymmetricProcrustes);
  const MatrixXd C = A_.transpose() * B_;
  const Eigen::SelfAdjointEigenSolver<MatrixXd> cross(C + C.transpose(), Eigen::EigenvaluesOnly);
  EXPECT_EQ(*r.diagnostics.cross_term_positive_definite, cross.eigenvalues()(0) > 0.0);
}

TEST_F(LargeN, SpdeOfARankDeficientBIsItsSemidefiniteMinimizer) {
  // B of rank 50 < n = 70 (Corollary III.7): X is positive semidefinite of rank 50 and still
  // solves X P X = Q; its area criterion is tr(P X) + tr(X^+ Q) - 2 tr(A^T B).
  test::Generator g(52);
  const MatrixXd B = (A_ * g.spd(kN, 20.0)).leftCols(50) * g.gaussian(50, kN);
  const FitResult r = fit(A_, B, Method::Spde);
  ASSERT_TRUE(r.ok()) << r.message;
  const MatrixXd P = A_.transpose() * A_, Q = B.transpose() * B;
  EXPECT_LE((r.X * P * r.X - Q).norm(), 1e5 * kEps * Q.norm());
  const Eigen::SelfAdjointEigenSolver<MatrixXd> eig(r.X);
  const double top = eig.eigenvalues()(kN - 1);
  EXPECT_LT(eig.eigenvalues()(kN - 51), 1e-8 * top);
  EXPECT_GT(eig.eigenvalues()(kN - 50), 1e-6 * top);
  const MatrixXd X_plus = eig.eigenvectors().rightCols(50) *
                          eig.eigenvalues().tail(50).cwiseInverse().asDiagonal() *
                          eig.eigenvectors().rightCols(50).transpose();
  const double f = (P * r.X).trace() + (X_plus * Q).trace() - 2.0 * (A_.transpose() * B).trace();
  ASSERT_TRUE(r.diagnostics.area_criterion.has_value());
  EXPECT_NEAR(*r.diagnostics.area_criterion, f, 1e-6 * (P * r.X).trace());
}

}  // namespace
}  // namespace spdfit
