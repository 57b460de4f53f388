// FitOptions::bootstrap: the fields are filled for every method, the numbers depend on the seed
// and not on the threads, failed replicates are counted, and the options are checked. (The
// numbers themselves are checked against independent references in tests/python/test_bootstrap.py.)
#include <cstdio>
#include <gtest/gtest.h>

#include "spdfit/fit.hpp"
#include "spdfit/fit_files.hpp"
#include "spdfit/io.hpp"
#include "file_test_support.hpp"
#include "test_support.hpp"

namespace spdfit {
namespace {

using test::Generator;

struct Data {
  MatrixXd A, B;
};

Data noisy(std::uint64_t seed, Index m, Index n) {
  Generator g(seed);
  const MatrixXd W = g.gaussian(n, n);
  const MatrixXd X = W * W.transpose() + MatrixXd::Identity(n, n) * static_cast<double>(n);
  const MatrixXd A0 = g.gaussian(m, n) * 3.0;
  return {A0 + 0.2 * g.gaussian(m, n), A0 * X + 0.2 * g.gaussian(m, n)};
}

TEST(Bootstrap, EveryMethodFillsTheFields) {
  const Data d = noisy(1, 80, 3);
  FitOptions options;
  options.bootstrap = 50;
  for (Method method : kSelectableMethods) {
    const FitResult r = fit(d.A, d.B, method, options);
    ASSERT_TRUE(r.ok()) << to_string(method);
    ASSERT_TRUE(r.bootstrap.has_value()) << to_string(method);
    const Bootstrap& b = *r.bootstrap;
    EXPECT_EQ(b.replicates, 50);
    EXPECT_EQ(b.failed, 0);
    EXPECT_EQ(b.method, r.method);
    EXPECT_EQ(b.standard_errors.rows(), 3);
    EXPECT_TRUE((b.standard_errors.array() > 0).all()) << to_string(method);
    EXPECT_TRUE((b.interval.lower.array() <= b.interval.upper.array()).all());
    EXPECT_EQ(b.eigenvalues.has_value(), r.diagnostics.symmetric) << to_string(method);
  }
}

TEST(Bootstrap, SameNumbersForAnyThreadCountAndTheSeedMatters) {
  const Data d = noisy(2, 60, 4);
  FitOptions options;
  options.bootstrap = 64;
  options.threads = 1;
  const FitResult one = fit(d.A, d.B, Method::SpdTotalLeastSquares, options);
  options.threads = 3;
  const FitResult three = fit(d.A, d.B, Method::SpdTotalLeastSquares, options);
  EXPECT_EQ(one.bootstrap->standard_errors, three.bootstrap->standard_errors);
  EXPECT_EQ(one.bootstrap->interval.lower, three.bootstrap->interval.lower);
  EXPECT_EQ(one.bootstrap->bias, three.bootstrap->bias);
  options.seed = 2;
  const FitResult other = fit(d.A, d.B, Method::SpdTotalLeastSquares, options);
  EXPECT_NE(one.bootstrap->standard_errors, other.bootstrap->standard_errors);
  // X itself does not depend on the bootstrap.
  EXPECT_EQ(one.X, fit(d.A, d.B, Method::SpdTotalLeastSquares).X);
}

TEST(Bootstrap, AReductionHasNoRowsToResample) {
  const Data d = noisy(3, 30, 2);
  FitOptions options;
  options.bootstrap = 10;
  EXPECT_FALSE(fit(reduce(TriangularFactor::from_data(d.A, d.B), options), Method::Spde).bootstrap.has_value());
  EXPECT_FALSE(fit(d.A, d.B, Method::Spde).bootstrap.has_value());
}

TEST(Bootstrap, OptionsAreChecked) {
  FitOptions options;
  options.bootstrap = -1;
  std::string why;
  EXPECT_FALSE(options.is_valid(&why));
  EXPECT_NE(why.find("bootstrap"), std::string::npos);
  options.bootstrap = 10;
  for (double level : {0.0, 1.0, -0.5, 95.0}) {
    options.confidence = level;
    EXPECT_FALSE(options.is_valid(&why)) << level;
    EXPECT_NE(why.find("confidence"), std::string::npos);
  }
}

TEST(Bootstrap, NoStandardErrorsFromReplicatesThatAgreeToRounding) {
  // Data without noise: every resample gives X to rounding; never a standard error of 0.
  Generator g(4);
  const MatrixXd A = g.gaussian(40, 2);
  const MatrixXd X = (MatrixXd(2, 2) << 2.0, 0.5, 0.5, 1.0).finished();
  FitOptions options;
  options.bootstrap = 30;
  const FitResult r = fit(A, A * X, Method::LeastSquares, options);
  ASSERT_TRUE(r.ok() && r.bootstrap);
  EXPECT_TRUE(r.bootstrap->standard_errors.array().isNaN().all());
  EXPECT_FALSE(r.bootstrap->eigenvalues.has_value());
  bool warned = false;
  for (const Warning& w : r.warnings) warned |= w.text.find("all agree to rounding") != std::string::npos;
  EXPECT_TRUE(warned);
}

class StreamingBootstrapFiles : public test::ScratchDirectory {};

TEST_F(StreamingBootstrapFiles, TooFewGroupsResampleInMemoryWithinTheBudgetAndAreRefusedBeyondIt) {
  const Data d = noisy(5, 3000, 3);  // 1 group of 4096 rows; A and B take 141 KiB as doubles
  const std::string a = Path("A.npy"), b = Path("B.npy");
  io::write_npy(a, d.A);
  io::write_npy(b, d.B);
  FitOptions options;
  options.bootstrap = 20;
  StreamOptions stream;
  const FitResult resampled = fit_files(a, b, Method::Spde, options, stream);
  ASSERT_TRUE(resampled.ok() && resampled.bootstrap);
  EXPECT_EQ(resampled.bootstrap->scheme, "multinomial");
  EXPECT_EQ(resampled.bootstrap->standard_errors, fit(d.A, d.B, Method::Spde, options).bootstrap->standard_errors);
  stream.bootstrap_memory_bytes = 100 << 10;
  try {
    (void)fit_files(a, b, Method::Spde, options, stream);
    FAIL() << "expected a DataError";
  } catch (const io::DataError& e) {
    EXPECT_EQ(e.source(), a);
    EXPECT_NE(std::string(e.what()).find("needs about 100 groups (409600 rows) for its standard errors, but the data "
                                         "have 3000 rows (1 group): resampling its rows in memory instead would take "
                                         "141 KiB, more than the 100 KiB allowed"),
              std::string::npos)
        << e.what();
  }
}

// Standard input is read once: its text is kept while it is streamed, up to the budget, so that
// too few groups are resampled from it in memory; a text beyond the budget is refused.
TEST_F(StreamingBootstrapFiles, TooFewGroupsFromStandardInputResampleItsKeptTextWithinTheBudget) {
  const Data d = noisy(5, 3000, 3);
  const std::string a = Path("A.csv"), b = Path("B.npy");
  io::write_csv(a, d.A);  // shortest round-trip text: the same doubles read back
  io::write_npy(b, d.B);
  FitOptions options;
  options.bootstrap = 20;
  StreamOptions stream;
  ASSERT_NE(std::freopen(a.c_str(), "rb", stdin), nullptr);
  const FitResult resampled = fit_files("-", b, Method::Spde, options, stream);
  ASSERT_TRUE(resampled.ok() && resampled.bootstrap);
  EXPECT_EQ(resampled.bootstrap->scheme, "multinomial");
  EXPECT_EQ(resampled.bootstrap->standard_errors, fit(d.A, d.B, Method::Spde, options).bootstrap->standard_errors);
  bool said = false;
  for (const Warning& w : resampled.warnings) said |= w.text.find("standard input's text kept") != std::string::npos;
  EXPECT_TRUE(said);

  // The text (more than 100 KiB: 9000 numbers of about 19 digits) is beyond a budget of 100 KiB: refused, naming standard input.
  stream.bootstrap_memory_bytes = 100 << 10;
  ASSERT_NE(std::freopen(a.c_str(), "rb", stdin), nullptr);
  try {
    (void)fit_files("-", b, Method::Spde, options, stream);
    FAIL() << "expected a DataError";
  } catch (const io::DataError& e) {
    EXPECT_EQ(e.source(), "<stdin>");
    EXPECT_NE(std::string(e.what()).find("have 3000 rows (1 group): standard input is read once, and its text was "
                                         "more than the 100 KiB kept to resample its rows in memory"),
              std::string::npos)
        << e.what();
  }
  ASSERT_NE(std::freopen("/dev/null", "rb", stdin), nullptr);
}

}  // namespace
}  // namespace spdfit
