// Higham's nearest symmetric positive (semi)definite matrix.
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <Eigen/SVD>
#include <vector>

#include "spdfit/format.hpp"
#include "spdfit/nearest_spd.hpp"
#include "test_support.hpp"

namespace spdfit {
namespace {

using test::Generator;
using test::kEps;

double min_eigenvalue(const MatrixXd& X) {
  return Eigen::SelfAdjointEigenSolver<MatrixXd>(X, Eigen::EigenvaluesOnly).eigenvalues()(0);
}

TEST(NearestSpd, IsSymmetricSemidefiniteAndHighamsFormula) {
  Generator g(51);
  const MatrixXd X = g.gaussian(6, 6);
  const NearestSpdResult r = nearest_spd(X);
  EXPECT_TRUE(r.X == r.X.transpose());
  EXPECT_GE(min_eigenvalue(r.X), -10 * 6 * kEps * r.X.norm());
  // Higham / thesis eq. 4.39: (S + H)/2 with H the polar factor of S = (X + X^T)/2, via SVD.
  const MatrixXd S = 0.5 * (X + X.transpose());
  Eigen::JacobiSVD<MatrixXd> svd(S, Eigen::ComputeFullV);
  const MatrixXd H = svd.matrixV() * svd.singularValues().asDiagonal() * svd.matrixV().transpose();
  EXPECT_LT(test::relative_error(r.X, 0.5 * (S + H)), 1e-14);
  EXPECT_NEAR(r.distance, (X - r.X).norm(), 1e-14 * X.norm());
  EXPECT_GT(r.clipped, 0);
}

TEST(NearestSpd, IsCloserThanOtherPositiveSemidefiniteMatrices) {
  Generator g(52);
  const MatrixXd X = g.gaussian(5, 5);
  const NearestSpdResult r = nearest_spd(X);
  const double best = (X - r.X).norm();
  const MatrixXd S = 0.5 * (X + X.transpose());
  Eigen::SelfAdjointEigenSolver<MatrixXd> eig(S);
  const MatrixXd& W = eig.eigenvectors();
  const VectorXd lambda = eig.eigenvalues();
  // Other ways to make S semidefinite: its polar factor |S|, a shift by -lambda_min, and
  // clipping the negative eigenvalues at other nonnegative values.
  std::vector<MatrixXd> others;
  others.push_back(W * lambda.cwiseAbs().asDiagonal() * W.transpose());
  others.push_back(S - lambda(0) * MatrixXd::Identity(5, 5));
  for (double floor : {1e-3, 0.1, 1.0}) {
    others.push_back(W * lambda.cwiseMax(floor).asDiagonal() * W.transpose());
  }
  // Random semidefinite perturbations of the answer.
  for (int trial = 0; trial < 200; ++trial) {
    const MatrixXd G = g.gaussian(5, 2) * (trial % 2 ? 0.01 : 0.5);
    others.push_back(r.X + G * G.transpose());
  }
  for (const MatrixXd& other : others) EXPECT_GE((X - other).norm(), best * (1 - 1e-14));
}

TEST(NearestSpd, MinimumEigenvalueGivesAStrictlyDefiniteMatrix) {
  Generator g(53);
  const MatrixXd X = Generator::symmetrize(g.gaussian(8, 8));
  for (double floor : {1e-8, 1e-3, 0.5}) {
    const NearestSpdResult r = nearest_spd(X, floor);
    EXPECT_TRUE(r.X == r.X.transpose());
    EXPECT_GE(min_eigenvalue(r.X), floor * (1 - 1e-8) - 10 * 8 * kEps * r.X.norm());
    EXPECT_GT(min_eigenvalue(r.X), 0.0);
  }
}

TEST(NearestSpd, LeavesAnAdmissibleMatrixUnchanged) {
  Generator g(54);
  const MatrixXd X = g.spd(6, 100.0);
  const NearestSpdResult r = nearest_spd(X);
  EXPECT_TRUE(r.X == X);
  EXPECT_EQ(r.clipped, 0);
  EXPECT_EQ(r.distance, 0.0);
}

TEST(NearestSpd, HandlesEntriesNearTheDoubleRange) {
  Generator g(55);
  const MatrixXd X = g.gaussian(4, 4) * 1e300;
  const NearestSpdResult r = nearest_spd(X);
  EXPECT_TRUE(r.X.allFinite());
  EXPECT_TRUE(std::isfinite(r.distance));
  const NearestSpdResult unit = nearest_spd(X / 1e300);
  EXPECT_LT(test::relative_error(r.X / 1e300, unit.X), 1e-14);
}

// Regression (found by the stress tests): eigenvalues of a matrix with entries near the largest
// double exceed it, so the eigensolver's overflowed to Inf and the answer was NaN, although the
// nearest semidefinite matrix (entries 1.35e308) fits.
TEST(NearestSpdRegression, EigenvaluesBeyondTheDoubleRangeGiveAFiniteAnswer) {
  MatrixXd X(2, 2);
  X << 1e308, -1.7e308, -1.7e308, 1e308;  // eigenvalues 2.7e308 and -0.7e308
  const NearestSpdResult r = nearest_spd(X);
  ASSERT_TRUE(r.X.allFinite());
  EXPECT_EQ(r.clipped, 1);
  EXPECT_NEAR(r.X(0, 0) / 1.35e308, 1.0, 1e-15);
  EXPECT_NEAR(r.X(0, 1) / -1.35e308, 1.0, 1e-15);
  EXPECT_NEAR(r.min_eigenvalue_before / -0.7e308, 1.0, 1e-15);
  EXPECT_TRUE(std::isfinite(r.distance));
}

// A tiny matrix under a large floor min_eig: the units follow the floor, not the entries.
TEST(NearestSpd, FloorFarAboveTheEntries) {
  const NearestSpdResult r = nearest_spd(MatrixXd::Identity(2, 2) * 1e-300, 1e10);
  EXPECT_TRUE(r.X.isApprox(MatrixXd::Identity(2, 2) * 1e10, 1e-15));
  EXPECT_EQ(r.clipped, 2);
}

TEST(NearestSpd, AnswerBeyondTheDoubleRangeIsAnError) {
  // Eigenvalues 3.09e308 and -0.39e308: the nearest semidefinite matrix has (0, 0) entry 1.85e308.
  MatrixXd X(2, 2);
  X << 1.7e308, 1.7e308, 1.7e308, 1.0e308;
  EXPECT_THROW(nearest_spd(X), std::runtime_error);
}

// The relative floor: r times the largest eigenvalue of the symmetric part, so that repairing s X
// gives s Y, and a Cholesky factorization succeeds. The closed form: the clip at that floor.
TEST(NearestSpd, RelativeFloorFollowsTheScale) {
  Generator g(57);
  const MatrixXd X = Generator::symmetrize(g.gaussian(70, 70));  // 70: the LAPACK path
  Eigen::SelfAdjointEigenSolver<MatrixXd> eig(X);
  const double floor = 1e-8 * eig.eigenvalues().maxCoeff();
  const NearestSpdResult r = nearest_spd(X, EigenvalueFloor::relative_to_largest(1e-8));
  EXPECT_NEAR(r.min_eig, floor, 1e-13 * floor);
  const MatrixXd expected =
      eig.eigenvectors() * eig.eigenvalues().cwiseMax(floor).asDiagonal() * eig.eigenvectors().transpose();
  EXPECT_LT((r.X - expected).norm(), 1e-13 * X.norm());
  EXPECT_TRUE(r.cholesky_ok);
  // Only the note of the clip: how many eigenvalues were raised, to which floor.
  ASSERT_EQ(r.warnings.size(), 1u);
  EXPECT_EQ(r.warnings[0].text, std::to_string(r.clipped) + " eigenvalue(s) of the symmetric part were below " +
                               format_number(r.min_eig) + " (1e-08 x the largest eigenvalue) and were raised to it");
  EXPECT_EQ(r.clipped, (eig.eigenvalues().array() < floor).count());
  const NearestSpdResult tiny = nearest_spd(X * std::ldexp(1.0, -40), EigenvalueFloor::relative_to_largest(1e-8));
  EXPECT_EQ(tiny.X, r.X * std::ldexp(1.0, -40));
  // Nothing positive to be relative to: an error, not a silent zero matrix.
  EXPECT_THROW(nearest_spd(-MatrixXd::Identity(3, 3), EigenvalueFloor::relative_to_largest(1e-8)),
               std::invalid_argument);
  EXPECT_THROW(nearest_spd(X, EigenvalueFloor::relative_to_largest(1.0)), std::invalid_argument);
  EXPECT_FALSE(EigenvalueFloor::absolute(-1.0).is_valid());
  EXPECT_TRUE(EigenvalueFloor::absolute(2.0).is_valid());
}

// An absolute floor far above a small-scale matrix moves it more than the repair: a warning.
TEST(NearestSpd, WarnsWhenTheFloorMovesMoreThanTheRepair) {
  Generator g(58);
  const MatrixXd X = Generator::symmetrize(g.gaussian(6, 6)) * 1e-8;
  const NearestSpdResult r = nearest_spd(X, 1e-6);
  ASSERT_EQ(r.warnings.size(), 2u);  // and the clip's note, which every clip gives
  EXPECT_NE(r.warnings[0].text.find("more than the repair itself"), std::string::npos);
  EXPECT_EQ(r.warnings[1].text, "6 eigenvalue(s) of the symmetric part were below 1e-06 and were raised to it");
  EXPECT_EQ(r.warnings[1].code, Code::EigenvaluesRaised);
  // floor 0: no floor, no floor warning; the clip's note only
  ASSERT_EQ(nearest_spd(X).warnings.size(), 1u);
  EXPECT_NE(nearest_spd(X).warnings[0].text.find("were below 0 and were raised to it"), std::string::npos);
  MatrixXd asymmetric = MatrixXd::Identity(3, 3);
  asymmetric(0, 1) = 0.1;
  ASSERT_EQ(nearest_spd(asymmetric).warnings.size(), 1u);
  EXPECT_NE(nearest_spd(asymmetric).warnings[0].text.find("not symmetric"), std::string::npos);
}

// The one rule for which floor a repair uses (the CLI's nearest and Python share it).
TEST(EigenvalueFloor, ChosenFromWhatWasGiven) {
  const EigenvalueFloor none = EigenvalueFloor::chosen(std::nullopt, std::nullopt, false);
  EXPECT_TRUE(none.relative);
  EXPECT_EQ(none.value, EigenvalueFloor::kRepairDefault);
  EXPECT_FALSE(EigenvalueFloor::chosen(0.5, std::nullopt, false).relative);
  EXPECT_EQ(EigenvalueFloor::chosen(0.5, std::nullopt, false).value, 0.5);
  EXPECT_EQ(EigenvalueFloor::chosen(std::nullopt, 1e-3, false).value, 1e-3);
  EXPECT_EQ(EigenvalueFloor::chosen(std::nullopt, std::nullopt, true).value, 0.0);
  EXPECT_THROW(EigenvalueFloor::chosen(0.5, 1e-3, false), std::invalid_argument);
  EXPECT_THROW(EigenvalueFloor::chosen(0.5, std::nullopt, true), std::invalid_argument);
}

TEST(NearestSpd, RejectsMisuse) {
  EXPECT_THROW(nearest_spd(MatrixXd::Ones(2, 3)), std::invalid_argument);
  EXPECT_THROW(nearest_spd(MatrixXd(0, 0)), std::invalid_argument);
  EXPECT_THROW(nearest_spd(MatrixXd::Identity(2, 2), -1.0), std::invalid_argument);
  EXPECT_THROW(nearest_spd(MatrixXd::Identity(2, 2), INFINITY), std::invalid_argument);
  MatrixXd bad = MatrixXd::Identity(2, 2);
  bad(0, 1) = std::nan("");
  EXPECT_THROW(nearest_spd(bad), std::invalid_argument);
}

}  // namespace
}  // namespace spdfit
