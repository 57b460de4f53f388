// The one numerical-rank rule (spdfit/rank.hpp): sigma_i counts iff sigma_i > tolerance * sigma_1,
// strictly, as NumPy's matrix_rank; checked AT exact ties through every caller: fit's reduction
// (rank_tolerance), solve (threshold) and the linkage least-squares solve (threshold). Diagonal
// data with power-of-two entries keep the singular values exact through the QR and the SVD.
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
  MatrixXd A = MatrixXd::Zero(2, 2);
  A.diagonal() << 1.0, 0.5;  // singular values exactly 1 and 0.5
  const MatrixXd B = MatrixXd::Identity(2, 2);
  FitOptions at_tie, below_tie;
  at_tie.rank_tolerance = 0.5;
  below_tie.rank_tolerance = 0.4999999;
  EXPECT_EQ(reduce(TriangularFactor::from_data(A, B), at_tie).rank_a(), 1);
  EXPECT_EQ(reduce(TriangularFactor::from_data(A, B), below_tie).rank_a(), 2);
  EXPECT_EQ(fit(A, B, Method::LeastSquares, at_tie).diagnostics.rank_a, 1);
}

TEST(Rank, SolveUsesTheStrictRuleAtATie) {
  MatrixXd A = MatrixXd::Zero(2, 2);
  A.diagonal() << 1.0, 0.5;
  const MatrixXd b = MatrixXd::Ones(2, 1);
  LinearSystemOptions at_tie, below_tie;
  at_tie.threshold = 0.5;
  below_tie.threshold = 0.4999999;
  EXPECT_EQ(solve(A, b, at_tie).rank, 1);
  EXPECT_EQ(solve(A, b, below_tie).rank, 2);
}

TEST(Rank, TheLinkageSolveUsesTheStrictRuleAtATie) {
  MatrixXd M = MatrixXd::Zero(3, 3);
  M.diagonal() << 1.0, 0.5, 0.25;
  const VectorXd rhs = VectorXd::Ones(3);
  EXPECT_EQ(linkage::detail::small_least_squares(M, rhs, 0.5).rank, 1);
  EXPECT_EQ(linkage::detail::small_least_squares(M, rhs, 0.25).rank, 2);
  EXPECT_EQ(linkage::detail::small_least_squares(M, rhs, 0.2).rank, 3);
}

}  // namespace
}  // namespace spdfit
