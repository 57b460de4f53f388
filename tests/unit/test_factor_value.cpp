// TriangularFactor as a value (for MPI and pickling): merged() leaves its inputs alone and gives
// the factor of the union; serialize/deserialize round-trip bit for bit and refuse bytes that are
// not a factor, saying why.
#include <gtest/gtest.h>

#include <stdexcept>
#include <string>

#include "spdfit/fit.hpp"
#include "spdfit/triangular_factor.hpp"
#include "test_support.hpp"

namespace spdfit {
namespace {

using test::Generator;

// R is unique up to the signs of its rows: compare R^T R, the Gram matrix of [A B] (scaled).
double gram_difference(const TriangularFactor& a, const TriangularFactor& b) {
  return (a.R().transpose() * a.R() - b.R().transpose() * b.R()).norm() / (a.R().transpose() * a.R()).norm();
}

TEST(FactorValue, MergedIsTheFactorOfTheUnionAndLeavesItsInputsAlone) {
  Generator g(1);
  const MatrixXd A = g.gaussian(40, 3), B = g.gaussian(40, 3) * 1e5;
  const TriangularFactor top = TriangularFactor::from_data(A.topRows(25), B.topRows(25));
  const TriangularFactor bottom = TriangularFactor::from_data(A.bottomRows(15), B.bottomRows(15));
  const std::string top_before = top.serialize(), bottom_before = bottom.serialize();
  const TriangularFactor both = TriangularFactor::merged(top, bottom);
  EXPECT_EQ(top.serialize(), top_before);
  EXPECT_EQ(bottom.serialize(), bottom_before);
  const TriangularFactor whole = TriangularFactor::from_data(A, B);
  EXPECT_EQ(both.rows(), 40);
  EXPECT_EQ(both.exponent_a(), whole.exponent_a());
  EXPECT_EQ(both.exponent_b(), whole.exponent_b());
  EXPECT_LT(gram_difference(both, whole), 1e-14);
  EXPECT_LT((fit(reduce(both), Method::Spde).X - fit(A, B, Method::Spde).X).norm(),
            1e-12 * fit(A, B, Method::Spde).X.norm());
  EXPECT_THROW(TriangularFactor::merged(top, TriangularFactor(4)), std::invalid_argument);
}

TEST(FactorValue, SerializeRoundTripsBitForBit) {
  Generator g(2);
  for (const Index m : {Index{0}, Index{2}, Index{30}}) {
    TriangularFactor f(3);
    if (m > 0) f.append(g.gaussian(m, 3) * 1e-200, g.gaussian(m, 3) * 1e200);
    const std::string bytes = f.serialize();
    EXPECT_EQ(bytes.size(), 8u + 4 + 8 + 8 + 2 * 5 + 8 * 21);
    const TriangularFactor back = TriangularFactor::deserialize(bytes);
    EXPECT_EQ(back.n(), 3);
    EXPECT_EQ(back.rows(), m);
    EXPECT_EQ(back.exponent_a(), f.exponent_a());
    EXPECT_EQ(back.exponent_b(), f.exponent_b());
    EXPECT_EQ(back.R(), f.R());
    EXPECT_EQ(back.serialize(), bytes);
  }
  // A factor whose A is all zero so far keeps "no exponent" across the round trip: merging data
  // into it later behaves as merging into the original.
  TriangularFactor zero_a(2);
  zero_a.append(MatrixXd::Zero(3, 2), MatrixXd::Ones(3, 2));
  const TriangularFactor back = TriangularFactor::deserialize(zero_a.serialize());
  const TriangularFactor more = TriangularFactor::from_data(MatrixXd::Identity(2, 2) * 1e10, MatrixXd::Ones(2, 2));
  EXPECT_EQ(TriangularFactor::merged(back, more).R(), TriangularFactor::merged(zero_a, more).R());
}

void expect_refused(const std::string& bytes, const std::string& fragment) {
  try {
    TriangularFactor::deserialize(bytes);
    ADD_FAILURE() << "accepted bytes that should say: " << fragment;
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos) << e.what();
  }
}

TEST(FactorValue, DeserializeRefusesWhatIsNotAFactor) {
  Generator g(3);
  const std::string good = TriangularFactor::from_data(g.gaussian(1, 2), g.gaussian(1, 2)).serialize();
  expect_refused("", "wrong magic");
  expect_refused("not a factor at all", "wrong magic");
  std::string bytes = good;
  bytes[8] = 4;  // layout version 4 (3 is a factor with an intercept)
  expect_refused(bytes, "layout version 4 is not 1, 2 or 3");
  bytes = good;
  bytes[12] = 0;  // n = 0
  expect_refused(bytes, "n = 0");
  expect_refused(good.substr(0, good.size() - 1), "bytes of R where n = 2, d = 2 needs");
  expect_refused(good + "x", "bytes of R where n = 2, d = 2 needs");
  bytes = good;
  bytes[28] = 7;  // A's exponent flag
  expect_refused(bytes, "exponent flag is 7");
  // An Inf in R(0, 0), the first double after the 38-byte header.
  bytes = good;
  const std::string inf_bits = std::string("\0\0\0\0\0\0\xf0\x7f", 8);
  bytes.replace(38, 8, inf_bits);
  expect_refused(bytes, "R(0, 0) is not finite");
  // One row accumulated: R's row 1 must be zero. R(1, 1) is the third double (column 1: R(0,1), R(1,1)).
  bytes = good;
  bytes.replace(38 + 2 * 8, 8, std::string("\0\0\0\0\0\0\xf0\x3f", 8));  // 1.0
  expect_refused(bytes, "nonzero entry in row 1 beyond the 1 rows");

  // Layout 2: a non-square factor (A 1 x 2, B 1 x 3) carries d after n.
  const std::string wide = TriangularFactor::from_data(g.gaussian(1, 2), g.gaussian(1, 3)).serialize();
  ASSERT_EQ(wide[8], 2);
  bytes = wide;
  bytes[20] = 0;  // d = 0
  expect_refused(bytes, "d = 0 is not at least 1");
  bytes = wide;
  bytes[20] = 2;  // d = n = 2 in layout 2
  expect_refused(bytes, "layout 2 with d = n");
  expect_refused(wide.substr(0, wide.size() - 8), "bytes of R where n = 2, d = 3 needs");
}

TEST(FactorValue, NonSquareFactorsRoundTripAndMerge) {
  // A factor of A (n = 3 columns) and B (d = 2): the bytes come back bit for bit, a square factor
  // is still written in layout 1 (readable by spdfit before non-square factors), and merging
  // keeps the shape and equals the factor of all the rows (the Gram matrix, to rounding).
  Generator g(11);
  const MatrixXd A1 = g.gaussian(7, 3), B1 = g.gaussian(7, 2), A2 = g.gaussian(5, 3), B2 = g.gaussian(5, 2);
  const TriangularFactor f1 = TriangularFactor::from_data(A1, B1), f2 = TriangularFactor::from_data(A2, B2);
  const std::string bytes = f1.serialize();
  EXPECT_EQ(bytes[8], 2);
  const TriangularFactor back = TriangularFactor::deserialize(bytes);
  EXPECT_EQ(back.n(), 3);
  EXPECT_EQ(back.d(), 2);
  EXPECT_EQ(back.serialize(), bytes);
  EXPECT_EQ(TriangularFactor::from_data(A1, A1).serialize()[8], 1);

  const TriangularFactor merged = TriangularFactor::merged(back, f2);
  EXPECT_EQ(merged.rows(), 12);
  MatrixXd all(12, 5);
  all << A1, B1, A2, B2;
  const TriangularFactor whole = TriangularFactor::from_data(all.leftCols(3), all.rightCols(2));
  const MatrixXd gram = whole.R().transpose() * whole.R();
  EXPECT_LT((merged.R().transpose() * merged.R() - gram).norm() / gram.norm(), 1e-14);
  EXPECT_THROW(TriangularFactor::merged(f1, TriangularFactor(3)), std::invalid_argument);
}

}  // namespace
}  // namespace spdfit
