// The noise estimate (Diagnostics::noise_sigma) costs an SVD of the whole (n + d) x (n + d) factor:
// a fit computes it when it is first read, once for all copies of the result and every method
// fitted from the same Reduction, and the TLS family take it from their own SVD. The value read
// late is the one computed at once, to the last bit.
#include <gtest/gtest.h>

#include <Eigen/SVD>
#include <cmath>
#include <thread>
#include <vector>

#include "factor/reduce.hpp"
#include "numerics/least_squares.hpp"
#include "spdfit/fit.hpp"
#include "spdfit/render.hpp"
#include "test_support.hpp"

namespace spdfit {
namespace {

// The TLS family's noise estimate comes from an SVD with right singular vectors, the others' from
// a values-only SVD of the same matrix: both backward stable, so the trailing singular values
// agree to a few units of eps * sigma_max. Here sigma_max / sigma_{n+1} is below 1e3, so relative
// agreement of 1e-10 leaves a margin of about 1e3 over rounding.
constexpr double kTwoSvdsAgree = 1e-10;

struct Data {
  MatrixXd A, B;
};

// m x n data with noise of standard deviation 0.3 in A and B.
Data noisy(Index m, Index n, unsigned seed) {
  test::Generator g(seed);
  const MatrixXd A0 = g.gaussian(m, n);
  const MatrixXd X = g.spd(n, 10.0);
  return {A0 + 0.3 * g.gaussian(m, n), A0 * X + 0.3 * g.gaussian(m, n)};
}

// The noise estimate computed directly (noise_variance on the reduced data), not through a fit.
double eager_noise_sigma(const Reduction& reduction) {
  return std::sqrt(*detail::noise_variance(detail::data_of(reduction)));
}

// n = 5 (one-sided Jacobi SVD of the 10 x 10 factor) and n = 70 (LAPACK's, 140 x 140).
class LazyNoiseEstimate : public ::testing::TestWithParam<Index> {};

TEST_P(LazyNoiseEstimate, NotComputedUntilReadThenOnceForEveryCopy) {
  const Index n = GetParam();
  const Data data = noisy(4 * n, n, 3);
  for (Method method : {Method::Spde, Method::SymmetricProcrustes, Method::LeastSquares}) {
    const std::uint64_t before = detail::noise_variance_runs();
    const FitResult result = fit(data.A, data.B, method);
    ASSERT_EQ(result.status, Status::Success);
    EXPECT_EQ(detail::noise_variance_runs(), before) << to_string(method) << ": computed by the fit";
    EXPECT_TRUE(result.diagnostics.noise_sigma.pending());
    const FitResult copy = result;
    const double sigma = result.diagnostics.noise_sigma.value();
    EXPECT_EQ(detail::noise_variance_runs(), before + 1);
    EXPECT_FALSE(result.diagnostics.noise_sigma.pending());
    EXPECT_FALSE(copy.diagnostics.noise_sigma.pending());
    EXPECT_EQ(*copy.diagnostics.noise_sigma, sigma);  // the copy shares the one computation
    EXPECT_EQ(detail::noise_variance_runs(), before + 1);
  }
}

TEST_P(LazyNoiseEstimate, ReadLateEqualsComputedAtOnceToTheLastBit) {
  const Index n = GetParam();
  const Data data = noisy(4 * n, n, 4);
  const Reduction reduction = reduce(TriangularFactor::from_data(data.A, data.B));
  const double eager = eager_noise_sigma(reduction);
  const FitResult early = fit(data.A, data.B, Method::Spde);
  const double read_early = *early.diagnostics.noise_sigma;
  const FitResult late = fit(data.A, data.B, Method::Spde);
  const FitResult other = fit(data.A, data.B, Method::SymmetricProcrustes);
  (void)fit(data.A, data.B, Method::LeastSquares);  // work in between
  EXPECT_EQ(read_early, eager);
  EXPECT_EQ(*late.diagnostics.noise_sigma, eager);
  EXPECT_EQ(*other.diagnostics.noise_sigma, eager);
  // The rendering computes it as well, with the same digits.
  EXPECT_EQ(to_json(fit(data.A, data.B, Method::Spde)), to_json(early));
  // The estimate itself against its definition: the d smallest singular values of [A B].
  MatrixXd AB(data.A.rows(), 2 * n);
  AB << data.A, data.B;
  const VectorXd s = Eigen::JacobiSVD<MatrixXd>(AB).singularValues();
  const double tail = s.tail(n).norm();
  EXPECT_NEAR(eager, tail / std::sqrt(static_cast<double>(n * (4 * n - n))), kTwoSvdsAgree * eager);
}

TEST_P(LazyNoiseEstimate, OnceForEveryMethodFittedFromOneReduction) {
  const Index n = GetParam();
  const Data data = noisy(4 * n, n, 5);
  const Reduction reduction = reduce(TriangularFactor::from_data(data.A, data.B));
  const std::uint64_t before = detail::noise_variance_runs();
  std::vector<FitResult> results;
  for (Method method : {Method::Spde, Method::SymmetricProcrustes, Method::LeastSquares}) {
    results.push_back(fit(reduction, method));
  }
  for (const FitResult& r : results) EXPECT_TRUE(r.diagnostics.noise_sigma.has_value());
  EXPECT_EQ(detail::noise_variance_runs(), before + 1);
  for (const FitResult& r : results) EXPECT_EQ(*r.diagnostics.noise_sigma, *results[0].diagnostics.noise_sigma);
}

TEST_P(LazyNoiseEstimate, TotalLeastSquaresTakesItFromItsOwnSvd) {
  const Index n = GetParam();
  const Data data = noisy(4 * n, n, 6);
  const Reduction reduction = reduce(TriangularFactor::from_data(data.A, data.B));
  const double values_only = eager_noise_sigma(reduction);
  for (Method method :
       {Method::TotalLeastSquares, Method::TotalLeastSquaresSymmetric, Method::TotalLeastSquaresPsd}) {
    const std::uint64_t before = detail::noise_variance_runs();
    const FitResult result = fit(data.A, data.B, method);
    ASSERT_EQ(result.status, Status::Success);
    EXPECT_FALSE(result.diagnostics.noise_sigma.pending()) << to_string(method);
    ASSERT_TRUE(result.diagnostics.noise_sigma.has_value());
    EXPECT_EQ(detail::noise_variance_runs(), before) << to_string(method) << ": a second SVD";
    if (n <= 32) {
      // The one-sided Jacobi SVD's values do not depend on whether it accumulates vectors.
      EXPECT_EQ(*result.diagnostics.noise_sigma, values_only);
    } else {
      EXPECT_NEAR(*result.diagnostics.noise_sigma, values_only, kTwoSvdsAgree * values_only);
    }
  }
}

TEST_P(LazyNoiseEstimate, ReadFromTwoThreadsAtOnce) {
  const Index n = GetParam();
  const Data data = noisy(4 * n, n, 7);
  const FitResult result = fit(data.A, data.B, Method::Spde);
  const FitResult copy = result;
  const std::uint64_t before = detail::noise_variance_runs();
  double first = 0.0, second = 0.0;
  std::thread one([&] { first = *result.diagnostics.noise_sigma; });
  std::thread two([&] { second = *copy.diagnostics.noise_sigma; });
  one.join();
  two.join();
  EXPECT_EQ(first, second);
  EXPECT_EQ(detail::noise_variance_runs(), before + 1);
}

TEST_P(LazyNoiseEstimate, ScaledConditionNumbersReadLateAsTheRankWouldComputeThem) {
  const Index n = GetParam();
  const Data data = noisy(4 * n, n, 11);
  const FitResult result = fit(data.A, data.B, Method::Spde);
  // Well-conditioned data: the ranks did not need the scaled SVDs, so the fit left them unread.
  EXPECT_TRUE(result.diagnostics.cond_a_scaled.pending());
  EXPECT_TRUE(result.diagnostics.cond_b_scaled.pending());
  // What reduce_into computes when asked for cond(A D) at once (report_above = 0).
  const Reduction reduction = reduce(TriangularFactor::from_data(data.A, data.B));
  const detail::DynamicReduction& reduced = detail::data_of(reduction);
  double eager_a = 0.0, eager_b = 0.0;
  detail::equilibrated_rank(reduced.R11, reduced.s_a, 1e-15, &eager_a, 0.0);
  detail::equilibrated_rank(reduced.R_b, reduced.s_b, 1e-15, &eager_b, 0.0);
  EXPECT_EQ(result.diagnostics.cond_a_scaled.get(), eager_a);
  EXPECT_EQ(result.diagnostics.cond_b_scaled.get(), eager_b);
  EXPECT_FALSE(result.diagnostics.cond_a_scaled.pending());
  EXPECT_GE(eager_a, 1.0);
}

INSTANTIATE_TEST_SUITE_P(SmallAndLapackSvd, LazyNoiseEstimate, ::testing::Values(Index{5}, Index{70}));

TEST(LazyNoiseEstimateRules, NothingWithoutReportedDiagnosticsNorWithoutSpareRows) {
  const Data data = noisy(40, 10, 8);
  FitOptions lean;
  lean.reported_diagnostics = false;
  const std::uint64_t before = detail::noise_variance_runs();
  const FitResult result = fit(data.A, data.B, Method::Spde, lean);
  EXPECT_FALSE(result.diagnostics.noise_sigma.pending());
  EXPECT_FALSE(result.diagnostics.noise_sigma.has_value());
  const Data square = noisy(10, 10, 9);  // m = n: no rows for a noise estimate
  const FitResult exact = fit(square.A, square.B, Method::Spde);
  EXPECT_FALSE(exact.diagnostics.noise_sigma.pending());
  EXPECT_FALSE(exact.diagnostics.noise_sigma.has_value());
  EXPECT_EQ(detail::noise_variance_runs(), before);
}

TEST(LazyNoiseEstimateRules, AutoComputesItOnceForItsChoiceAndTheResult) {
  const Data data = noisy(40, 10, 10);
  const std::uint64_t before = detail::noise_variance_runs();
  const FitResult result = fit(data.A, data.B, Method::Auto);
  ASSERT_EQ(result.status, Status::Success);
  EXPECT_EQ(detail::noise_variance_runs(), before + 1);  // auto chooses by it
  EXPECT_TRUE(result.diagnostics.noise_sigma.has_value());
  EXPECT_EQ(detail::noise_variance_runs(), before + 1);
}

TEST(LazyOptionalValue, ReadsAsAnOptional) {
  LazyOptional empty;
  EXPECT_FALSE(empty.has_value());
  EXPECT_FALSE(empty.pending());
  LazyOptional plain = 2.5;
  EXPECT_EQ(*plain, 2.5);
  int calls = 0;
  const LazyOptional deferred = LazyOptional::deferred([&calls]() -> std::optional<double> {
    ++calls;
    return 1.25;
  });
  EXPECT_TRUE(deferred.pending());
  EXPECT_EQ(calls, 0);
  const std::optional<double> as_optional = deferred;
  EXPECT_EQ(as_optional, std::optional<double>(1.25));
  EXPECT_EQ(deferred.value_or(0.0), 1.25);
  EXPECT_EQ(calls, 1);
  const LazyOptional nothing = LazyOptional::deferred([]() -> std::optional<double> { return std::nullopt; });
  EXPECT_FALSE(nothing);
  EXPECT_THROW((void)nothing.value(), std::bad_optional_access);
}

}  // namespace
}  // namespace spdfit
