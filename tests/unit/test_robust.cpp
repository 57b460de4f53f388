// The robust fit's constants and weights (robust/m_estimator.hpp) against their published values,
// and the row scores (pipeline/row_scores.hpp) against a direct computation.
#include <gtest/gtest.h>

#include <Eigen/LU>
#include <Eigen/QR>

#include <cmath>
#include <cstring>

#include "pipeline/row_scores.hpp"
#include "robust/m_estimator.hpp"
#include "spdfit/fit.hpp"
#include "test_support.hpp"

namespace spdfit {
namespace {

using test::Generator;

TEST(Robust, TuningConstantsAreTheTextbooksForOneColumn) {
  // 95% efficiency at the normal distribution: Huber's k = 1.345, Tukey's c = 4.685 (Holland and
  // Welsch 1977; Beaton and Tukey 1974), to the 3-4 digits they are quoted with.
  EXPECT_NEAR(detail::robust_tuning(RobustLoss::Huber, 1), 1.345, 1e-3);
  EXPECT_NEAR(detail::robust_tuning(RobustLoss::Tukey, 1), 4.685, 1e-3);
  // The chi median with 1 degree of freedom is the normal's 0.6745 (the MAD's constant).
  EXPECT_NEAR(detail::chi_median(1), 0.6744897501960817, 1e-8);
  // More columns: larger constants (a row's norm grows like sqrt(d)).
  EXPECT_GT(detail::robust_tuning(RobustLoss::Huber, 6), detail::robust_tuning(RobustLoss::Huber, 3));
  EXPECT_GT(detail::robust_tuning(RobustLoss::Tukey, 6), detail::robust_tuning(RobustLoss::Tukey, 3));
}

TEST(Robust, MedianNearAGuessIsTheMedianToTheBit) {
  // Odd and even counts, with and without counts of 0, guesses inside the middle (the bracketed
  // selection), beside it (the middle ranks outside the bracket: the full selection), and none.
  Generator gen(11);
  std::vector<double> buffer;
  for (const Eigen::Index m : {1, 2, 3, 10, 1001, 1000, 20000}) {
    Eigen::VectorXd u(m);
    for (Eigen::Index i = 0; i < m; ++i) u(i) = std::abs(gen.normal()) + std::abs(gen.normal());
    Eigen::VectorXd counts(m);
    for (Eigen::Index i = 0; i < m; ++i) counts(i) = i % 3 == 0 ? 0.0 : 1.0 + (i % 2);
    for (const bool with_counts : {false, true}) {
      std::vector<double> kept;
      for (Eigen::Index i = 0; i < m; ++i) {
        if (!with_counts || counts(i) > 0) kept.push_back(u(i));
      }
      const Eigen::VectorXd none;
      const Eigen::VectorXd& c = with_counts ? counts : none;
      if (kept.empty()) {
        EXPECT_TRUE(std::isnan(detail::median_near(u, c, 1.0, buffer)));
        continue;
      }
      const double exact = detail::median(kept);
      for (const double guess : {exact, exact * 1.03, exact * 0.95, exact * 3.0, exact / 3.0, 0.0, -1.0}) {
        EXPECT_EQ(detail::median_near(u, c, guess, buffer), exact) << "m = " << m << ", guess " << guess;
      }
    }
  }
}

TEST(Robust, WeightsFollowTheirLosses) {
  EXPECT_EQ(detail::robust_weight(RobustLoss::Huber, 1.0, 1.345), 1.0);
  EXPECT_DOUBLE_EQ(detail::robust_weight(RobustLoss::Huber, 2.69, 1.345), 0.5);
  EXPECT_DOUBLE_EQ(detail::robust_weight(RobustLoss::Tukey, 0.0, 4.685), 1.0);
  EXPECT_EQ(detail::robust_weight(RobustLoss::Tukey, 4.685, 4.685), 0.0);
  const double u = 2.0, k = 4.0;
  EXPECT_DOUBLE_EQ(detail::robust_weight(RobustLoss::Tukey, u, k), std::pow(1.0 - 0.25, 2));
}

// The vectorized weights of a whole iteration are robust_weight's, row by row, to the bit.
TEST(Robust, WeightsOfAllRowsAreEachRowsToTheBit) {
  Generator g(23);
  VectorXd u(2003);
  for (Index i = 0; i < u.size(); ++i) u(i) = std::abs(g.normal()) * (i % 7 == 0 ? 10.0 : 1.0);
  u(0) = 0.0;
  u(1) = 1.345 * 0.8;  // exactly on Huber's corner once scaled by 0.8
  u(2) = 4.685 * 0.8;  // and Tukey's
  for (const RobustLoss loss : {RobustLoss::Huber, RobustLoss::Tukey, RobustLoss::None}) {
    const double k = loss == RobustLoss::Tukey ? 4.685 : 1.345;
    for (const double scale : {0.8, 0.0}) {
      const VectorXd w = detail::robust_weights(loss, u, scale, k);
      ASSERT_EQ(w.size(), u.size());
      for (Index i = 0; i < u.size(); ++i) {
        const double one = detail::robust_weight(loss, scale > 0.0 ? u(i) / scale : 0.0, k);
        ASSERT_EQ(std::memcmp(&one, &w(i), sizeof(double)), 0) << "row " << i << " scale " << scale;
      }
    }
  }
}

TEST(Robust, OnCleanDataTheRobustFitIsNearThePlainOne) {
  Generator g(21);
  // Equal noise in A and B: the model spd-tls whitens the residuals with.
  const MatrixXd A0 = g.gaussian(300, 3), X = g.spd(3, 5.0);
  const MatrixXd A = A0 + 0.01 * g.gaussian(300, 3), B = A0 * X + 0.01 * g.gaussian(300, 3);
  FitOptions options;
  const FitResult plain = fit(A, B, Method::SpdTotalLeastSquares, options);
  for (RobustLoss loss : {RobustLoss::Huber, RobustLoss::Tukey}) {
    options.robust = loss;
    const FitResult robust = fit(A, B, Method::SpdTotalLeastSquares, options);
    ASSERT_TRUE(robust.ok() && robust.robust) << robust.message;
    EXPECT_TRUE(robust.robust->converged);
    EXPECT_LT((robust.X - plain.X).norm(), 0.01 * plain.X.norm());
    // Gaussian rows weighed below 0.5 (Huber: u > 2 k; Tukey: u > 0.54 k): a few percent of them.
    EXPECT_LE(robust.robust->rows_downweighted_count, 30u);
  }
  options.robust = RobustLoss::Huber;
  EXPECT_THROW(fit(A, B, Method::Spde, options), OptionError);
  EXPECT_THROW(reduce(TriangularFactor::from_data(A, B), options), std::invalid_argument);
}

// The leverages' two routes: R11^-1 where A has full rank (here wide enough, n = 20, for the BLAS
// products), the SVD's pseudo-inverse where it has not (a column that is the sum of two others);
// against the hat matrix of the pseudo-inverse formed directly.
TEST(Robust, RowScoresTakeTheRankOfA) {
  Generator g(24);
  for (const Index n : {Index{20}, Index{3}}) {
    const Index m = 200;
    MatrixXd A = g.gaussian(m, n);
    const bool deficient = n == 3;
    if (deficient) A.col(2) = A.col(0) + A.col(1);
    const MatrixXd B = A * g.spd(n, 3.0) + 0.1 * g.gaussian(m, n);
    const FitResult r = fit(A, B, Method::LeastSquares);
    ASSERT_TRUE(r.ok());
    EXPECT_EQ(r.diagnostics.rank_a, deficient ? 2 : n);
    const TriangularFactor factor = TriangularFactor::from_data(A, B);
    const VectorXd score = detail::row_scores(A, B, r, factor, FitOptions{});
    ASSERT_EQ(score.size(), m);
    const Eigen::CompleteOrthogonalDecomposition<MatrixXd> cod(A);
    const MatrixXd H = A * cod.pseudoInverse();
    for (Index i = 0; i < m; ++i) {
      const double expected = (A.row(i) * r.X - B.row(i)).norm() / std::sqrt(1.0 - H(i, i));
      EXPECT_NEAR(score(i), expected, 1e-9 * expected) << "n = " << n << ", row " << i;
    }
  }
}

TEST(Robust, RowScoresAreStudentizedResidualsForLeastSquares) {
  Generator g(22);
  const MatrixXd A = g.gaussian(40, 2), B = A * g.spd(2, 3.0) + 0.1 * g.gaussian(40, 2);
  const FitResult r = fit(A, B, Method::LeastSquares);
  const TriangularFactor factor = TriangularFactor::from_data(A, B);
  const VectorXd score = detail::row_scores(A, B, r, factor, FitOptions{});
  ASSERT_EQ(score.size(), 40);
  // h = diag(A (A^T A)^-1 A^T), ls whitens by I.
  const MatrixXd G = A.transpose() * A;
  const MatrixXd H = A * G.inverse() * A.transpose();
  for (Index i = 0; i < 40; ++i) {
    const double expected = (A.row(i) * r.X - B.row(i)).norm() / std::sqrt(1.0 - H(i, i));
    EXPECT_NEAR(score(i), expected, 1e-10 * expected);
  }
}

}  // namespace
}  // namespace spdfit
