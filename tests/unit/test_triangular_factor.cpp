// The triangular factor carries the Gram matrix of [A B] exactly (to rounding), however the
// rows arrive, and keeps data of any scale representable.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <vector>

#include "spdfit/triangular_factor.hpp"
#include "test_support.hpp"

namespace spdfit {
namespace {

using test::Generator;
using test::kEps;

// R^T R (unscaled) against [A B]^T [A B]: the defining identity of the factor.
MatrixXd gram_from_factor(const TriangularFactor& f) {
  const Index n = f.n();
  MatrixXd R = f.R();
  R.leftCols(n) *= std::ldexp(1.0, f.exponent_a());
  R.rightCols(n) *= std::ldexp(1.0, f.exponent_b());
  return R.transpose() * R;
}

// The factor of the unscaled data: R with its A columns times 2^ea * a_factor and its B
// columns times 2^eb * b_factor.
MatrixXd unscaled(const TriangularFactor& f, double a_factor, double b_factor) {
  const Index n = f.n();
  MatrixXd R = f.R();
  R.leftCols(n) = R.leftCols(n).unaryExpr([&](double x) { return std::ldexp(x, f.exponent_a()) * a_factor; });
  R.rightCols(n) =
      R.rightCols(n).unaryExpr([&](double x) { return std::ldexp(x, f.exponent_b()) * b_factor; });
  return R;
}

MatrixXd gram_of_data(const MatrixXd& A, const MatrixXd& B) {
  MatrixXd C(A.rows(), A.cols() + B.cols());
  C << A, B;
  return C.transpose() * C;
}

// Rounding of a Householder QR and of one Gram product: a few n eps relative to ||C||^2.
constexpr double kGramTolerance = 100 * kEps;

TEST(TriangularFactor, IsUpperTriangularAndReproducesTheGramMatrix) {
  Generator g(1);
  const MatrixXd A = g.gaussian(40, 5), B = g.gaussian(40, 5);
  const TriangularFactor f = TriangularFactor::from_data(A, B);
  EXPECT_EQ(f.rows(), 40);
  EXPECT_EQ(f.n(), 5);
  EXPECT_TRUE(f.R().isUpperTriangular(0.0));
  const MatrixXd G = gram_of_data(A, B);
  EXPECT_LT((gram_from_factor(f) - G).norm() / G.norm(), kGramTolerance);
}

TEST(TriangularFactor, ScaledColumnsAreTheFactorOfTheScaledData) {
  // FitOptions::scale_a and scale_b on a streamed factor: R diag(a, b) is a factor of
  // [A diag(a), B diag(b)], whatever the factors (kN to N, g to m/s^2, tiny ones).
  Generator g(7);
  const MatrixXd A = g.gaussian(60, 4), B = g.gaussian(60, 4);
  Eigen::VectorXd a(4), b(4);
  a << 9.80665, 1.0, 1e-3, 3.0;
  b << 1000.0, 1000.0, 0.5, 1e6;
  TriangularFactor f = TriangularFactor::from_data(A, B);
  f.scale_columns(a, b);
  EXPECT_EQ(f.rows(), 60);
  EXPECT_TRUE(f.R().isUpperTriangular(0.0));
  const MatrixXd G = gram_of_data(A * a.asDiagonal(), B * b.asDiagonal());
  EXPECT_LT((gram_from_factor(f) - G).norm() / G.norm(), kGramTolerance);
  EXPECT_THROW(f.scale_columns(Eigen::VectorXd::Ones(3), b), std::invalid_argument);
  EXPECT_THROW(f.scale_columns(-a, b), std::invalid_argument);
}

TEST(TriangularFactor, ChunksAndMergesGiveTheSameGramMatrix) {
  Generator g(2);
  const MatrixXd A = g.gaussian(100, 4), B = g.gaussian(100, 4);
  TriangularFactor chunked(4);
  for (Index start = 0; start < 100; start += 7) {
    const Index rows = std::min<Index>(7, 100 - start);
    chunked.append(A.middleRows(start, rows), B.middleRows(start, rows));
  }
  TriangularFactor first = TriangularFactor::from_data(A.topRows(30), B.topRows(30));
  const TriangularFactor second = TriangularFactor::from_data(A.bottomRows(70), B.bottomRows(70));
  first.merge(second);
  const MatrixXd G = gram_of_data(A, B);
  EXPECT_EQ(chunked.rows(), 100);
  EXPECT_EQ(first.rows(), 100);
  EXPECT_LT((gram_from_factor(chunked) - G).norm() / G.norm(), kGramTolerance);
  EXPECT_LT((gram_from_factor(first) - G).norm() / G.norm(), kGramTolerance);
}

TEST(TriangularFactor, FewerRowsThanTwiceTheColumnsLeavesZeroRows) {
  Generator g(3);
  const MatrixXd A = g.gaussian(5, 4), B = g.gaussian(5, 4);
  const TriangularFactor f = TriangularFactor::from_data(A, B);
  EXPECT_EQ(f.R().bottomRows(3).norm(), 0.0);
  const MatrixXd G = gram_of_data(A, B);
  EXPECT_LT((gram_from_factor(f) - G).norm() / G.norm(), kGramTolerance);
}

TEST(TriangularFactor, ScalesExtremeDataByPowersOfTwo) {
  Generator g(4);
  const MatrixXd A = g.gaussian(10, 3), B = g.gaussian(10, 3);
  const TriangularFactor reference = TriangularFactor::from_data(A, B);
  const MatrixXd R_ref = unscaled(reference, 1.0, 1.0);
  for (double scale : {1e-300, 1e-160, 1.0, 1e160, 1e300}) {
    const TriangularFactor f = TriangularFactor::from_data(A * scale, B / scale);
    EXPECT_TRUE(f.R().allFinite());
    EXPECT_LE(f.R().cwiseAbs().maxCoeff(), std::sqrt(10.0));  // scaled entries below 1 in magnitude
    // Undoing both the stored powers of two and the data's scale gives the same factor to
    // rounding (the data differ from A and B by a rounding each).
    EXPECT_LT((unscaled(f, 1.0 / scale, scale) - R_ref).norm() / R_ref.norm(), 1e-14) << scale;
  }
  // A power-of-two scaling changes no bit of the stored factor.
  const TriangularFactor exact =
      TriangularFactor::from_data(std::ldexp(1.0, 700) * A, std::ldexp(1.0, -900) * B);
  EXPECT_TRUE(exact.R() == reference.R());
  EXPECT_EQ(exact.exponent_a(), reference.exponent_a() + 700);
  EXPECT_EQ(exact.exponent_b(), reference.exponent_b() - 900);
}

TEST(TriangularFactor, ZeroFirstChunkDoesNotFixTheScale) {
  Generator g(5);
  const MatrixXd A = g.gaussian(6, 2) * 1e-200, B = g.gaussian(6, 2) * 1e-200;
  TriangularFactor f(2);
  f.append(MatrixXd::Zero(3, 2), MatrixXd::Zero(3, 2));
  f.append(A, B);
  EXPECT_LT(f.exponent_a(), -600);
  EXPECT_GT(f.R().cwiseAbs().maxCoeff(), 0.1);
}

TEST(TriangularFactor, LaterLargerChunkRaisesTheScale) {
  Generator g(6);
  const MatrixXd A1 = g.gaussian(6, 2), B1 = g.gaussian(6, 2);
  const MatrixXd A2 = g.gaussian(6, 2) * 1e250, B2 = g.gaussian(6, 2) * 1e250;
  TriangularFactor f = TriangularFactor::from_data(A1, B1);
  f.append(A2, B2);
  MatrixXd A(12, 2), B(12, 2);
  A << A1, A2;
  B << B1, B2;
  const TriangularFactor whole = TriangularFactor::from_data(A, B);
  EXPECT_EQ(f.exponent_a(), whole.exponent_a());
  EXPECT_LT(((f.R().transpose() * f.R()) - (whole.R().transpose() * whole.R())).norm() /
                (whole.R().transpose() * whole.R()).norm(),
            kGramTolerance);
}

TEST(TriangularFactor, RejectsMisuse) {
  EXPECT_THROW(TriangularFactor(0), std::invalid_argument);
  EXPECT_THROW(TriangularFactor(2, 0), std::invalid_argument);
  TriangularFactor wide(2, 3);  // B may have other columns than A, but always the factor's
  EXPECT_THROW(wide.append(MatrixXd::Ones(4, 2), MatrixXd::Ones(4, 2)), std::invalid_argument);
  EXPECT_NO_THROW(wide.append(MatrixXd::Ones(4, 2), MatrixXd::Ones(4, 3)));
  EXPECT_THROW(TriangularFactor::from_data(MatrixXd::Ones(4, 2), MatrixXd::Ones(3, 2)),
               std::invalid_argument);
  MatrixXd bad = MatrixXd::Ones(4, 2);
  bad(1, 1) = std::nan("");
  EXPECT_THROW(TriangularFactor::from_data(bad, MatrixXd::Ones(4, 2)), std::invalid_argument);
  bad(1, 1) = INFINITY;
  EXPECT_THROW(TriangularFactor::from_data(MatrixXd::Ones(4, 2), bad), std::invalid_argument);
  TriangularFactor f(2);
  EXPECT_THROW(f.merge(TriangularFactor(3)), std::invalid_argument);
}

// Frequency weights: rows counted c times are the factor of the data with those rows repeated
// (what a bootstrap resample is), without the copies.
TEST(TriangularFactor, CountedRowsAreRepeatedRows) {
  Generator g(31);
  const Index m = 2500;  // more than one internal chunk of counted rows
  const MatrixXd A = g.gaussian(m, 3) * 1e5, B = g.gaussian(m, 3) * 1e-7;
  std::vector<std::uint32_t> counts(static_cast<std::size_t>(m));
  Index repeated = 0;
  for (Index i = 0; i < m; ++i) {
    counts[static_cast<std::size_t>(i)] = static_cast<std::uint32_t>(i % 4);  // 0, 1, 2, 3
    repeated += i % 4;
  }
  MatrixXd Ar(repeated, 3), Br(repeated, 3);
  Index at = 0;
  for (Index i = 0; i < m; ++i) {
    for (Index c = 0; c < i % 4; ++c, ++at) {
      Ar.row(at) = A.row(i);
      Br.row(at) = B.row(i);
    }
  }
  TriangularFactor counted(3);
  counted.append(A, B, counts);
  EXPECT_EQ(counted.rows(), repeated);
  const MatrixXd G = gram_of_data(Ar, Br);
  const MatrixXd scale = G.diagonal().cwiseSqrt() * G.diagonal().cwiseSqrt().transpose();
  EXPECT_LT((gram_from_factor(counted) - G).cwiseQuotient(scale).cwiseAbs().maxCoeff(), kGramTolerance);
  // All zero counts: nothing added.
  TriangularFactor empty(3);
  empty.append(A, B, std::vector<std::uint32_t>(static_cast<std::size_t>(m), 0));
  EXPECT_EQ(empty.rows(), 0);
  EXPECT_THROW(empty.append(A, B, std::vector<std::uint32_t>(3, 1)), std::invalid_argument);
}

TEST(TriangularFactor, WeightedMergeCountsEachFactorsRows) {
  Generator g(32);
  std::vector<MatrixXd> As, Bs;
  std::vector<TriangularFactor> parts;
  for (int k = 0; k < 4; ++k) {
    As.push_back(g.gaussian(30, 2) * std::ldexp(1.0, 40 * k));
    Bs.push_back(g.gaussian(30, 2));
    parts.push_back(TriangularFactor::from_data(As.back(), Bs.back()));
  }
  const std::vector<std::uint32_t> counts = {2, 0, 1, 3};
  TriangularFactor merged(2);
  std::vector<const TriangularFactor*> pointers;
  for (const TriangularFactor& p : parts) pointers.push_back(&p);
  merged.merge(pointers, counts);
  EXPECT_EQ(merged.rows(), 30 * (2 + 0 + 1 + 3));
  MatrixXd G = MatrixXd::Zero(4, 4);
  for (int k = 0; k < 4; ++k) G += counts[static_cast<std::size_t>(k)] * gram_of_data(As[k], Bs[k]);
  const MatrixXd scale = G.diagonal().cwiseSqrt() * G.diagonal().cwiseSqrt().transpose();
  EXPECT_LT((gram_from_factor(merged) - G).cwiseQuotient(scale).cwiseAbs().maxCoeff(), kGramTolerance);
  EXPECT_THROW(merged.merge(pointers, {1, 2}), std::invalid_argument);
  const TriangularFactor other(3);
  EXPECT_THROW(merged.merge({&other}, {1}), std::invalid_argument);
}

}  // namespace
}  // namespace spdfit
