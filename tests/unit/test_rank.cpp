// The one numerical-rank rule (spdfit/rank.hpp): sigma_i counts iff sigma_i > tolerance * sigma_1,
// strictly, as NumPy's matrix_rank; checked AT exact ties through every caller: fit's reduction
// (rank_tolerance), solve (threshold) and the linkage least-squares solve (threshold), each of
// which decides on its matrix with the columns scaled to norms in [0.5, 1). Diagonal data with
// entries in [0.5, 1) keep the singular values exact through the scaling, the QR and the SVD.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>

#include "linkage/small_least_squares.hpp"
#include "spdfit/fit.hpp"
#include "spdfit/fit_options.hpp"
#include "spdfit/linear_system.hpp"
#include "spdfit/rank.hpp"
#include "spdfit/reduction.hpp"
#include "spdfit/triangular_factor.hpp"

namespace spdfit {
namespace {

using Eigen::MatrixXd;
using Eigen::VectorXd;

constexpr double kEps = std::numeric_limits<double>::epsilon();

TEST(Rank, CountsSingularValuesStrictlyAboveTheCutoff) {
  const VectorXd s = (VectorXd(3) << 1.0, 0.5, 0.25).finished();
  EXPECT_EQ(numerical_rank(s, 0.5), 1);        // 0.5 = 0.5 * 1: at the tie, zero
  EXPECT_EQ(numerical_rank(s, 0.4999999), 2);  // just below the tie: kept
  EXPECT_EQ(numerical_rank(s, 0.0), 3);
  EXPECT_EQ(numerical_rank(VectorXd::Zero(3), 0.0), 0);
  EXPECT_EQ(numerical_rank(VectorXd(0), 0.5), 0);
  EXPECT_EQ(numerical_rank((VectorXd(2) << 1.0, 0.0).finished(), 0.0), 1);  // an exact zero is never kept
}

TEST(Rank, DefaultToleranceAndValidation) {
  EXPECT_EQ(default_rank_tolerance(10, 3), 10 * kEps);
  EXPECT_EQ(rank_cutoff(-1.0, 3, 10), 10 * kEps);
  EXPECT_EQ(rank_cutoff(0.25, 3, 10), 0.25);
  std::string error;
  EXPECT_TRUE(is_valid_rank_tolerance(0.0, "x", &error));
  EXPECT_TRUE(is_valid_rank_tolerance(-1.0, "x", &error));
  EXPECT_FALSE(is_valid_rank_tolerance(1.0, "rank_tolerance", &error));
  EXPECT_EQ(error, "rank_tolerance must be a number below 1 (negative for the default max(m, n) * eps)");
  EXPECT_FALSE(is_valid_rank_tolerance(std::nan(""), "threshold", &error));
  EXPECT_FALSE(is_valid_rank_tolerance(std::numeric_limits<double>::infinity(), "threshold", &error));
}

TEST(Rank, FitsReductionUsesTheStrictRuleAtATie) {
  // The rank is decided with the columns scaled to norms in [0.5, 1) (numerics/least_squares.hpp):
  // diagonal entries there already stay as they are, so the singular values are exactly 0.75 and
  // 0.5625 = 0.75 * 0.75, a tie at 0.75.
  MatrixXd A = MatrixXd::Zero(2, 2);
  A.diagonal() << 0.75, 0.5625;
  const MatrixXd B = MatrixXd::Identity(2, 2);
  FitOptions at_tie, below_tie;
  at_tie.rank_tolerance = 0.75;
  below_tie.rank_tolerance = 0.7499999;
  EXPECT_EQ(reduce(TriangularFactor::from_data(A, B), at_tie).rank_a(), 1);
  EXPECT_EQ(reduce(TriangularFactor::from_data(A, B), below_tie).rank_a(), 2);
  EXPECT_EQ(fit(A, B, Method::LeastSquares, at_tie).diagnostics.rank_a, 1);
}

TEST(Rank, SolveUsesTheStrictRuleAtATie) {
  // Columns of equal norm (so the column scaling is one power of two for both), singular values
  // sqrt(2) and sqrt(2) / 2. The cut-off t with t * sigma_max == sigma_min exactly, in the scaled
  // values solve reports, counts sigma_min as zero; the next double below keeps it.
  MatrixXd A(2, 2);
  A << 1.0, 1.0, 0.5, -0.5;
  const MatrixXd b = MatrixXd::Ones(2, 1);
  const Eigen::VectorXd s = solve(A, b).scaled_singular_values;
  double t = s(1) / s(0);
  while (t * s(0) > s(1)) t = std::nextafter(t, 0.0);
  while (t * s(0) < s(1)) t = std::nextafter(t, 1.0);
  ASSERT_EQ(t * s(0), s(1));
  LinearSystemOptions at_tie, below_tie;
  at_tie.rank_tolerance = t;
  below_tie.rank_tolerance = std::nextafter(t, 0.0);
  ASSERT_LT(*below_tie.rank_tolerance * s(0), s(1));
  EXPECT_EQ(solve(A, b, at_tie).rank, 1);
  EXPECT_EQ(solve(A, b, below_tie).rank, 2);
}

TEST(Rank, TheLinkageSolveUsesTheStrictRuleAtATie) {
  // Norms in [0.5, 1), untouched by the column scaling: 0.65625 = 0.75 * 0.875 and
  // 0.546875 = 0.625 * 0.875 exactly, ties at 0.75 and 0.625.
  MatrixXd M = MatrixXd::Zero(3, 3);
  M.diagonal() << 0.875, 0.65625, 0.546875;
  const VectorXd rhs = VectorXd::Ones(3);
  EXPECT_EQ(linkage::detail::small_least_squares(M, rhs, 0.75).rank, 1);
  EXPECT_EQ(linkage::detail::small_least_squares(M, rhs, 0.625).rank, 2);
  EXPECT_EQ(linkage::detail::small_least_squares(M, rhs, 0.5).rank, 3);
}

}  // namespace
}  // namespace spdfit
