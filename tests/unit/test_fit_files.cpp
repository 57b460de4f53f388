// fit_files and read_pair: the one path from data files to an estimate that the CLI and Python
// share; Reduction's read-only view; FitResult's NotComputed default; fit_all's shared TLS SVD.
#include <gtest/gtest.h>

#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "file_test_support.hpp"
#include "io/row_selection.hpp"
#include "spdfit/fit.hpp"
#include "spdfit/fit_files.hpp"
#include "spdfit/io.hpp"
#include "spdfit/spde.hpp"
#include "spdfit/total_least_squares.hpp"
#include "test_support.hpp"

namespace spdfit {
namespace {

class FitFilesTest : public test::NoisyDataFiles {};

// The CSV holds the shortest round-trip text of each value, so A is read back exactly.
TEST_F(FitFilesTest, ReadWholeIsTheInMemoryFitBitForBit) {
  MakeData(50, 4, 1);
  for (Method method : kAllMethods) {
    const FitResult from_files = fit_files(a_path_, b_path_, method);
    const FitResult in_memory = fit(A_, B_, method);
    ASSERT_TRUE(from_files.ok()) << to_string(method) << ": " << from_files.message;
    EXPECT_EQ(from_files.status, Status::Success);
    EXPECT_EQ(from_files.X, in_memory.X) << to_string(method);
  }
}

// Streamed in blocks of 7 rows the QR is blocked differently: equal to rounding (cond(A) ~ 1,
// cond(X) = 10, so a few eps in R moves X by well under 1e-12 relative).
TEST_F(FitFilesTest, StreamedIsTheWholeFitToRounding) {
  MakeData(200, 5, 2);
  StreamOptions stream;
  stream.block_rows = 7;
  stream.threads = 2;
  for (Method method : kAllMethods) {
    const FitResult whole = fit_files(a_path_, b_path_, method);
    const FitResult streamed = fit_files(a_path_, b_path_, method, {}, stream);
    ASSERT_TRUE(streamed.ok()) << to_string(method);
    EXPECT_LE((streamed.X - whole.X).norm(), 1e-12 * whole.X.norm()) << to_string(method);
  }
}

TEST_F(FitFilesTest, ReadPairNamesTheFileWithTooFewRowsOrAnotherShape) {
  io::write_csv(Path("wide.csv"), MatrixXd::Ones(2, 3));
  io::write_csv(Path("B3.csv"), MatrixXd::Ones(3, 3));
  io::write_csv(Path("A3.csv"), MatrixXd::Identity(3, 3));
  io::write_csv(Path("B4.csv"), MatrixXd::Ones(4, 3));
  try {
    read_pair(Path("wide.csv"), Path("B3.csv"));
    FAIL() << "expected a DataError";
  } catch (const io::DataError& e) {
    EXPECT_EQ(e.source(), Path("wide.csv"));
    EXPECT_NE(std::string(e.what()).find("A has 2 rows (samples) but 3 columns"), std::string::npos) << e.what();
  }
  try {
    fit_files(Path("A3.csv"), Path("B4.csv"), Method::Spde);
    FAIL() << "expected a DataError";
  } catch (const io::DataError& e) {
    EXPECT_EQ(e.source(), Path("B4.csv"));
    EXPECT_NE(std::string(e.what()).find("B is 4x3 but A"), std::string::npos) << e.what();
  }
}

TEST_F(FitFilesTest, InvalidOptionsAreMisuse) {
  MakeData(10, 2, 3);
  FitOptions options;
  options.rank_tolerance = 2.0;
  EXPECT_THROW(fit_files(a_path_, b_path_, Method::Spde, options), std::invalid_argument);
}

TEST(RowSelection, RangesAndListsOfOneBasedRows) {
  using io::detail::selected_rows;
  const std::vector<Eigen::Index> some = selected_rows("2:4, 9,7:", "rows", 10, "log.csv");
  EXPECT_EQ(some, (std::vector<Eigen::Index>{1, 2, 3, 6, 7, 8, 9}));  // 0-based, ascending, each once
  EXPECT_EQ(selected_rows(":3,2:3", "rows", 10, "log.csv"), (std::vector<Eigen::Index>{0, 1, 2}));
  EXPECT_EQ(selected_rows("10", "rows", 10, "log.csv"), (std::vector<Eigen::Index>{9}));
  auto message = [](const std::string& spec, std::uint64_t rows) -> std::string {
    try {
      (void)selected_rows(spec, "rest_rows", rows, "log.csv");
    } catch (const std::exception& e) {
      return e.what();
    }
    return "";
  };
  EXPECT_NE(message("0:3", 10).find("no row 0"), std::string::npos);
  EXPECT_NE(message("5:3", 10).find("runs backwards (write 3:5)"), std::string::npos);
  EXPECT_NE(message("1,,2", 10).find("empty item"), std::string::npos);
  EXPECT_NE(message(":", 10).find("neither a start nor an end"), std::string::npos);
  EXPECT_NE(message("1.5", 10).find("not a row number"), std::string::npos);
  EXPECT_NE(message("8:11", 10).find("row 11 is beyond the 10 data rows of log.csv"), std::string::npos);
  EXPECT_NE(message("8:11", 10).find("`rest_rows` '8:11'"), std::string::npos);
  EXPECT_THROW(selected_rows("8:11", "rows", 10, "log.csv"), io::DataError);
  EXPECT_THROW(io::detail::check_row_selection("x", "rows"), OptionError);
}

TEST(FitResultTest, ADefaultResultIsNotComputed) {
  const FitResult result;
  EXPECT_EQ(result.status, Status::NotComputed);
  EXPECT_FALSE(result.ok());
  EXPECT_STREQ(to_string(Status::NotComputed), "not_computed");
  EXPECT_STREQ(to_string(Status::Success), "success");
  EXPECT_STREQ(to_string(Status::NumericalFailure), "numerical_failure");
}

TEST(ReductionTest, IsAReadOnlyViewOfTheReducedData) {
  test::Generator g(4);
  MatrixXd A = g.gaussian(30, 3);
  A.col(2) = A.col(0);  // rank 2
  const MatrixXd B = g.gaussian(30, 3);
  FitOptions options;
  options.diagnostics = false;
  const Reduction r = reduce(TriangularFactor::from_data(A, B), options);
  EXPECT_EQ(r.m(), 30);
  EXPECT_EQ(r.n(), 3);
  EXPECT_EQ(r.rank_a(), 2);
  EXPECT_EQ(r.rank_b(), 3);
  EXPECT_FALSE(r.options().diagnostics);
  const Reduction copy = r;  // copies share the data
  EXPECT_EQ(copy.rank_a(), 2);

  const Reduction empty;
  EXPECT_EQ(empty.n(), 0);
  EXPECT_THROW(spde(empty), std::invalid_argument);
  EXPECT_THROW(fit(empty, Method::TotalLeastSquares), std::invalid_argument);
}

// fit_all computes the TLS SVD once for tls, tls-sym and tls-psd: the same results, bit for bit,
// as the three functions called one by one, warnings and failures included.
TEST(FitAllTest, SharesTheTlsSvdWithTheSameResults) {
  test::Generator g(5);
  const MatrixXd X = g.spd(4, 5.0);
  const MatrixXd A = g.gaussian(40, 4);
  const MatrixXd B = A * X + 0.5 * g.gaussian(40, 4);
  const Reduction data = reduce(TriangularFactor::from_data(A, B));
  const std::vector<FitResult> all = fit_all(data);
  ASSERT_EQ(all.size(), kAllMethods.size());
  for (std::size_t i = 0; i < kAllMethods.size(); ++i) {
    const FitResult one = fit(data, kAllMethods[i]);
    EXPECT_EQ(all[i].method, kAllMethods[i]);
    EXPECT_EQ(all[i].status, one.status);
    EXPECT_EQ(all[i].X, one.X) << to_string(kAllMethods[i]);
    EXPECT_EQ(all[i].warnings, one.warnings);
    EXPECT_EQ(all[i].diagnostics.tls_sigma_n, one.diagnostics.tls_sigma_n);
  }
  // No TLS solution: A's second column is zero, so the smallest singular direction of [A B] is
  // (e_2, 0), whose B part is zero (V22 singular). The three fail alike, from one SVD.
  MatrixXd A2 = g.gaussian(12, 2), B2 = g.gaussian(12, 2);
  A2.col(1).setZero();
  const std::vector<FitResult> all2 = fit_all(reduce(TriangularFactor::from_data(A2, B2)));
  for (std::size_t i = 0; i < kAllMethods.size(); ++i) {
    const FitResult one = fit(A2, B2, kAllMethods[i]);
    EXPECT_EQ(all2[i].status, one.status) << to_string(kAllMethods[i]);
    EXPECT_EQ(all2[i].X, one.X) << to_string(kAllMethods[i]);
    EXPECT_EQ(all2[i].message, one.message);
  }
  EXPECT_EQ(all2[2].status, Status::NumericalFailure);  // tls
  EXPECT_EQ(all2[4].status, Status::NumericalFailure);  // tls-psd
}

}  // namespace
}  // namespace spdfit
