// experiment::estimate, the experiments' inner loop: for n <= 8 it runs on stack matrices
// (src/estimators/small_problem.cpp), chunking the QR when m > 4n, and must give fit()'s estimates to
// rounding, the same failures and the same rejections; above n = 8 it is fit() itself.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <stdexcept>
#include <vector>

#include "spdfit/experiment/monte_carlo.hpp"
#include "spdfit/fit.hpp"
#include "test_support.hpp"

namespace spdfit {
namespace {

const std::vector<Method> kMethods(kAllMethods.begin(), kAllMethods.end());

// Every method through estimate() against fit_all() on the same data.
void expect_same_as_fit(const MatrixXd& A, const MatrixXd& B, const std::string& what) {
  std::vector<MatrixXd> X;
  experiment::estimate(A, B, kMethods, X);
  const std::vector<FitResult> fits = fit_all(A, B);
  ASSERT_EQ(X.size(), fits.size()) << what;
  for (std::size_t i = 0; i < fits.size(); ++i) {
    const std::string label = what + ", " + std::string(to_string(fits[i].method));
    ASSERT_EQ(X[i].size() > 0, fits[i].ok()) << label;
    if (!fits[i].ok()) continue;
    ASSERT_EQ(X[i].rows(), fits[i].X.rows()) << label;
    const double scale = fits[i].X.cwiseAbs().maxCoeff();
    EXPECT_LE((X[i] - fits[i].X).cwiseAbs().maxCoeff(), 1e-11 * scale) << label;
  }
}

TEST(Estimate, GivesFitsEstimatesToRounding) {
  test::Generator g(41);
  // n up to 8 is the stack path (2 and 8 are its two bounds), 9 the dynamic one; m > 4n factors
  // the data in chunks.
  for (Index n : {1, 2, 3, 6, 8, 9}) {
    for (Index m : {n, 2 * n + 1, 4 * n, 10 * n + 3}) {
      const MatrixXd A = g.gaussian(m, n);
      const MatrixXd B = A * g.spd(n, 30.0) + 0.1 * g.gaussian(m, n);
      expect_same_as_fit(A, B, "n = " + std::to_string(n) + ", m = " + std::to_string(m));
    }
  }
}

TEST(Estimate, EachMethodAloneGivesTheBitsOfAllTogether) {
  // Alone, a method that does not use R11's singular vectors (spde, the TLS family, spd-tls) runs
  // on a reduction without them; the estimate must not change by a bit, on the stack path too.
  test::Generator g(44);
  for (Index n : {2, 6, 9}) {
    const MatrixXd A = g.gaussian(5 * n, n);
    const MatrixXd B = A * g.spd(n, 30.0) + 0.1 * g.gaussian(5 * n, n);
    std::vector<MatrixXd> together;
    experiment::estimate(A, B, kMethods, together);
    for (std::size_t i = 0; i < kMethods.size(); ++i) {
      std::vector<MatrixXd> alone;
      experiment::estimate(A, B, {kMethods[i]}, alone);
      ASSERT_EQ(alone.size(), 1u);
      EXPECT_TRUE(alone[0].size() == together[i].size() && alone[0] == together[i])
          << "n = " << n << ", " << to_string(kMethods[i]);
    }
  }
}

TEST(Estimate, ScalesAcrossTheDoubleRangeLikeFit) {
  // Exponents beyond +-1022 take the entry-by-entry scaling (denormal data).
  test::Generator g(42);
  for (double scale_a : {1e-310, 1e-150, 1e150}) {
    const MatrixXd A = g.gaussian(20, 3);
    const MatrixXd B = A * g.spd(3, 10.0) + 0.1 * g.gaussian(20, 3);
    expect_same_as_fit(A * scale_a, B, "A scaled by " + std::to_string(scale_a));
  }
}

TEST(Estimate, FailsWhereFitFails) {
  test::Generator g(43);
  MatrixXd A = g.gaussian(30, 4);
  A.col(3) = A.col(1);  // rank-deficient A: spde has no minimizer
  const MatrixXd B = g.gaussian(30, 4);
  std::vector<MatrixXd> X;
  experiment::estimate(A, B, {Method::Spde, Method::LeastSquares}, X);
  ASSERT_EQ(X.size(), 2u);
  EXPECT_EQ(X[0].size(), 0);
  EXPECT_FALSE(fit(A, B, Method::Spde).ok());
  expect_same_as_fit(A, B, "rank-deficient A");
}

TEST(Estimate, RejectsWhatFitRejects) {
  std::vector<MatrixXd> X;
  const std::vector<Method> spde = {Method::Spde};
  const MatrixXd A = MatrixXd::Ones(5, 2);
  EXPECT_THROW(experiment::estimate(A, MatrixXd::Ones(5, 3), spde, X), std::invalid_argument);
  EXPECT_THROW(experiment::estimate(MatrixXd::Ones(1, 2), MatrixXd::Ones(1, 2), spde, X),
               std::invalid_argument);
  MatrixXd bad = A;
  bad(2, 1) = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(experiment::estimate(A, bad, spde, X), std::invalid_argument);
  EXPECT_THROW(experiment::estimate(MatrixXd(5, 0), MatrixXd(5, 0), spde, X), std::invalid_argument);
}

}  // namespace
}  // namespace spdfit
