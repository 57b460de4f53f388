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

// FitOptions::noise_estimate = false (the command line printing X alone) skips only the noise
// estimate: every method's X, status, ranks, diagnostics and other warnings are the same; auto
// chooses the same method (it computes the estimate it needs itself).
TEST(FitWithoutNoiseEstimate, OnlyTheNoiseEstimateAndItsWarningAreLeftOut) {
  test::Generator g(13);
  for (Index n : {2, 6, 12, 80}) {
    const Index m = n + n / 2;  // m - n < n: the noise estimate's thin-data warning
    const MatrixXd A = g.gaussian(m, n);
    const MatrixXd B = A * g.spd(n, 100.0) + 0.5 * g.gaussian(m, n);
    FitOptions lean;
    lean.noise_estimate = false;
    for (Method method : {Method::LeastSquares, Method::SymmetricProcrustes, Method::TotalLeastSquares,
                          Method::Spde, Method::SpdTotalLeastSquares, Method::Auto}) {
      // The iterative methods at n = 80 take seconds: the small sizes cover them.
      if (n > 12 && (method == Method::SpdTotalLeastSquares || method == Method::Auto)) continue;
      const FitResult full = fit(A, B, method);
      const FitResult without = fit(A, B, method, lean);
      const std::string name = std::string(to_string(method)) + ", n = " + std::to_string(n);
      ASSERT_TRUE(full.ok()) << name << ": " << full.message;
      EXPECT_EQ(without.status, full.status) << name;
      EXPECT_EQ(without.X, full.X) << name;
      EXPECT_TRUE(full.diagnostics.noise_sigma.has_value()) << name;
      EXPECT_FALSE(without.diagnostics.noise_sigma.has_value()) << name;
      EXPECT_EQ(without.diagnostics.rank_a, full.diagnostics.rank_a) << name;
      EXPECT_EQ(without.diagnostics.cond_a_scaled, full.diagnostics.cond_a_scaled) << name;
      EXPECT_EQ(without.diagnostics.min_eigenvalue, full.diagnostics.min_eigenvalue) << name;
      EXPECT_EQ(without.diagnostics.chosen_method, full.diagnostics.chosen_method) << name;
      // The warnings are the full run's without the one about the noise estimate.
      std::vector<std::string> expected;
      bool warned = false;
      for (const std::string& w : full.warnings) {
        if (w.rfind("the noise estimate (noise_sigma) rests on", 0) == 0) {
          warned = true;
        } else {
          expected.push_back(w);
        }
      }
      EXPECT_TRUE(warned) << name;
      EXPECT_EQ(without.warnings, expected) << name;
    }
  }
}

}  // namespace
}  // namespace spdfit
