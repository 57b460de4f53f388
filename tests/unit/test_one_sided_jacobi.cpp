// The one-sided Jacobi SVD behind detail::svd: a valid SVD, sorted, and accurate for the small
// singular values of graded matrices, checked against divide and conquer in long double.
#include <gtest/gtest.h>

#include <Eigen/SVD>

#include "numerics/linalg.hpp"
#include "test_support.hpp"

namespace spdfit {
namespace {

using test::Generator;
using test::kEps;

TEST(OneSidedJacobi, IsAnOrthogonalFactorizationWithSortedSingularValues) {
  Generator g(91);
  for (Index n : {1, 2, 5, 12, 40}) {
    const MatrixXd A = g.gaussian(n + 3, n);
    const detail::Svd d = detail::svd(A);
    EXPECT_LT((d.U * d.s.asDiagonal() * d.V.transpose() - A).norm(), 50 * n * kEps * A.norm()) << n;
    EXPECT_LT((d.U.transpose() * d.U - MatrixXd::Identity(n, n)).norm(), 50 * n * kEps);
    EXPECT_LT((d.V.transpose() * d.V - MatrixXd::Identity(n, n)).norm(), 50 * n * kEps);
    for (Index i = 1; i < n; ++i) EXPECT_GE(d.s(i - 1), d.s(i));
  }
}

TEST(OneSidedJacobi, SmallSingularValuesOfGradedMatricesAreRelativelyAccurate) {
  // A = B D with B well-conditioned and D graded over 1e12: one-sided Jacobi's singular values
  // are accurate to a modest multiple of eps relative to each, however small (Demmel-Veselic).
  Generator g(92);
  using MatrixL = Eigen::Matrix<long double, Eigen::Dynamic, Eigen::Dynamic>;
  for (int trial = 0; trial < 10; ++trial) {
    const MatrixXd A = g.gaussian(8, 8) * Generator::log_spaced(8, 1e12).asDiagonal();
    const detail::Svd d = detail::svd(A, false, false);
    Eigen::BDCSVD<MatrixL> reference(A.cast<long double>());
    for (Index i = 0; i < 8; ++i) {
      const double exact = static_cast<double>(reference.singularValues()(i));
      EXPECT_NEAR(d.s(i), exact, 1e-12 * exact) << "trial " << trial << " sigma_" << i;
    }
  }
}

TEST(OneSidedJacobi, ZeroColumnsGiveZeroSingularValues) {
  MatrixXd A = MatrixXd::Zero(4, 3);
  A(0, 0) = 2.0;
  const detail::Svd d = detail::svd(A);
  EXPECT_EQ(d.s(0), 2.0);
  EXPECT_EQ(d.s(1), 0.0);
  EXPECT_EQ(d.s(2), 0.0);
  EXPECT_TRUE(d.U.allFinite());
}

}  // namespace
}  // namespace spdfit
