// The structured repairs: kept entries and elementwise weights (nearest_structured), rank and
// factors (nearest_low_rank.hpp), raised variances, and their rules in the option table. Against
// independent references written here: Dykstra's alternating projections for the convex problems
// (slow, but a separate algorithm), the variational inequality of the convex problem, the
// Riemannian and projected gradients of the non-convex ones; and the input checks.
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>

#include "spdfit/nearest_low_rank.hpp"
#include "spdfit/nearest_request.hpp"
#include "spdfit/nearest_structured.hpp"
#include "test_support.hpp"

namespace spdfit {
namespace {

using test::Generator;

// An indefinite symmetric matrix with unit diagonal: a correlation matrix plus symmetric noise.
MatrixXd noisy_correlation(Generator& g, Index n, double noise = 0.4) {
  const MatrixXd F = g.gaussian(n, std::max<Index>(1, n / 3));
  MatrixXd S = F * F.transpose();
  S.diagonal().array() += 0.5;
  const VectorXd d = S.diagonal().cwiseSqrt().cwiseInverse();
  MatrixXd C = d.asDiagonal() * S * d.asDiagonal();
  MatrixXd E(n, n);
  for (Index j = 0; j < n; ++j)
    for (Index i = 0; i < n; ++i) E(i, j) = g.uniform(-noise, noise);
  C += 0.5 * (E + E.transpose());
  C.diagonal().setOnes();
  return C;
}

double smallest_eigenvalue(const MatrixXd& X) { return Eigen::SelfAdjointEigenSolver<MatrixXd>(X).eigenvalues()(0); }

MatrixXd psd_part(const MatrixXd& M) {
  Eigen::SelfAdjointEigenSolver<MatrixXd> eig(M);
  return eig.eigenvectors() * eig.eigenvalues().cwiseMax(0.0).asDiagonal() * eig.eigenvectors().transpose();
}

// Dykstra's alternating projections onto the semidefinite cone and the affine set of matrices
// with the kept entries (mask) and a unit diagonal: converges to the nearest point of their
// intersection (Higham 2002's algorithm with a general fixed set).
MatrixXd dykstra(const MatrixXd& C, const Eigen::Matrix<bool, -1, -1>& mask, int iterations) {
  MatrixXd Y = C, dS = MatrixXd::Zero(C.rows(), C.cols()), X = C;
  for (int k = 0; k < iterations; ++k) {
    const MatrixXd R = Y - dS;
    X = psd_part(R);
    dS = X - R;
    Y = X;
    for (Index j = 0; j < C.cols(); ++j)
      for (Index i = 0; i < C.rows(); ++i)
        if (mask(i, j) || i == j) Y(i, j) = i == j ? 1.0 : C(i, j);
  }
  return Y;
}

TEST(NearestStructured, FixedEntriesAgreeWithDykstraAndAreExact) {
  Generator g(11);
  const Index n = 7;
  MatrixXd C = noisy_correlation(g, n);
  // A kept block taken from a correlation matrix (itself semidefinite).
  const MatrixXd Z = g.gaussian(3, 8);
  MatrixXd B = Z * Z.transpose();
  const VectorXd s = B.diagonal().cwiseSqrt().cwiseInverse();
  B = s.asDiagonal() * B * s.asDiagonal();
  C.topLeftCorner(3, 3) = B;
  Eigen::Matrix<bool, -1, -1> mask = Eigen::Matrix<bool, -1, -1>::Zero(n, n);
  mask.topLeftCorner(3, 3).setConstant(true);
  NearestStructure structure;
  structure.fixed = mask.cast<double>();
  NearestCorrelationOptions options;
  options.floor = EigenvalueFloor::absolute(0.0);
  const NearestResult r = nearest_structured(C, DiagonalRule::Unit, structure, options);
  EXPECT_TRUE(r.converged);
  EXPECT_EQ(r.fixed_entries, 3);
  // The kept entries are C's symmetric part's (C's block, a product, may be asymmetric by an ulp),
  // to the last bit.
  const MatrixXd symmetric = (C + C.transpose()) / 2;
  // (Off the diagonal: the diagonal is the unit one, which C's block has only to rounding.)
  for (Index j = 0; j < 3; ++j) {
    for (Index i = j + 1; i < 3; ++i) EXPECT_EQ(r.X(i, j), symmetric(i, j)) << i << "," << j;
  }
  EXPECT_TRUE((r.X.diagonal().array() == 1.0).all());
  // Semidefinite to the Newton method's tolerance: setting the kept entries exactly at the end
  // moves the eigenvalues by as much as the last step's residual.
  EXPECT_GT(smallest_eigenvalue(r.X), -1e-10);
  const MatrixXd reference = dykstra(C, mask, 20000);
  // Dykstra's method converges linearly and slowly: 1e-6 is its accuracy here, not ours.
  EXPECT_NEAR(r.distance, (reference - C).norm(), 1e-6 * r.distance);
  // The dual bound comes from the last, nearly feasible, dual iterate: a bound to the solver's
  // tolerance (measured here: 6e-12 relative above the distance), not a rigorous one.
  EXPECT_LE(r.lower_bound, r.distance * (1 + 1e-9));
  EXPECT_GT(r.lower_bound, r.distance * (1 - 1e-8));
}

// The variational inequality of the convex problem: <X - C, K - X> >= 0 for every admissible K
// (here: convex combinations of X with random admissible matrices: the kept entries and a unit
// diagonal, semidefinite); with H weights, <H o H o (X - C), K - X> >= 0.
TEST(NearestStructured, HWeightsSatisfyTheVariationalInequality) {
  Generator g(12);
  const Index n = 8;
  const MatrixXd C = noisy_correlation(g, n);
  MatrixXd H(n, n);
  for (Index j = 0; j < n; ++j)
    for (Index i = 0; i <= j; ++i) H(i, j) = H(j, i) = g.uniform(0.1, 1.0);
  H(0, n - 1) = H(n - 1, 0) = 0.0;
  NearestStructure structure;
  structure.h_weights = H;
  NearestCorrelationOptions options;
  options.floor = EigenvalueFloor::absolute(0.0);
  const NearestResult r = nearest_structured(C, DiagonalRule::Unit, structure, options);
  ASSERT_TRUE(r.converged);
  EXPECT_EQ(r.method, "augmented Lagrangian (H weights)");
  EXPECT_LE(r.optimality_residual, 1e-10);
  const MatrixXd gradient = H.cwiseAbs2().cwiseProduct(r.X - C);
  for (int trial = 0; trial < 50; ++trial) {
    const MatrixXd Y = g.gaussian(n, 1 + trial % n);
    MatrixXd K = Y * Y.transpose();
    const VectorXd s = K.diagonal().cwiseSqrt().cwiseInverse();
    K = s.asDiagonal() * K * s.asDiagonal();
    EXPECT_GE(gradient.cwiseProduct(K - r.X).sum(), -1e-8 * gradient.norm());
  }
  // A bound to the augmented Lagrangian's tolerance (measured here: 3e-10 relative above).
  EXPECT_LE(r.lower_bound, r.distance * (1 + 1e-9));
  EXPECT_GT(r.lower_bound, r.distance * (1 - 1e-7));
}

TEST(NearestStructured, RankOneHIsTheDiagonalWeights) {
  Generator g(13);
  const MatrixXd C = noisy_correlation(g, 6);
  VectorXd h(6);
  for (Index i = 0; i < 6; ++i) h(i) = g.uniform(0.5, 2.0);
  NearestStructure structure;
  structure.h_weights = h * h.transpose();
  NearestCorrelationOptions weighted;
  weighted.weights = h.cwiseAbs2();
  const NearestResult a = nearest_structured(C, DiagonalRule::Unit, structure);
  const NearestResult b = nearest_correlation(C, weighted);
  EXPECT_LT((a.X - b.X).cwiseAbs().maxCoeff(), 1e-12);
}

TEST(NearestStructured, InfeasibleKeptEntriesAreNamed) {
  MatrixXd C = MatrixXd::Identity(4, 4);
  const double c[4] = {0.9, 0.9, 0.9, -0.9};
  const Index pairs[4][2] = {{0, 1}, {1, 2}, {2, 3}, {3, 0}};
  for (int k = 0; k < 4; ++k) C(pairs[k][0], pairs[k][1]) = C(pairs[k][1], pairs[k][0]) = c[k];
  NearestStructure structure;
  structure.fixed = (MatrixXd(4, 2) << 1, 2, 2, 3, 3, 4, 4, 1).finished();
  try {
    nearest_structured(C, DiagonalRule::Unit, structure);
    FAIL() << "a 4-cycle without a completion was accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("no positive semidefinite matrix with the kept diagonal"), std::string::npos)
        << e.what();
  }
  MatrixXd block = MatrixXd::Zero(4, 4);
  block.topLeftCorner(3, 3).setOnes();
  structure.fixed = block;
  C(0, 2) = C(2, 0) = -0.9;
  try {
    nearest_structured(C, DiagonalRule::Unit, structure);
    FAIL() << "an indefinite kept block was accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("rows and columns 1, 2, 3 is not positive semidefinite"), std::string::npos)
        << e.what();
    EXPECT_EQ(code_of(e), Code::DataValue);
    EXPECT_EQ(subject_of(e), "fixed");
  }
}

TEST(NearestLowRank, RankIsAStationaryPointOfRankK) {
  Generator g(14);
  const Index n = 12, K = 3;
  const MatrixXd C = noisy_correlation(g, n);
  const NearestResult r = nearest_correlation_rank(C, K);
  EXPECT_TRUE(r.converged);
  EXPECT_LE(r.optimality_residual, 1e-9);
  EXPECT_EQ(r.F.cols(), K);
  EXPECT_LT((r.F * r.F.transpose() - r.X).cwiseAbs().maxCoeff(), 1e-14);
  EXPECT_TRUE((r.X.diagonal().array() == 1.0).all());
  // The Riemannian gradient, recomputed here: 4 (X - C) F with the diagonal out, projected on each
  // row's tangent space.
  MatrixXd R = r.X - C;
  R.diagonal().setZero();
  MatrixXd grad = 4.0 * R * r.F;
  for (Index i = 0; i < n; ++i) grad.row(i) -= grad.row(i).dot(r.F.row(i)) * r.F.row(i);
  EXPECT_LT(grad.norm(), 1e-7 * 4.0 * C.norm());
  EXPECT_LE(r.lower_bound, r.distance);
  EXPECT_EQ(r.starts.size(), 5u);
}

TEST(NearestLowRank, FactorsInTheBallAtAStationaryPoint) {
  Generator g(15);
  const Index n = 40, K = 4;
  const MatrixXd C = noisy_correlation(g, n, 0.2);
  NearestLowRankOptions options;
  const NearestResult r = nearest_correlation_factors(C, K, options);
  EXPECT_TRUE(r.converged);
  EXPECT_LE(r.F.rowwise().norm().maxCoeff(), 1.0 + 1e-15);
  MatrixXd X = r.F * r.F.transpose();
  X.diagonal().setOnes();
  EXPECT_LT((X - r.X).cwiseAbs().maxCoeff(), 1e-14);
  EXPECT_NEAR(r.distance, (X - C).norm(), 1e-12 * r.distance);
  options.form_x = false;
  const NearestResult only = nearest_correlation_factors(C, K, options);
  EXPECT_EQ(only.X.size(), 0);
  EXPECT_TRUE((only.F.array() == r.F.array()).all());
}

TEST(NearestLowRank, KOutOfRangeIsRefused) {
  const MatrixXd C = MatrixXd::Identity(3, 3);
  EXPECT_THROW(nearest_correlation_rank(C, 4), std::invalid_argument);
  EXPECT_THROW(nearest_correlation_rank(C, 0), std::invalid_argument);
  EXPECT_THROW(nearest_correlation_factors(C, 4), std::invalid_argument);
  // A K the data's size refuses is a data error (the front ends: exit 1, DataError) naming the option.
  try {
    nearest_correlation_rank(C, 4);
  } catch (const InputError& e) {
    EXPECT_EQ(e.code(), Code::DataShape);
    EXPECT_EQ(e.subject(), "rank");
  }
}

TEST(NearestRequest, NewOptionsCombineOnlyAsTheIssueSays) {
  const auto ok = [](std::vector<std::string_view> given) {
    EXPECT_NO_THROW(check_nearest_request(given)) << given.front();
  };
  const auto refused = [](std::vector<std::string_view> given, const std::string& first, const std::string& second) {
    try {
      check_nearest_request(given);
      ADD_FAILURE() << first << " with " << second << " was accepted";
    } catch (const OptionError& e) {
      const std::string message = e.what();
      EXPECT_NE(message.find("`" + first + "`"), std::string::npos) << message;
      EXPECT_NE(message.find("`" + second + "`"), std::string::npos) << message;
    }
  };
  ok({"fixed", "h_weights", "corr"});
  ok({"fixed", "keep_diag"});
  ok({"rank", "weights", "corr"});
  ok({"min_diag", "rank", "corr"});
  ok({"min_diag", "factors", "corr", "factors_only"});
  ok({"min_diag", "fixed", "h_weights"});
  ok({"min_diag", "via_corr"});
  refused({"fixed", "rank", "corr"}, "fixed", "rank");
  refused({"fixed", "factors", "corr"}, "fixed", "factors");
  refused({"h_weights", "rank", "corr"}, "h_weights", "rank");
  refused({"h_weights", "factors", "corr"}, "h_weights", "factors");
  refused({"rank", "factors", "corr"}, "rank", "factors");
}

TEST(RaiseVariances, RaisesAndNamesThem) {
  MatrixXd C = MatrixXd::Identity(3, 3);
  C(1, 1) = 0.0;
  C(2, 2) = -1.0;
  std::vector<Warning> warnings;
  const MatrixXd raised = raise_variances(C, 0.5, warnings);
  EXPECT_EQ(raised.diagonal(), (VectorXd(3) << 1.0, 0.5, 0.5).finished());
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_EQ(warnings[0].code, Code::DiagonalChanged);
  EXPECT_EQ(warnings[0].subject, "min_diag");
  EXPECT_NE(warnings[0].text.find("diagonal entries 2 (0), 3 (-1) were below `min_diag`"), std::string::npos)
      << warnings[0].text;
}

}  // namespace
}  // namespace spdfit
