// spdfit's block QR (src/numerics/block_qr.hpp): R <- the R of [R; C], built for several
// instruction sets and chosen at run time. Checked against Eigen's HouseholderQR (an independent
// implementation: R agrees entry by entry up to the signs of its rows, which depend on the
// reflectors' heads, not only R^T R), against the Gram matrix it must reproduce, and variant
// against variant bit for bit (every variant this CPU runs).
#include <gtest/gtest.h>

#include <Eigen/QR>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <vector>

#include "numerics/block_qr.hpp"
#include "spdfit/blas.hpp"
#include "numerics/linalg.hpp"
#include "spdfit/triangular_factor.hpp"

namespace {

using Eigen::Index;
using Eigen::MatrixXd;
using spdfit::detail::VectorIsa;

constexpr double kEps = std::numeric_limits<double>::epsilon();

std::vector<VectorIsa> variants_of_this_cpu() {
  std::vector<VectorIsa> out;
  for (VectorIsa isa : {VectorIsa::Baseline, VectorIsa::Avx2, VectorIsa::Avx512}) {
    if (isa <= spdfit::detail::cpu_vector_isa()) out.push_back(isa);
  }
  return out;
}

MatrixXd eigen_r(const MatrixXd& A) {
  const Eigen::HouseholderQR<MatrixXd> qr(A);
  return qr.matrixQR().topRows(A.cols()).triangularView<Eigen::Upper>();
}

// R with its rows' signs chosen so that the diagonal is nonnegative: the R of a full-rank A is
// unique up to those signs.
MatrixXd signed_rows(MatrixXd R) {
  for (Index i = 0; i < R.rows(); ++i) {
    if (R(i, i) < 0.0) R.row(i) *= -1.0;
  }
  return R;
}

MatrixXd block_r(VectorIsa isa, const MatrixXd& A) {
  MatrixXd R = MatrixXd::Zero(A.cols(), A.cols());
  MatrixXd C = A;
  spdfit::detail::absorb_into_triangle(isa, R, C);
  return R;
}

// Relative to ||A||^2: the backward error of a Householder QR is a modest multiple of eps ||A||
// (Higham, Accuracy and Stability, Theorem 19.4), so R^T R - A^T A is within about m eps ||A||^2
// in the worst case and within a few eps ||A||^2 in practice for random data.
double gram_error(const MatrixXd& R, const MatrixXd& A) {
  return (R.transpose() * R - A.transpose() * A).norm() / A.squaredNorm();
}

TEST(BlockQr, MatchesEigenHouseholderOnEveryVariant) {
  std::srand(7);
  // Shapes below, at and above a chunk (32768 / k rows, at least 128), narrow and wider.
  for (const auto& [m, k] : std::vector<std::pair<Index, Index>>{
           {1, 1}, {5, 5}, {12, 12}, {13, 12}, {200, 3}, {3000, 12}, {5000, 40}, {700, 63}, {9, 2}}) {
    const MatrixXd A = MatrixXd::Random(m, k);
    const MatrixXd reference = signed_rows(eigen_r(A));
    const double scale = A.norm();
    for (VectorIsa isa : variants_of_this_cpu()) {
      SCOPED_TRACE(std::string(spdfit::detail::vector_isa_name(isa)) + " m=" + std::to_string(m) +
                   " k=" + std::to_string(k));
      const MatrixXd R = block_r(isa, A);
      EXPECT_TRUE(R.isUpperTriangular(0.0));
      EXPECT_LE((signed_rows(R) - reference).norm(), 100 * kEps * static_cast<double>(m) * scale);
      EXPECT_LE(gram_error(R, A), 100 * kEps);
    }
  }
}

TEST(BlockQr, VariantsGiveTheSameBits) {
  std::srand(11);
  const MatrixXd A = MatrixXd::Random(10000, 14);
  const MatrixXd baseline = block_r(VectorIsa::Baseline, A);
  for (VectorIsa isa : variants_of_this_cpu()) {
    SCOPED_TRACE(spdfit::detail::vector_isa_name(isa));
    const MatrixXd R = block_r(isa, A);
    EXPECT_EQ(std::memcmp(R.data(), baseline.data(), sizeof(double) * static_cast<std::size_t>(R.size())), 0)
        << "largest difference " << (R - baseline).cwiseAbs().maxCoeff();
  }
}

TEST(BlockQr, AbsorbsRowsUnderAnExistingTriangle) {
  // Folding C under R = the R of A1 gives the R of [A1; C]: R^T R = A1^T A1 + C^T C.
  std::srand(3);
  const MatrixXd A1 = MatrixXd::Random(50, 8), C = MatrixXd::Random(777, 8);
  MatrixXd stacked(A1.rows() + C.rows(), 8);
  stacked << A1, C;
  for (VectorIsa isa : variants_of_this_cpu()) {
    MatrixXd R = eigen_r(A1);
    MatrixXd work = C;
    spdfit::detail::absorb_into_triangle(isa, R, work);
    EXPECT_LE((signed_rows(R) - signed_rows(eigen_r(stacked))).norm(),
              100 * kEps * static_cast<double>(stacked.rows()) * stacked.norm());
    EXPECT_LE(gram_error(R, stacked), 100 * kEps);
  }
}

TEST(BlockQr, ZeroAndRankDeficientColumns) {
  // A zero column is skipped (H = I, R's column zero there) and a repeated column gives a zero
  // diagonal entry below it, as Eigen's QR does.
  std::srand(5);
  MatrixXd A = MatrixXd::Random(300, 5);
  A.col(1).setZero();
  A.col(3) = A.col(0);
  for (VectorIsa isa : variants_of_this_cpu()) {
    const MatrixXd R = block_r(isa, A);
    EXPECT_EQ(R(1, 1), 0.0);
    EXPECT_LE(std::abs(R(3, 3)), 100 * kEps * A.norm());
    EXPECT_LE(gram_error(R, A), 100 * kEps);
    EXPECT_TRUE(R.allFinite());
  }
  const MatrixXd Z = MatrixXd::Zero(40, 4);
  EXPECT_EQ(block_r(spdfit::detail::kernel_isa(), Z), MatrixXd::Zero(4, 4));
}

TEST(BlockQr, RefusesMismatchedShapes) {
  MatrixXd R = MatrixXd::Zero(3, 3), C = MatrixXd::Zero(5, 4);
  EXPECT_THROW(spdfit::detail::absorb_into_triangle(R, C), std::invalid_argument);
}

TEST(BlockQr, TriangularFactorUsesItAndStaysAccurate) {
  // The QR every in-memory fit and streamed block runs below 64 columns; ill-conditioned columns
  // (scaled over 12 orders of magnitude) keep R accurate column by column, as Householder does.
  std::srand(9);
  MatrixXd A = MatrixXd::Random(20000, 10);
  for (Index j = 0; j < A.cols(); ++j) A.col(j) *= std::pow(10.0, -static_cast<double>(j) * 1.2);
  const MatrixXd R = signed_rows(spdfit::detail::triangular_factor(A));
  const MatrixXd reference = signed_rows(eigen_r(A));
  for (Index j = 0; j < A.cols(); ++j) {
    EXPECT_LE((R.col(j) - reference.col(j)).norm(), 1e3 * kEps * A.col(j).norm()) << "column " << j;
  }
}

TEST(BlockQr, KernelChoiceIsReported) {
  const std::string report = spdfit::kernel_isa_report();
  EXPECT_NE(report.find(spdfit::detail::vector_isa_name(spdfit::detail::kernel_isa())), std::string::npos);
  EXPECT_LE(spdfit::detail::kernel_isa(), spdfit::detail::cpu_vector_isa());
}

}  // namespace

namespace {

TEST(BlockQr, ChunkedAppendHasTheBitsOfOnePass) {
  // TriangularFactor::append takes its rows in the QR's chunks and raises the exponents chunk by
  // chunk; the rows grow by 2^20 halfway (A) and 2^-30 then 2^40 (B), so R is rescaled mid-way. It
  // must give the bits of the QR of all the rows, scaled by the final exponents, in one call.
  std::srand(21);
  const Index m = 9000, n = 4, d = 3;
  MatrixXd A = MatrixXd::Random(m, n), B = MatrixXd::Random(m, d);
  A.bottomRows(m / 2) *= std::ldexp(1.0, 20);
  B.topRows(m / 3) *= std::ldexp(1.0, -30);
  B.bottomRows(100) *= std::ldexp(1.0, 40);
  const spdfit::TriangularFactor f = spdfit::TriangularFactor::from_data(A, B);
  MatrixXd scaled(m, n + d);
  scaled << A * std::ldexp(1.0, -f.exponent_a()), B * std::ldexp(1.0, -f.exponent_b());
  const MatrixXd expected = spdfit::detail::triangular_factor_in_place(scaled);
  EXPECT_GT(m, spdfit::detail::absorb_chunk_rows(n + d));  // more than one chunk
  EXPECT_EQ(std::memcmp(f.R().data(), expected.data(), sizeof(double) * static_cast<std::size_t>(expected.size())),
            0)
      << "largest difference " << (f.R() - expected).cwiseAbs().maxCoeff();
  EXPECT_EQ(f.rows(), m);
}

TEST(BlockQr, AppendWithNanLeavesTheFactorAsItWas) {
  // The NaN is in a later chunk than the first: the chunks before it must not stay folded in.
  std::srand(22);
  const MatrixXd A0 = MatrixXd::Random(300, 3), B0 = MatrixXd::Random(300, 3);
  spdfit::TriangularFactor f = spdfit::TriangularFactor::from_data(A0, B0);
  const std::string before = f.serialize();
  MatrixXd A = MatrixXd::Random(20000, 3) * 1e6, B = MatrixXd::Random(20000, 3);
  B(19000, 2) = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(f.append(A, B), std::invalid_argument);
  EXPECT_EQ(f.serialize(), before);
}

}  // namespace
