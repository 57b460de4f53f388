// Least squares at the accuracy the data allow (issue 17; numerics/least_squares.hpp): the rank
// does not depend on the units of the unknowns, a power-of-two change of units changes the
// solution by exactly the inverse factor, and refinement with compensated residuals reaches
// about eps where plain solves stop at cond eps.
#include <gtest/gtest.h>

#include <cmath>

#include "numerics/least_squares.hpp"
#include "spdfit/fit.hpp"
#include "spdfit/linear_system.hpp"
#include "test_support.hpp"

namespace spdfit {
namespace {

using test::Generator;
using test::kEps;

// A well-conditioned core with columns spread over 1e-12..1e12: the unscaled condition number
// is about 1e24, the scaled one that of the core.
MatrixXd graded(Generator& g, Index m, Index n, double core_condition) {
  const VectorXd spread = Generator::log_spaced(n, 1e24) * 1e12;
  return g.with_condition(m, n, core_condition) * spread.asDiagonal();
}

TEST(CertifiedAccuracy, ColumnExponentsPutNormsInHalfOpenUnitInterval) {
  MatrixXd A(2, 3);
  A << 3.0, 0.0, 1e-300, 4.0, 0.0, 0.0;  // norms 5, 0 and 1e-300
  const Eigen::VectorXi e = detail::column_exponents(A);
  EXPECT_EQ(e(0), 3);  // 5 / 8 = 0.625
  EXPECT_EQ(e(1), 0);  // a zero column stays as it is
  const double scaled = std::ldexp(1e-300, -e(2));
  EXPECT_GE(scaled, 0.5);
  EXPECT_LT(scaled, 1.0);
}

// Dot2's residual is the exactly rounded b - A x where plain arithmetic loses everything.
TEST(CertifiedAccuracy, AccurateResidualSurvivesCancellation) {
  MatrixXd A(1, 3);
  A << 1e16, 1.0, -1e16;
  const MatrixXd x = MatrixXd::Ones(3, 1);
  const MatrixXd b = MatrixXd::Zero(1, 1);
  EXPECT_EQ(detail::accurate_residual(A, x, b)(0, 0), -1.0);
  // 1 + 2^-52 squared is 1 + 2^-51 + 2^-104: the last term is lost in double, not here.
  const double t = 1.0 + kEps;
  MatrixXd a(1, 1), y(1, 1), c(1, 1);
  a << t;
  y << t;
  c << 1.0 + 2.0 * kEps;
  EXPECT_EQ(detail::accurate_residual(a, y, c)(0, 0), -std::ldexp(1.0, -104));
}

// The rank is a property of the problem, not of the units: columns of very different size are
// no reason to call A singular, and every column scaling gives the same rank.
TEST(CertifiedAccuracy, RankDoesNotDependOnColumnUnits) {
  Generator g(1701);
  for (int trial = 0; trial < 10; ++trial) {
    const Index n = 2 + trial % 6, m = n + 3 + trial;
    const MatrixXd A = graded(g, m, n, 1e3);
    const MatrixXd b = g.gaussian(m, 1);
    const LinearSystemResult r = solve(A, b);
    EXPECT_EQ(r.rank, n) << "trial " << trial;
    EXPECT_GT(r.condition_number, 1e20);
    EXPECT_LT(r.scaled_condition_number, 1e5);
    // fit's reduction decides rank_a the same way.
    EXPECT_EQ(fit(A, g.gaussian(m, n), Method::LeastSquares).diagnostics.rank_a, n);
  }
}

// Scaling column j of A by 2^k (a change of units of unknown j) scales x_j by exactly 2^-k and
// leaves every other entry bit for bit the same: solve works in the scaled unknowns throughout.
TEST(CertifiedAccuracy, PowerOfTwoColumnScalingIsExact) {
  Generator g(1702);
  for (int trial = 0; trial < 20; ++trial) {
    const Index n = 1 + trial % 7, m = n + 1 + trial % 5;
    const MatrixXd A = trial % 2 ? graded(g, m, n, 1e6) : g.with_condition(m, n, 1e4);
    const MatrixXd b = g.gaussian(m, 2);
    const MatrixXd x = solve(A, b).solution;
    const Index j = trial % n;
    const int k = (trial % 3 - 1) * (1 + 37 * trial);  // down, none and up, by up to 2^700
    MatrixXd As = A;
    As.col(j) *= std::ldexp(1.0, k);
    const MatrixXd xs = solve(As, b).solution;
    for (Index i = 0; i < n; ++i) {
      for (Index c = 0; c < 2; ++c) {
        EXPECT_EQ(xs(i, c), i == j ? std::ldexp(x(i, c), -k) : x(i, c)) << "trial " << trial << " entry " << i;
      }
    }
  }
}

// fit --method ls from the triangular factor: back substitution in R11 X = R12 after a
// Householder QR, both exact under a power-of-two scaling of a column.
TEST(CertifiedAccuracy, PowerOfTwoColumnScalingIsExactForFitLs) {
  Generator g(1703);
  for (int trial = 0; trial < 10; ++trial) {
    const Index n = 2 + trial % 5, m = 3 * n;
    const MatrixXd A = g.with_condition(m, n, 1e3);
    const MatrixXd B = g.gaussian(m, n);
    const MatrixXd X = fit(A, B, Method::LeastSquares).X;
    const Index j = trial % n;
    const int k = trial % 2 ? 40 : -33;
    MatrixXd As = A;
    As.col(j) *= std::ldexp(1.0, k);
    MatrixXd expected = X;
    expected.row(j) *= std::ldexp(1.0, -k);
    EXPECT_EQ(fit(As, B, Method::LeastSquares).X, expected) << "trial " << trial;
  }
}

// Other factors change the data by rounding only, so the solution moves by about cond(A D)
// times that, in the scaled unknowns.
TEST(CertifiedAccuracy, OtherColumnScalingsChangeTheSolutionToRounding) {
  Generator g(1704);
  for (int trial = 0; trial < 20; ++trial) {
    const Index n = 2 + trial % 6, m = n + 4;
    const MatrixXd A = graded(g, m, n, 1e4);
    const MatrixXd b = g.gaussian(m, 1);
    const LinearSystemResult r = solve(A, b);
    VectorXd factors(n);  // e^-6 .. e^6 per column
    for (Index i = 0; i < n; ++i) factors(i) = std::exp(g.uniform(-6.0, 6.0));
    const MatrixXd As = A * factors.asDiagonal();
    const VectorXd xs = solve(As, b).solution.col(0);
    // Back to A's unknowns, and compared in the unknowns of unit-norm columns.
    const VectorXd norms = A.colwise().norm().transpose();
    const VectorXd y = r.solution.col(0).cwiseProduct(norms);
    const VectorXd ys = xs.cwiseProduct(factors).cwiseProduct(norms);
    EXPECT_LE((ys - y).norm(), 16.0 * n * kEps * r.scaled_condition_number * y.norm()) << "trial " << trial;
  }
}

// A polynomial fit through exact data: x = 1..20, columns x^0..x^10 (every entry an integer
// below 2^53, so A and b are exact) and integer coefficients. Unscaled, A's condition number is
// about 1e16 and an unscaled rank rule calls it singular; with unit-norm columns it is about 1e10,
// and refinement brings the coefficients to nearly full precision where one solve gives
// cond eps.
TEST(CertifiedAccuracy, ExactPolynomialDataGiveExactCoefficients) {
  const Index m = 20, n = 11;
  MatrixXd A(m, n);
  VectorXd b(m);
  VectorXd c(n);
  c << 3, -2, 5, 1, -4, 2, -1, 1, -1, 1, 1;
  for (Index i = 0; i < m; ++i) {
    const double x = static_cast<double>(i + 1);
    double power = 1.0;
    for (Index k = 0; k < n; ++k, power *= x) A(i, k) = power;
  }
  b = A * c;  // every partial sum is an integer below 2^53: exact
  ASSERT_LT(b.cwiseAbs().maxCoeff(), std::ldexp(1.0, 53));
  const LinearSystemResult r = solve(A, b);
  EXPECT_EQ(r.rank, n);
  EXPECT_GT(r.condition_number, 1e14);
  EXPECT_GT(r.refinement_steps, 0);
  const VectorXd x = r.solution.col(0);
  for (Index k = 0; k < n; ++k) {
    // LRE >= 10 on every coefficient; a single solve reaches about 16 - log10(cond(A D)) ~ 6.
    EXPECT_LE(std::abs(x(k) - c(k)), 1e-10 * std::abs(c(k))) << "coefficient " << k;
  }
}

}  // namespace
}  // namespace spdfit
