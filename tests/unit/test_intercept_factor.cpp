// The factor of [1 A B] (TriangularFactor with an intercept, Offsets::Estimate): it carries the
// scatter of the rows about their means and the means, however the rows arrive (chunks, merges,
// counts, weights, bytes), and a fit of it does not see constant offsets, however large.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <vector>

#include <Eigen/SVD>

#include "spdfit/fit.hpp"
#include "spdfit/hexapod/model.hpp"
#include "spdfit/hexapod/simulate.hpp"
#include "numerics/cholesky_downdate.hpp"
#include "pipeline/offsets.hpp"
#include "spdfit/triangular_factor.hpp"
#include "test_support.hpp"

namespace spdfit {
namespace {

using test::Generator;
using test::kEps;
using Eigen::RowVectorXd;

// The scatter matrix sum_i (z_i - mu)(z_i - mu)^T from the factor: R^T R unscaled.
MatrixXd scatter_from_factor(const TriangularFactor& f) {
  MatrixXd R = f.R();
  R.leftCols(f.n()) *= std::ldexp(1.0, f.exponent_a());
  R.rightCols(f.d()) *= std::ldexp(1.0, f.exponent_b());
  return R.transpose() * R;
}

// The reference: [A B] centred by its column means (computed in long double), then its Gram matrix.
MatrixXd scatter_of_data(const MatrixXd& A, const MatrixXd& B, VectorXd* means) {
  MatrixXd C(A.rows(), A.cols() + B.cols());
  C << A, B;
  VectorXd mu(C.cols());
  for (Index j = 0; j < C.cols(); ++j) {
    long double sum = 0;
    for (Index i = 0; i < C.rows(); ++i) sum += C(i, j);
    mu(j) = static_cast<double>(sum / C.rows());
  }
  if (means) *means = mu;
  const MatrixXd centred = C.rowwise() - mu.transpose();
  return centred.transpose() * centred;
}

// Pieces and merges centre each part by its own means and join them by one row each: the scatter
// agrees to rounding relative to the offsets (here 1e3 times the spread).
constexpr double kScatterTolerance = 1e-12;

TEST(InterceptFactor, CarriesTheScatterAboutTheMeansAndTheMeans) {
  Generator g(11);
  MatrixXd A = g.gaussian(57, 3), B = g.gaussian(57, 2);
  A.col(1).array() += 5.0;
  B.col(0).array() -= 3.0;
  const TriangularFactor f = TriangularFactor::from_data(A, B, true);
  EXPECT_TRUE(f.intercept());
  EXPECT_EQ(f.rows(), 57);
  VectorXd mu;
  const MatrixXd S = scatter_of_data(A, B, &mu);
  EXPECT_LT((scatter_from_factor(f) - S).norm() / S.norm(), kScatterTolerance);
  EXPECT_LT((f.means() - mu).norm(), 10 * kEps * mu.norm());
}

TEST(InterceptFactor, ChunksMergesCountsAndWeightsAgree) {
  Generator g(12);
  const MatrixXd A = g.gaussian(90, 3).array() + 1e3, B = g.gaussian(90, 3).array() - 2e3;
  const TriangularFactor whole = TriangularFactor::from_data(A, B, true);
  // Appended in pieces of 7 rows.
  TriangularFactor pieces(3, 3, true);
  for (Index first = 0; first < 90; first += 7) {
    const Index len = std::min<Index>(7, 90 - first);
    pieces.append(A.middleRows(first, len), B.middleRows(first, len));
  }
  // Merged from three factors, in order.
  TriangularFactor merged = TriangularFactor::from_data(A.topRows(30), B.topRows(30), true);
  merged.merge(TriangularFactor::from_data(A.middleRows(30, 41), B.middleRows(30, 41), true));
  merged.merge(TriangularFactor::from_data(A.bottomRows(19), B.bottomRows(19), true));
  const MatrixXd S = scatter_from_factor(whole);
  for (const TriangularFactor* f : {&pieces, &merged}) {
    EXPECT_EQ(f->rows(), 90);
    EXPECT_LT((scatter_from_factor(*f) - S).norm() / S.norm(), kScatterTolerance);
    EXPECT_LT((f->means() - whole.means()).norm(), 10 * kEps * whole.means().norm());
  }
  // Counts: each row counted twice is the scatter of the rows repeated.
  MatrixXd A2(180, 3), B2(180, 3);
  A2 << A, A;
  B2 << B, B;
  TriangularFactor counted(3, 3, true);
  counted.append(A, B, std::vector<std::uint32_t>(90, 2));
  EXPECT_EQ(counted.rows(), 180);
  const MatrixXd S2 = scatter_from_factor(TriangularFactor::from_data(A2, B2, true));
  EXPECT_LT((scatter_from_factor(counted) - S2).norm() / S2.norm(), kScatterTolerance);
  // Real weights 2: the same scatter, but 90 rows.
  TriangularFactor weighted(3, 3, true);
  weighted.append(A, B, VectorXd::Constant(90, 2.0));
  EXPECT_EQ(weighted.rows(), 90);
  EXPECT_LT((scatter_from_factor(weighted) - S2).norm() / S2.norm(), kScatterTolerance);
  // Merged with counts: a factor counted twice.
  TriangularFactor twice(3, 3, true);
  twice.merge({&whole}, {2});
  EXPECT_LT((scatter_from_factor(twice) - S2).norm() / S2.norm(), kScatterTolerance);
}

TEST(InterceptFactor, SerializesInLayoutThree) {
  Generator g(13);
  const TriangularFactor f = TriangularFactor::from_data(g.gaussian(20, 2), g.gaussian(20, 3), true);
  const std::string bytes = f.serialize();
  EXPECT_EQ(bytes[8], 3);
  const TriangularFactor back = TriangularFactor::deserialize(bytes);
  EXPECT_TRUE(back.intercept());
  EXPECT_EQ(back.serialize(), bytes);
  EXPECT_EQ(back.means(), f.means());
  EXPECT_THROW(TriangularFactor::merged(f, TriangularFactor::from_data(g.gaussian(5, 2), g.gaussian(5, 3))),
               std::invalid_argument);
}

// Offsets 1e4 times the columns' spread change no estimate beyond rounding: X to 1e-10 relative
// (the goal), for every method, the offsets c recovered.
TEST(InterceptFactor, OffsetsDoNotMoveTheEstimate) {
  Generator g(14);
  const Index m = 200, n = 3;
  const MatrixXd A0 = g.gaussian(m, n);
  const MatrixXd X = g.spd(n, 5.0);
  const MatrixXd B0 = A0 * X + 0.05 * g.gaussian(m, n);
  const RowVectorXd a = RowVectorXd::Constant(n, 1e4), b = (RowVectorXd(n) << -2e4, 3e4, 1e4).finished();
  const MatrixXd A = A0.rowwise() + a, B = B0.rowwise() + b;
  FitOptions options;
  options.offsets = Offsets::Estimate;
  for (Method method : {Method::LeastSquares, Method::SymmetricProcrustes, Method::Spde, Method::SpdTotalLeastSquares,
                        Method::PsdLeastSquares, Method::Auto}) {
    const FitResult shifted = fit(A, B, method, options);
    const FitResult plain = fit(A0, B0, method, options);
    ASSERT_TRUE(shifted.ok() && plain.ok()) << to_string(method);
    EXPECT_LT((shifted.X - plain.X).norm() / plain.X.norm(), 1e-10) << to_string(method);
    ASSERT_TRUE(shifted.offsets && plain.offsets) << to_string(method);
    ASSERT_EQ(shifted.offsets->c.size(), n);
    // c = b - a X + (the centred data's own offsets, the same for both).
    const VectorXd expected = plain.offsets->c + b.transpose() - plain.X.transpose() * a.transpose();
    EXPECT_LT((shifted.offsets->c - expected).norm() / expected.norm(), 1e-10) << to_string(method);
    EXPECT_EQ(shifted.diagnostics.m, m);
  }
}

// The fit with an intercept equals least squares of B on [1 A] (an independent solve).
TEST(InterceptFactor, LeastSquaresWithAnInterceptIsTheAugmentedSolve) {
  Generator g(15);
  const MatrixXd A = g.gaussian(60, 3).array() + 7.0;
  const MatrixXd B = g.gaussian(60, 2).array() - 4.0;
  FitOptions options;
  options.offsets = Offsets::Estimate;
  const FitResult r = fit(A, B, Method::LeastSquares, options);
  ASSERT_TRUE(r.offsets);
  MatrixXd Z(60, 4);
  Z << VectorXd::Ones(60), A;
  const MatrixXd coef = Z.colPivHouseholderQr().solve(B);
  EXPECT_LT((r.X - coef.bottomRows(3)).norm() / coef.norm(), 1e-12);
  EXPECT_LT((r.offsets->c - coef.row(0).transpose()).norm() / coef.norm(), 1e-12);
}

// Offsets rest: the fit of the data with the rest rows' means subtracted (by hand, here), and the
// noise estimate of centred data divides by m - 1 - n degrees of freedom, not m - n.
TEST(InterceptFactor, RestTaresAndTheNoiseEstimateCountsTheLostDegreeOfFreedom) {
  Generator g(16);
  const Index m = 80, n = 2, k = 40;
  const MatrixXd A = g.gaussian(m, n), rest_a = 0.1 * g.gaussian(k, n);
  MatrixXd B = A * g.spd(n, 3.0) + 0.1 * g.gaussian(m, n);
  MatrixXd rest_b = 0.1 * g.gaussian(k, n);
  B.col(0).array() += 21.0;
  rest_b.col(0).array() += 21.0;
  FitOptions options;
  options.noise = NoiseModel::from_rest(rest_a, rest_b);
  options.offsets = Offsets::Rest;
  const FitResult tared = fit(A, B, Method::SpdTotalLeastSquares, options);
  FitOptions by_hand = options;
  by_hand.offsets = Offsets::None;
  const MatrixXd At = A.rowwise() - rest_a.colwise().mean(), Bt = B.rowwise() - rest_b.colwise().mean();
  const FitResult reference = fit(At, Bt, Method::SpdTotalLeastSquares, by_hand);
  ASSERT_TRUE(tared.ok() && reference.ok() && tared.offsets);
  EXPECT_LT((tared.X - reference.X).norm() / reference.X.norm(), 1e-12);
  EXPECT_LT((tared.offsets->b - rest_b.colwise().mean().transpose()).norm(), 1e-12 * 21.0);
  // tls's noise estimate: the d smallest singular values of the centred [A B], over d (m - 1 - n).
  FitOptions estimate;
  estimate.offsets = Offsets::Estimate;
  const FitResult tls = fit(A, B, Method::TotalLeastSquares, estimate);
  MatrixXd C(m, 2 * n);
  C << A, B;
  C = C.rowwise() - C.colwise().mean();
  const VectorXd s = C.jacobiSvd().singularValues();
  const double expected = std::sqrt(s.tail(n).squaredNorm() / static_cast<double>(n * (m - 1 - n)));
  ASSERT_TRUE(tls.ok() && tls.diagnostics.noise_sigma);
  EXPECT_NEAR(*tls.diagnostics.noise_sigma, expected, 1e-12 * expected);
}

// hexapod simulate --preload (SimulationOptions::rest_force): the static load is in every row of B,
// moving or at rest, as an untared logger writes it; and offsets rest then gives the tared fit.
TEST(InterceptFactor, SimulatedPreloadIsInEveryRowAndRestRemovesIt) {
  hexapod::SimulationOptions options;
  options.samples = 3000;
  options.rest_samples = 3000;
  options.noise_var = 0.01;
  options.rest_force = VectorXd::LinSpaced(6, 10.0, 60.0);
  const hexapod::Measurements data = hexapod::simulate(hexapod::thesis_mass_matrix(), options, 5);
  const double se = 5.0 * std::sqrt(0.01 / 3000.0);
  EXPECT_LT(((data.B - data.B_true).colwise().mean().transpose() - options.rest_force).cwiseAbs().maxCoeff(), se);
  EXPECT_LT((data.rest_B.colwise().mean().transpose() - options.rest_force).cwiseAbs().maxCoeff(), se);
  FitOptions fit_options;
  fit_options.noise = NoiseModel::from_rest(data.rest_A, data.rest_B);
  fit_options.offsets = Offsets::Rest;
  const FitResult tared = fit(data.A, data.B, Method::SpdTotalLeastSquares, fit_options);
  fit_options.offsets = Offsets::None;
  const FitResult untared = fit(data.A, data.B, Method::SpdTotalLeastSquares, fit_options);
  ASSERT_TRUE(tared.ok() && untared.ok());
  const MatrixXd truth = hexapod::thesis_mass_matrix();
  EXPECT_LT((tared.X - truth).norm(), 0.05 * truth.norm());
  EXPECT_GT((untared.X - truth).norm(), 10 * (tared.X - truth).norm());
  // The untared fit says so, naming the option.
  bool warned = false;
  for (const Warning& w : untared.warnings) warned = warned || (w.subject == "offsets" && w.code == Code::Bias);
  EXPECT_TRUE(warned);
}

// The rank-one downdate that gives the centred factor from the plain one (an intercept warning
// for a fit without an intercept): Rc^T Rc = R^T R - x x^T to rounding, against the Gram matrices
// formed directly; refused where the difference is not positive definite or R is singular.
TEST(InterceptFactor, DowndateOfTheTriangularFactorIsTheCentredFactor) {
  Generator gen(41);
  const Index m = 400, k = 7;
  MatrixXd Z = gen.gaussian(m, k);
  Z.rowwise() += RowVectorXd::LinSpaced(k, -30.0, 50.0);  // offsets of 30-50 spreads
  const Eigen::HouseholderQR<MatrixXd> qr(Z);
  const MatrixXd R = qr.matrixQR().topRows(k).triangularView<Eigen::Upper>();
  const VectorXd mean = Z.colwise().mean().transpose();
  const VectorXd x = std::sqrt(static_cast<double>(m)) * mean;
  MatrixXd Rc;
  ASSERT_TRUE(detail::cholesky_downdate(R, x, Rc));
  EXPECT_TRUE(MatrixXd(Rc.triangularView<Eigen::StrictlyLower>()).isZero(0.0));
  const MatrixXd centred = Z.rowwise() - mean.transpose();
  const MatrixXd expected = centred.transpose() * centred;
  // Offsets of 50 spreads cost about 50^2 in the relative accuracy of the difference.
  EXPECT_LT((Rc.transpose() * Rc - expected).norm(), 1e-12 * (R.transpose() * R).norm());
  // ||R^-T x|| of 1 or more: R^T R - x x^T is singular or indefinite.
  MatrixXd unused;
  const VectorXd along = R.transpose() * VectorXd::Unit(k, 2);  // ||R^-T along|| = 1
  EXPECT_FALSE(detail::cholesky_downdate(R, 1.0000001 * along, unused));
  EXPECT_TRUE(detail::cholesky_downdate(R, 0.999 * along, unused));
  MatrixXd singular = R;
  singular(3, 3) = 0.0;
  EXPECT_FALSE(detail::cholesky_downdate(singular, x, unused));
}

// The offset warning from the plain factor (the downdate) says what it says from the factor of
// [1 A B] made from the rows.
TEST(InterceptFactor, OffsetWarningFromThePlainFactorAgreesWithTheRows) {
  Generator gen(43);
  const Index m = 300, n = 3;
  const MatrixXd X = gen.spd(n, 10.0);
  const MatrixXd A = gen.gaussian(m, n).array() + 1.0;
  MatrixXd B = A * X + 0.05 * gen.gaussian(m, n);
  B.rowwise() += RowVectorXd::Constant(n, 2.0);
  const FitOptions options;
  const TriangularFactor plain = TriangularFactor::from_data(A, B, false);
  const std::vector<Warning> from_plain = detail::offset_warnings(A, B, &plain, options);
  const std::vector<Warning> from_rows = detail::offset_warnings(A, B, nullptr, options);
  ASSERT_EQ(from_plain.size(), 1u);
  ASSERT_EQ(from_rows.size(), 1u);
  EXPECT_EQ(from_plain[0].code, Code::Bias);
  EXPECT_EQ(from_plain[0].text, from_rows[0].text);
  // No offsets: no warning either way.
  const MatrixXd B0 = A * X + 0.05 * gen.gaussian(m, n);
  const TriangularFactor plain0 = TriangularFactor::from_data(A, B0, false);
  EXPECT_TRUE(detail::offset_warnings(A, B0, &plain0, options).empty());
  EXPECT_TRUE(detail::offset_warnings(A, B0, nullptr, options).empty());
}

}  // namespace
}  // namespace spdfit
