// The large-n path: from 64 columns of [A B] the QR, and above n = 64 the SVDs, run on LAPACK
// (dgeqrf, dgesdd) when spdfit is built with SPDFIT_LAPACK, else on Eigen's HouseholderQR and
// BDCSVD. Checked against the estimators' defining equations and, for TLS, against Eigen's own
// SVD of [A B].
#include <gtest/gtest.h>

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

}  // namespace
}  // namespace spdfit
