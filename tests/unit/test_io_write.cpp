// format_double and write_csv.
#include <gtest/gtest.h>

#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <random>
#include <sstream>
#include <string>

#include "io/parse.hpp"
#include "spdfit/io.hpp"

namespace {

using Eigen::MatrixXd;
using spdfit::io::format_double;

std::uint64_t Bits(double x) {
  std::uint64_t bits;
  std::memcpy(&bits, &x, sizeof(bits));
  return bits;
}

double FromBits(std::uint64_t bits) {
  double x;
  std::memcpy(&x, &bits, sizeof(x));
  return x;
}

void ExpectRoundTrip(double x) {
  const std::string text = format_double(x);
  double back = 0;
  const auto [ptr, ec] = std::from_chars(text.data(), text.data() + text.size(), back);
  ASSERT_EQ(ec, std::errc()) << text;
  ASSERT_EQ(ptr, text.data() + text.size()) << text;
  ASSERT_EQ(Bits(back), Bits(x)) << text;
}

TEST(IoFormatDouble, Examples) {
  EXPECT_EQ(format_double(0.1), "0.1");
  EXPECT_EQ(format_double(1e-300), "1e-300");
  EXPECT_EQ(format_double(1.0), "1");
  EXPECT_EQ(format_double(-2.5), "-2.5");
  EXPECT_EQ(format_double(0.0), "0");
  EXPECT_EQ(format_double(-0.0), "0");  // equal to 0, without a sign it does not have
  EXPECT_EQ(format_double(0.1 + 0.2), "0.30000000000000004");
  EXPECT_EQ(format_double(1e21), "1e+21");
  EXPECT_EQ(format_double(123456.0), "123456");
  EXPECT_EQ(format_double(std::numeric_limits<double>::max()), "1.7976931348623157e+308");
  EXPECT_EQ(format_double(std::numeric_limits<double>::denorm_min()), "5e-324");
}

TEST(IoFormatDouble, Nonfinite) {
  const double inf = std::numeric_limits<double>::infinity();
  EXPECT_EQ(format_double(inf), "inf");
  EXPECT_EQ(format_double(-inf), "-inf");
  EXPECT_EQ(format_double(std::numeric_limits<double>::quiet_NaN()), "nan");
  EXPECT_EQ(format_double(-std::numeric_limits<double>::quiet_NaN()), "nan");
}

TEST(IoFormatDouble, RandomBitPatternsRoundTrip) {
  std::mt19937_64 rng(7);
  for (int k = 0; k < 200000; ++k) {
    const double x = FromBits(rng());
    if (!std::isfinite(x)) continue;
    ExpectRoundTrip(x);
  }
}

TEST(IoFormatDouble, DenormalsRoundTrip) {
  std::mt19937_64 rng(11);
  const std::uint64_t mantissa = (std::uint64_t{1} << 52) - 1;
  for (int k = 0; k < 50000; ++k) {
    const std::uint64_t bits = rng() & mantissa;  // exponent 0: denormal (or zero)
    ExpectRoundTrip(FromBits(bits));
    ExpectRoundTrip(-FromBits(bits));
  }
  ExpectRoundTrip(std::numeric_limits<double>::denorm_min());
  ExpectRoundTrip(std::numeric_limits<double>::min());
  ExpectRoundTrip(FromBits(mantissa));  // the largest denormal
}

TEST(IoFormatDouble, RandomValuesRoundTrip) {
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  std::uniform_int_distribution<int> exponent(-320, 300);
  for (int k = 0; k < 50000; ++k) ExpectRoundTrip(std::ldexp(uniform(rng), exponent(rng)));
}

TEST(IoWriteCsv, Text) {
  const MatrixXd X = (MatrixXd(2, 3) << 1, 2.5, -3, 0.1, 1e-300, 0).finished();
  std::ostringstream out;
  spdfit::io::write_csv(out, X);
  EXPECT_EQ(out.str(), "1,2.5,-3\n0.1,1e-300,0\n");
}

TEST(IoWriteCsv, EmptyMatrixWritesNothing) {
  std::ostringstream out;
  spdfit::io::write_csv(out, MatrixXd(0, 3));
  EXPECT_EQ(out.str(), "");
}

TEST(IoWriteCsv, BlockOfALargerMatrix) {
  const MatrixXd X = (MatrixXd(3, 3) << 1, 2, 3, 4, 5, 6, 7, 8, 9).finished();
  std::ostringstream out;
  spdfit::io::write_csv(out, X.block(1, 1, 2, 2));
  EXPECT_EQ(out.str(), "5,6\n8,9\n");
}

TEST(IoWriteCsv, ReadsBackExactly) {
  std::mt19937_64 rng(5);
  MatrixXd X(40, 7);
  for (Eigen::Index i = 0; i < X.size(); ++i) {
    do {
      X(i) = FromBits(rng());
    } while (!std::isfinite(X(i)));
  }
  X(0, 0) = -0.0;
  X(1, 0) = std::numeric_limits<double>::denorm_min();
  std::ostringstream out;
  spdfit::io::write_csv(out, X);
  const MatrixXd back = spdfit::io::parse_delimited(out.str(), "X.csv").values;
  ASSERT_EQ(back.rows(), X.rows());
  ASSERT_EQ(back.cols(), X.cols());
  EXPECT_EQ(Bits(back(0, 0)), Bits(0.0));  // -0 is written as 0
  for (Eigen::Index i = 1; i < X.size(); ++i) EXPECT_EQ(Bits(back(i)), Bits(X(i)));
}

}  // namespace
