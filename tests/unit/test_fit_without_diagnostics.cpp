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

// FitOptions::reported_diagnostics = false (the command line printing X alone) skips the noise
// estimate, the column-scaled condition numbers, the residual and the area criterion: every
// method's X, status, ranks, eigenvalues and other warnings are the same; auto chooses the same
// method (it computes the noise estimate it needs itself).
TEST(FitWithoutReportedDiagnostics, OnlyWhatIsReportedAloneIsLeftOut) {
  test::Generator g(13);
  for (Index n : {2, 6, 12, 80}) {
    const Index m = n + n / 2;  // m - n < n: the noise estimate's thin-data warning
    const MatrixXd A = g.gaussian(m, n);
    const MatrixXd B = A * g.spd(n, 100.0) + 0.5 * g.gaussian(m, n);
    FitOptions lean;
    lean.reported_diagnostics = false;
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
      EXPECT_GT(full.diagnostics.cond_a_scaled, 0.0) << name;
      EXPECT_GT(full.diagnostics.cond_b_scaled, 0.0) << name;
      EXPECT_EQ(without.diagnostics.cond_a_scaled, 0.0) << name;  // well-conditioned: no warning to give
      EXPECT_EQ(without.diagnostics.cond_b_scaled, 0.0) << name;
      EXPECT_EQ(without.diagnostics.cond_a, full.diagnostics.cond_a) << name;
      EXPECT_GT(full.diagnostics.residual_norm, 0.0) << name;
      EXPECT_EQ(without.diagnostics.residual_norm, 0.0) << name;
      EXPECT_FALSE(without.diagnostics.area_criterion.has_value()) << name;
      EXPECT_EQ(without.diagnostics.positive_definite, full.diagnostics.positive_definite) << name;
      EXPECT_EQ(without.diagnostics.area_criterion_minimum, full.diagnostics.area_criterion_minimum) << name;
      if (full.diagnostics.positive_definite) {
        EXPECT_FALSE(without.diagnostics.cross_term_positive_definite.has_value()) << name;
      } else {  // procrustes' warning names it
        EXPECT_EQ(without.diagnostics.cross_term_positive_definite, full.diagnostics.cross_term_positive_definite);
      }
      EXPECT_EQ(without.diagnostics.min_eigenvalue, full.diagnostics.min_eigenvalue) << name;
      EXPECT_EQ(without.diagnostics.chosen_method, full.diagnostics.chosen_method) << name;
      // The warnings are the full run's without the one about the noise estimate.
      std::vector<Warning> expected;
      bool warned = false;
      for (const Warning& w : full.warnings) {
        if (w.text.rfind("the noise estimate (noise_sigma) rests on", 0) == 0) {
          EXPECT_EQ(w.code, Code::NoiseEstimate) << name;
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

// Procrustes' warning about an estimate that is not positive definite names whether A^T B + B^T A
// is: without the reported diagnostics that is computed for the warning, which stays the same.
TEST(FitWithoutReportedDiagnostics, ProcrustesStillSaysWhyItsEstimateIsIndefinite) {
  test::Generator g(15);
  for (Index n : {3, 70}) {
    const MatrixXd A = g.gaussian(2 * n, n);
    Eigen::VectorXd x = Eigen::VectorXd::LinSpaced(n, 2.0, -1.0);  // an indefinite X
    const MatrixXd B = A * x.asDiagonal() + 0.01 * g.gaussian(2 * n, n);
    FitOptions lean;
    lean.reported_diagnostics = false;
    const FitResult full = fit(A, B, Method::SymmetricProcrustes);
    const FitResult without = fit(A, B, Method::SymmetricProcrustes, lean);
    ASSERT_TRUE(full.ok()) << full.message;
    ASSERT_FALSE(full.diagnostics.positive_definite);
    EXPECT_EQ(without.X, full.X);
    EXPECT_EQ(without.warnings, full.warnings);
    ASSERT_TRUE(without.diagnostics.cross_term_positive_definite.has_value());
    EXPECT_EQ(*without.diagnostics.cross_term_positive_definite, *full.diagnostics.cross_term_positive_definite);
  }
}

// An ill-conditioned A keeps its warning, with the same condition number, without the data's
// diagnostics: cond(A D) is computed wherever its bound may pass the warning's threshold.
TEST(FitWithoutReportedDiagnostics, AnIllConditionedAIsStillWarnedAbout) {
  test::Generator g(14);
  for (const double cond : {1e9, 1e11, 1e13}) {
    const Index m = 40, n = 6;
    const MatrixXd U = g.orthonormal(m, n), V = g.orthonormal(n, n);
    Eigen::VectorXd s(n);
    for (Index k = 0; k < n; ++k) s(k) = std::pow(cond, -static_cast<double>(k) / (n - 1));
    MatrixXd A = U * s.asDiagonal() * V.transpose();
    A.col(2) *= 4.0;  // columns in different units: the bound and the scaled value differ
    const MatrixXd B = A * g.spd(n, 10.0);
    // A rank cut-off below 1e-12, so that the rank alone does not call for cond(A D).
    FitOptions options;
    options.rank_tolerance = 1e-17;
    FitOptions lean = options;
    lean.reported_diagnostics = false;
    const FitResult full = fit(A, B, Method::Spde, options);
    const FitResult without = fit(A, B, Method::Spde, lean);
    ASSERT_EQ(without.status, full.status) << cond;
    EXPECT_EQ(without.X, full.X) << cond;
    EXPECT_EQ(without.warnings, full.warnings) << cond;
    const bool warned = full.diagnostics.cond_a_scaled > 1e12;
    EXPECT_EQ(warned, cond > 1e12) << cond;
    if (warned) {
      EXPECT_EQ(without.diagnostics.cond_a_scaled, full.diagnostics.cond_a_scaled) << cond;
    }
  }
}

}  // namespace
}  // namespace spdfit
