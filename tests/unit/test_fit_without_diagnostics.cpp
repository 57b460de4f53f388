// FitOptions::diagnostics = false (the Monte Carlo experiments' inner loop) gives the same
// estimate, bit for bit, and the same failures; it only leaves the estimate's diagnostics out.
#include <gtest/gtest.h>

#include "spdfit/fit.hpp"
#include "test_support.hpp"

namespace spdfit {
namespace {

FitOptions without_diagnostics() {
  FitOptions options;
  options.diagnostics = false;
  return options;
}

TEST(FitWithoutDiagnostics, EveryMethodGivesTheSameEstimate) {
  test::Generator g(11);
  for (Index n : {1, 2, 6, 12}) {
    const MatrixXd A = g.gaussian(2 * n + 3, n);
    const MatrixXd B = A * g.spd(n, 100.0) + 0.5 * g.gaussian(2 * n + 3, n);
    const std::vector<FitResult> full = fit_all(A, B);
    const std::vector<FitResult> lean = fit_all(A, B, without_diagnostics());
    ASSERT_EQ(full.size(), lean.size());
    for (std::size_t k = 0; k < full.size(); ++k) {
      EXPECT_EQ(lean[k].status, full[k].status) << to_string(full[k].method);
      EXPECT_EQ(lean[k].X, full[k].X) << to_string(full[k].method) << ", n = " << n;
      EXPECT_EQ(lean[k].diagnostics.rank_a, full[k].diagnostics.rank_a);
      EXPECT_EQ(lean[k].diagnostics.m, 2 * n + 3);
      EXPECT_FALSE(lean[k].diagnostics.min_eigenvalue.has_value());
      EXPECT_FALSE(lean[k].diagnostics.area_criterion.has_value());
    }
  }
}

TEST(FitWithoutDiagnostics, FailuresAreStillReported) {
  test::Generator g(12);
  MatrixXd A = g.gaussian(10, 3);
  A.col(2) = A.col(0);  // rank-deficient: spde has no minimizer
  const MatrixXd B = g.gaussian(10, 3);
  const FitResult lean = fit(A, B, Method::Spde, without_diagnostics());
  const FitResult full = fit(A, B, Method::Spde);
  EXPECT_FALSE(lean.ok());
  EXPECT_EQ(lean.message, full.message);
}

}  // namespace
}  // namespace spdfit
