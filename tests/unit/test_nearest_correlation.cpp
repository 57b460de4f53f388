// nearest_correlation, nearest_keep_diagonal and nearest_via_correlation: Higham's (2002)
// published example, the optimality conditions of the fixed-diagonal problem with and without a
// floor, the unit diagonal, alpha as the floor, scaling, the via-correlation identity, the floor
// warning, and the input checks.
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>

#include "numerics/linalg.hpp"
#include "spdfit/nearest_correlation.hpp"
#include "test_support.hpp"

namespace spdfit {
namespace {

using test::Generator;

// Higham's (2002) tridiagonal test matrix, also NAG's g02aa/g02ab example: 2 on the diagonal, -1 beside it.
MatrixXd highams_matrix() {
  MatrixXd C(4, 4);
  C << 2, -1, 0, 0, -1, 2, -1, 0, 0, -1, 2, -1, 0, 0, -1, 2;
  return C;
}

// Higham, "Computing the nearest correlation matrix - a problem from finance", IMA J. Numer.
// Anal. 22 (2002), section 4: the tridiagonal matrix and its nearest correlation matrix (4 decimals).
TEST(NearestCorrelation, HighamsExample) {
  const MatrixXd C = highams_matrix();
  MatrixXd expected(4, 4);
  expected << 1, -0.8084, 0.1916, 0.1068, -0.8084, 1, -0.6562, 0.1916, 0.1916, -0.6562, 1, -0.8084, 0.1068,
      0.1916, -0.8084, 1;
  const NearestCorrelationResult r = nearest_correlation(C);
  EXPECT_TRUE(r.converged);
  EXPECT_LT((r.X - expected).cwiseAbs().maxCoeff(), 6e-5);
  EXPECT_LT(r.iterations, 20);
}

// NAG's documented example of g02ab (nearest correlation matrix with weights and a bound on the
// eigenvalues): Higham's matrix, alpha = 0.02, g02ab's w = (100, 20, 20, 20), which are the square
// roots of W's diagonal (g02ab's convention), so our weights are their squares; the published
// answer to 4 decimals.
TEST(NearestCorrelation, NagG02abExample) {
  const MatrixXd C = highams_matrix();
  MatrixXd expected(4, 4);
  expected << 1, -0.9371, 0.0262, 0.0087, -0.9371, 1, -0.3069, 0.2315, 0.0262, -0.3069, 1, -0.9037, 0.0087,
      0.2315, -0.9037, 1;
  NearestCorrelationOptions o;
  o.alpha = 0.02;
  o.weights = (VectorXd(4) << 100, 20, 20, 20).finished().cwiseAbs2();
  const NearestResult r = nearest_correlation(C, o);
  EXPECT_TRUE(r.converged);
  EXPECT_LT((r.X - expected).cwiseAbs().maxCoeff(), 6e-5);
  EXPECT_GT(Eigen::SelfAdjointEigenSolver<MatrixXd>(r.X).eigenvalues()(0), 0.02 - 1e-12);
}

// Optimality: the feasible set (PSD, unit diagonal) is convex, so X minimizes ||X - C||_F^2 / 2
// exactly when the variational inequality <X - C, K - X> >= 0 holds for every correlation matrix
// K; checked on random ones, of low rank so that they reach the boundary.
TEST(NearestCorrelation, OptimalityAndUnitDiagonal) {
  Generator g(7);
  for (Index n : {5, 30, 80}) {
    // A correlation-like matrix with noise that makes it indefinite.
    const MatrixXd M = g.gaussian(n, n);
    MatrixXd C = (M + M.transpose()) / (2.0 * std::sqrt(static_cast<double>(n)));
    C.diagonal().setOnes();
    const NearestCorrelationResult r = nearest_correlation(C);
    ASSERT_TRUE(r.converged) << n;
    EXPECT_TRUE(r.warnings.empty());
    EXPECT_LT((r.X.diagonal().array() - 1.0).abs().maxCoeff(), 1e-14);
    EXPECT_EQ(r.X, r.X.transpose());
    EXPECT_GT(Eigen::SelfAdjointEigenSolver<MatrixXd>(r.X).eigenvalues()(0), -1e-12);
    if (Eigen::SelfAdjointEigenSolver<MatrixXd>(C).eigenvalues()(0) < 0.0) {
      EXPECT_GT(r.clipped, 0) << n;
    }
    const MatrixXd D = r.X - C;
    for (int k = 0; k < 20; ++k) {
      const MatrixXd F = g.gaussian(n, 3);
      MatrixXd K = F * F.transpose();
      const VectorXd s = K.diagonal().cwiseSqrt().cwiseInverse();
      K = (s.asDiagonal() * K * s.asDiagonal()).eval();
      EXPECT_GT(D.cwiseProduct(K - r.X).sum(), -1e-9 * static_cast<double>(n)) << n;
    }
    EXPECT_NEAR(r.distance, D.norm(), 1e-12 * D.norm());
  }
}

// An asymmetric input is repaired through its symmetric part, with a warning.
TEST(NearestCorrelation, WarnsWhenCIsNotSymmetric) {
  MatrixXd C = MatrixXd::Identity(3, 3);
  C(0, 1) = 0.5;
  const NearestCorrelationResult r = nearest_correlation(C);
  ASSERT_EQ(r.warnings.size(), 1u);
  EXPECT_NE(r.warnings[0].text.find("not symmetric"), std::string::npos);
  EXPECT_NEAR(r.X(0, 1), 0.25, 1e-12);
}

TEST(NearestCorrelation, AlphaIsAFloorThatKeepsTheUnitDiagonal) {
  const MatrixXd C = highams_matrix();
  NearestCorrelationOptions o;
  o.alpha = 0.1;
  const NearestCorrelationResult r = nearest_correlation(C, o);
  EXPECT_TRUE(r.cholesky_ok);
  EXPECT_LT((r.X.diagonal().array() - 1.0).abs().maxCoeff(), 1e-15);
  EXPECT_GT(Eigen::SelfAdjointEigenSolver<MatrixXd>(r.X).eigenvalues()(0), 0.1 - 1e-10);
}

TEST(NearestCorrelation, AValidCorrelationMatrixIsItsOwnAnswer) {
  Generator g(3);
  MatrixXd F = g.gaussian(10, 10);
  MatrixXd K = F * F.transpose();
  const VectorXd s = K.diagonal().cwiseSqrt().cwiseInverse();
  K = s.asDiagonal() * K * s.asDiagonal();
  const NearestCorrelationResult r = nearest_correlation(K);
  EXPECT_LT((r.X - K).norm(), 1e-12);
  EXPECT_EQ(r.clipped, 0);
}

// An indefinite symmetric matrix with variances from 0.25 to 4 (a covariance gone wrong).
MatrixXd indefinite_covariance(Generator& g, Index n) {
  const MatrixXd M = g.gaussian(n, n);
  MatrixXd R = (M + M.transpose()) / (2.0 * std::sqrt(static_cast<double>(n)));
  R.diagonal().setOnes();
  const VectorXd sd = VectorXd::LinSpaced(n, 0.5, 2.0);
  return sd.asDiagonal() * R * sd.asDiagonal();
}

double smallest_eigenvalue(const MatrixXd& X) { return Eigen::SelfAdjointEigenSolver<MatrixXd>(X).eigenvalues()(0); }

// The fixed-diagonal problem with a floor: X minimizes ||X - C||_F over the convex set
// {X >= floor I, diag(X) = diag(C)} exactly when <X - C, K - X> >= 0 for every K in it. K: random
// low-rank correlations scaled to the diagonal diag(C) - floor, plus floor I (on the boundary).
TEST(NearestKeepDiagonal, OptimalityWithAndWithoutAFloor) {
  Generator g(11);
  for (Index n : {6, 40, 90}) {
    const MatrixXd C = indefinite_covariance(g, n);
    for (double floor : {0.0, 0.1}) {
      NearestCorrelationOptions o;
      o.floor = EigenvalueFloor::absolute(floor);
      const NearestResult r = nearest_keep_diagonal(C, o);
      ASSERT_TRUE(r.converged) << n;
      EXPECT_EQ(r.X.diagonal(), C.diagonal());
      EXPECT_EQ(r.X, r.X.transpose());
      EXPECT_GT(smallest_eigenvalue(r.X), floor - 1e-12) << n;
      EXPECT_EQ(r.min_eig, floor);
      EXPECT_NEAR(r.distance, (r.X - C).norm(), 1e-12 * r.distance);
      const MatrixXd D = r.X - C;
      const VectorXd target = (C.diagonal().array() - floor).sqrt().matrix();
      for (int k = 0; k < 20; ++k) {
        const MatrixXd F = g.gaussian(n, 2);
        MatrixXd K = F * F.transpose();
        const VectorXd s = K.diagonal().cwiseSqrt().cwiseInverse().cwiseProduct(target);
        K = (s.asDiagonal() * K * s.asDiagonal()).eval();
        K.diagonal().array() += floor;
        EXPECT_GT(D.cwiseProduct(K - r.X).sum(), -1e-9 * static_cast<double>(n)) << n << " " << floor;
      }
    }
  }
}

// NAG's alpha and the absolute floor are the same constraint X >= alpha I: the same minimizer.
TEST(NearestCorrelation, AlphaIsTheAbsoluteFloor) {
  Generator g(12);
  MatrixXd C = indefinite_covariance(g, 20);
  C.diagonal().setOnes();
  NearestCorrelationOptions a, f;
  a.alpha = 0.05;
  f.floor = EigenvalueFloor::absolute(0.05);
  EXPECT_LT((nearest_correlation(C, a).X - nearest_correlation(C, f).X).cwiseAbs().maxCoeff(), 1e-10);
  a.floor = f.floor;
  EXPECT_THROW(nearest_correlation(C, a), std::invalid_argument);  // both
  EXPECT_THROW(nearest_keep_diagonal(C, NearestCorrelationOptions{{}, {}, 0.1}), std::invalid_argument);
}

// Repairing s C gives s X: exactly for a power of two (every step scales exactly), to rounding
// otherwise; the relative floor follows.
TEST(NearestKeepDiagonal, RepairingSCGivesSX) {
  Generator g(13);
  const MatrixXd C = indefinite_covariance(g, 15);
  NearestCorrelationOptions o;
  o.floor = EigenvalueFloor::relative_to_largest(1e-3);
  const NearestResult r = nearest_keep_diagonal(C, o);
  EXPECT_EQ(nearest_keep_diagonal(C * 1024.0, o).X, r.X * 1024.0);
  EXPECT_EQ(nearest_keep_diagonal(C * std::ldexp(1.0, -600), o).X, r.X * std::ldexp(1.0, -600));
  const MatrixXd scaled = nearest_keep_diagonal(C * 3.7, o).X;
  EXPECT_LT((scaled - 3.7 * r.X).cwiseAbs().maxCoeff(), 1e-12 * 3.7 * C.cwiseAbs().maxCoeff());
  // The relative floor is of the correlation matrix D^-1/2 C D^-1/2, so scale-free.
  const VectorXd root = C.diagonal().cwiseSqrt().cwiseInverse();
  const MatrixXd R = root.asDiagonal() * C * root.asDiagonal();
  EXPECT_NEAR(r.min_eig, 1e-3 * Eigen::SelfAdjointEigenSolver<MatrixXd>(R).eigenvalues().maxCoeff(), 1e-15);
  EXPECT_NEAR(nearest_keep_diagonal(C * 3.7, o).min_eig, r.min_eig, 1e-14 * r.min_eig);
  EXPECT_TRUE(r.cholesky_ok);
}

// The diagonal-keeping repair's relative floor bounds the correlation matrix D^-1/2 X D^-1/2
// from below, so it is feasible whatever the variances' scales: variables in units 1e-4 to 1e4
// apart (variances 1e-8 to 1e8), where a floor relative to C's largest eigenvalue (1e-8 x about
// 1e8) would exceed the smallest variance. The floor is met exactly where it is active, and X
// factors by Cholesky.
TEST(NearestKeepDiagonal, RelativeFloorIsOfTheCorrelationMatrix) {
  Generator g(21);
  const Index n = 12;
  const MatrixXd M = g.gaussian(n, n);
  MatrixXd R = (M + M.transpose()) / std::sqrt(static_cast<double>(n));
  R.diagonal().setOnes();
  ASSERT_LT(smallest_eigenvalue(R), -0.1);  // a correlation matrix gone wrong
  VectorXd scales(n);
  for (Index i = 0; i < n; ++i) scales(i) = std::pow(10.0, -4.0 + 8.0 * static_cast<double>(i) / (n - 1));
  const MatrixXd C = scales.asDiagonal() * R * scales.asDiagonal();
  NearestCorrelationOptions o;
  o.floor = EigenvalueFloor::relative_to_largest(EigenvalueFloor::kRepairDefault);
  const NearestResult r = nearest_keep_diagonal(C, o);
  EXPECT_TRUE(r.converged);
  EXPECT_TRUE(r.cholesky_ok);
  EXPECT_EQ(r.X.diagonal(), C.diagonal());
  const double lambda_max = Eigen::SelfAdjointEigenSolver<MatrixXd>(R).eigenvalues().maxCoeff();
  EXPECT_NEAR(r.min_eig, EigenvalueFloor::kRepairDefault * lambda_max, 1e-14 * r.min_eig);
  const VectorXd root = C.diagonal().cwiseSqrt().cwiseInverse();
  const MatrixXd corr = root.asDiagonal() * r.X * root.asDiagonal();
  // Active (R is indefinite), met to the Newton tolerance relative to the unit diagonal.
  EXPECT_NEAR(Eigen::SelfAdjointEigenSolver<MatrixXd>(corr).eigenvalues()(0), r.min_eig, 1e-9);
  // The same problem as the repair of the correlation matrix with weights d (X = D^1/2 R~ D^1/2),
  // to the Newton tolerance: in C's units (relative to the largest variance; the distance is).
  NearestCorrelationOptions w = o;
  w.weights = C.diagonal();
  const NearestResult via = nearest_correlation(R, w);
  const MatrixXd back = C.diagonal().cwiseSqrt().asDiagonal() * via.X * C.diagonal().cwiseSqrt().asDiagonal();
  EXPECT_LT((back - r.X).norm(), 1e-9 * C.norm());
}

// statsmodels' route is the fixed-diagonal problem in the norm ||D^-1 (X - C) D^-1||_F, i.e. with
// weights 1 / diag(C).
TEST(NearestViaCorrelation, IsKeepDiagonalWithWeightsOneOverTheVariances) {
  Generator g(14);
  const MatrixXd C = indefinite_covariance(g, 25);
  const NearestResult via = nearest_via_correlation(C);
  NearestCorrelationOptions o;
  o.weights = C.diagonal().cwiseInverse();
  const NearestResult kept = nearest_keep_diagonal(C, o);
  EXPECT_LT((via.X - kept.X).cwiseAbs().maxCoeff(), 1e-9);
  EXPECT_EQ(via.X.diagonal(), C.diagonal());
  EXPECT_NEAR(via.distance, (via.X - C).norm(), 1e-12 * via.distance);
  MatrixXd bad = C;
  bad(3, 3) = 0.0;
  EXPECT_THROW(nearest_via_correlation(bad), std::invalid_argument);
  EXPECT_THROW(nearest_keep_diagonal(C, NearestCorrelationOptions{{}, EigenvalueFloor::absolute(0.25)}),
               std::invalid_argument);  // not below the smallest variance, 0.25
}

// A floor that moves the matrix more than the repair itself is named in a warning; the default
// relative floor does not trip it.
TEST(NearestCorrelation, WarnsWhenTheFloorDominates) {
  MatrixXd R = MatrixXd::Ones(4, 4);  // a rank-one correlation, made indefinite by 1e-9
  R(0, 1) = R(1, 0) = 1.0 + 1e-9;
  R(0, 2) = R(2, 0) = 1.0 - 1e-9;
  NearestCorrelationOptions o;
  o.floor = EigenvalueFloor::absolute(0.5);
  const NearestResult r = nearest_correlation(R, o);
  ASSERT_EQ(r.warnings.size(), 1u);
  EXPECT_NE(r.warnings[0].text.find("more than the repair itself"), std::string::npos);
  o.floor = EigenvalueFloor::relative_to_largest(EigenvalueFloor::kRepairDefault);
  EXPECT_TRUE(nearest_correlation(R, o).warnings.empty());
  EXPECT_TRUE(nearest_correlation(R, o).cholesky_ok);
}

// The BLAS products behind the Jacobian agree with Eigen's, for every transpose and for column
// blocks (an outer stride).
TEST(Linalg, MultiplyAgreesWithEigen) {
  Generator g(15);
  for (Index n : {5, 70, 130}) {
    const MatrixXd A = g.gaussian(n, n + 7), B = g.gaussian(n + 7, n);
    MatrixXd C;
    detail::multiply(A, false, B, false, C);
    EXPECT_LT((C - A * B).norm(), 1e-13 * A.norm() * B.norm());
    detail::multiply(A, true, A, false, C);
    EXPECT_LT((C - A.transpose() * A).norm(), 1e-13 * A.squaredNorm());
    detail::multiply(B, true, B.leftCols(n - 2), false, C);
    EXPECT_LT((C - B.transpose() * B.leftCols(n - 2)).norm(), 1e-13 * B.squaredNorm());
    detail::multiply(A.rightCols(n), false, B.bottomRows(n), true, C);
    EXPECT_LT((C - A.rightCols(n) * B.bottomRows(n).transpose()).norm(), 1e-13 * A.norm() * B.norm());
    detail::multiply(B, true, A, true, C);
    EXPECT_LT((C - B.transpose() * A.transpose()).norm(), 1e-13 * A.norm() * B.norm());
  }
  MatrixXd C;
  EXPECT_THROW(detail::multiply(MatrixXd(3, 4), false, MatrixXd(3, 4), false, C), std::invalid_argument);
}

// L U^-1 by the triangular solve from the right (the row scores' leverages): L recovered from the
// solution times U, on the BLAS's path (n >= 64) and Eigen's, with U read from its upper triangle.
TEST(Linalg, SolveUpperFromRightRecoversTheRows) {
  Generator g(17);
  for (Index n : {5, 70, 130}) {
    MatrixXd U = g.gaussian(n, n);
    U.diagonal().array() += 3.0 * std::sqrt(static_cast<double>(n));  // well conditioned
    const MatrixXd upper = U.triangularView<Eigen::Upper>();
    const MatrixXd L = g.gaussian(2 * n + 3, n);
    MatrixXd Y = L;
    detail::solve_upper_from_right_in_place(U, Y);  // U's lower triangle (nonzero here) is ignored
    EXPECT_LT((Y * upper - L).norm(), 1e-12 * L.norm());
  }
}

// The single-precision product (pattern_newton's conjugate gradients) agrees with the double one to
// float's rounding, for every transpose and for column blocks.
TEST(Linalg, SinglePrecisionMultiplyAgreesWithDouble) {
  Generator g(16);
  for (Index n : {5, 70, 130}) {
    const MatrixXd A = g.gaussian(n, n + 7), B = g.gaussian(n + 7, n);
    const Eigen::MatrixXf Af = A.cast<float>(), Bf = B.cast<float>();
    Eigen::MatrixXf C;
    const double bound = 1e-5 * A.norm() * B.norm();  // float eps 6e-8 times the inner dimension's growth
    detail::multiply(Af, false, Bf, false, C);
    EXPECT_LT((C.cast<double>() - A * B).norm(), bound);
    detail::multiply(Bf, true, Bf.leftCols(n - 2), false, C);
    EXPECT_LT((C.cast<double>() - B.transpose() * B.leftCols(n - 2)).norm(), 1e-5 * B.squaredNorm());
    detail::multiply(Af.rightCols(n), false, Bf.bottomRows(n), true, C);
    EXPECT_LT((C.cast<double>() - A.rightCols(n) * B.bottomRows(n).transpose()).norm(), bound);
    detail::multiply(Bf, true, Af, true, C);
    EXPECT_LT((C.cast<double>() - B.transpose() * A.transpose()).norm(), bound);
  }
  Eigen::MatrixXf C;
  EXPECT_THROW(detail::multiply(Eigen::MatrixXf(3, 4), false, Eigen::MatrixXf(3, 4), false, C), std::invalid_argument);
}

// The single-precision eigensolver (correlation_newton's early steps): eigenvalues within float's
// rounding of double precision's (Weyl: each within ||E||_2 of a backward error E), residual and
// orthogonality at float's level, ascending; Eigen's solver below 64 rows, ssyevd above, and a
// size above 2896, where LAPACKE_ssyevd's own workspace query (a float) would round the workspace
// below its minimum and ssyevd refused it.
TEST(Linalg, SinglePrecisionEigenAgreesWithDouble) {
  Generator g(17);
  for (Index n : {20, 150, 2900}) {
    const MatrixXd M0 = g.gaussian(n, n);
    const MatrixXd M = (M0 + M0.transpose()) / 2.0;
    Eigen::MatrixXf V = M.cast<float>();
    Eigen::VectorXf w;
    ASSERT_TRUE(detail::symmetric_eigen_in_place(V, w, true)) << n;
    MatrixXd Vd = M;
    VectorXd wd;
    ASSERT_TRUE(detail::symmetric_eigen_in_place(Vd, wd, false)) << n;
    const double norm = std::max(std::abs(wd(0)), std::abs(wd(n - 1)));
    // float's eps 6e-8, a growth of sqrt(n) and a margin
    const double level = 1e-6 * std::sqrt(static_cast<double>(n)) * norm;
    EXPECT_LT((w.cast<double>() - wd).cwiseAbs().maxCoeff(), level) << n;
    for (Index i = 1; i < n; ++i) ASSERT_LE(w(i - 1), w(i)) << n;
    const MatrixXd P = V.cast<double>();
    MatrixXd MP, PtP;
    detail::multiply(M, false, P, false, MP);
    EXPECT_LT((MP - P * w.cast<double>().asDiagonal()).norm(), level * std::sqrt(static_cast<double>(n)))
        << n;
    detail::multiply(P, true, P, false, PtP);
    EXPECT_LT((PtP - MatrixXd::Identity(n, n)).norm(), 1e-6 * static_cast<double>(n)) << n;
    Eigen::MatrixXf values_only = M.cast<float>();
    Eigen::VectorXf w2;
    ASSERT_TRUE(detail::symmetric_eigen_in_place(values_only, w2, false)) << n;
    EXPECT_LT((w2.cast<double>() - wd).cwiseAbs().maxCoeff(), level) << n;
  }
}

TEST(NearestCorrelation, InputChecks) {
  EXPECT_THROW(nearest_correlation(MatrixXd(2, 3)), std::invalid_argument);
  MatrixXd C = MatrixXd::Identity(3, 3);
  C(0, 1) = std::nan("");
  EXPECT_THROW(nearest_correlation(C), std::invalid_argument);
  NearestCorrelationOptions o;
  o.weights = VectorXd::Ones(2);
  EXPECT_THROW(nearest_correlation(MatrixXd::Identity(3, 3), o), std::invalid_argument);
  o.weights = VectorXd::Constant(3, -1.0);
  EXPECT_THROW(nearest_correlation(MatrixXd::Identity(3, 3), o), std::invalid_argument);
  o = {};
  o.alpha = 1.0;
  EXPECT_THROW(nearest_correlation(MatrixXd::Identity(3, 3), o), std::invalid_argument);
}

}  // namespace
}  // namespace spdfit
