// NoiseModel: its factories' validation (messages naming the option), completing a model to the
// data's sizes, and the rest rows' covariances: stable under a large offset, the same however the
// rows are blocked, unbiased (Monte Carlo with a tolerance from the standard error), with the
// warnings about a short or moving rest segment.
#include <gtest/gtest.h>

#include <Eigen/Cholesky>
#include <algorithm>

#include <cmath>
#include <stdexcept>
#include <string>

#include "file_test_support.hpp"
#include "noise/rest_moments.hpp"
#include "spdfit/fit_options.hpp"
#include "spdfit/io.hpp"
#include "spdfit/noise_model.hpp"
#include "spdfit/random.hpp"
#include "test_support.hpp"

namespace spdfit {
namespace {

using Eigen::Index;
using Eigen::MatrixXd;
using Eigen::VectorXd;
using test::Generator;
using test::relative_error;

// The message of the std::invalid_argument `call` throws ("" when it throws none).
template <typename Call>
std::string invalid_argument_of(Call call) {
  try {
    call();
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "";
}

bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

TEST(NoiseModelUnits, ScaledIsTheModelOfTheScaledRows) {
  // FitOptions::scale_a, scale_b: the model of rest rows in other units, scaled, is the model of
  // the rest rows converted (NumPy's np.cov of the converted rows is the same covariance).
  Generator g(31);
  const MatrixXd rest_a = g.gaussian(200, 3), rest_b = g.gaussian(200, 2);
  VectorXd a(3), b(2);
  a << 9.80665, 2.0, 0.001;
  b << 1000.0, 0.5;
  const NoiseModel scaled = NoiseModel::from_rest(rest_a, rest_b).resolved(3, 2).scaled(a, b);
  const NoiseModel converted = NoiseModel::from_rest(rest_a * a.asDiagonal(), rest_b * b.asDiagonal());
  EXPECT_LT(relative_error(scaled.cov_a(), converted.cov_a()), 1e-13);
  EXPECT_LT(relative_error(scaled.cov_b(), converted.cov_b()), 1e-13);
  EXPECT_LT(relative_error(scaled.rest_mean_b(), converted.rest_mean_b()), 1e-13);
  EXPECT_EQ(scaled.source(), NoiseSource::Rest);
  EXPECT_EQ(scaled.rest_rows(), converted.rest_rows());
  // One standard deviation for every column becomes one per column.
  const NoiseModel std_model = NoiseModel::from_std(0.1, 0.2).resolved(3, 2).scaled(a, b);
  EXPECT_LT(relative_error(std_model.std_a(), VectorXd(0.1 * a)), 1e-15);
  EXPECT_LT(relative_error(std_model.cov_b(), MatrixXd((0.2 * b).cwiseAbs2().asDiagonal())), 1e-15);
  EXPECT_THROW(NoiseModel::from_std(0.1, 0.2).scaled(a, b), std::invalid_argument);  // not resolved
  EXPECT_THROW(NoiseModel::from_std(0.1, 0.2).resolved(3, 2).scaled(-a, b), std::invalid_argument);
}

TEST(NoiseModelTest, StandardDeviationsPerColumnArePerColumnVariances) {
  const VectorXd std_a = (VectorXd(3) << 0.2, 0.0, 0.8).finished();
  const VectorXd std_b = (VectorXd(3) << 3.0, 1.0, 0.3).finished();
  const NoiseModel model = NoiseModel::from_std(std_a, std_b);
  EXPECT_EQ(model.source(), NoiseSource::Std);
  EXPECT_EQ(to_string(model.source()), "std");
  ASSERT_TRUE(model.is_resolved());
  EXPECT_EQ(model.cov_a(), MatrixXd(std_a.cwiseAbs2().asDiagonal()));
  EXPECT_EQ(model.cov_b(), MatrixXd(std_b.cwiseAbs2().asDiagonal()));
  EXPECT_FALSE(model.a_is_zero());
  EXPECT_FALSE(model.a_is_positive_definite());  // column 2 is exact
  EXPECT_TRUE(model.b_is_positive_definite());
  EXPECT_EQ(model.option_a(), "`noise_std_a`");
  EXPECT_EQ(model.option_b(), "`noise_std_b`");
  EXPECT_FALSE(model.rest_rows());
  // The sizes are checked when the model meets the data.
  EXPECT_EQ(model.resolved(3, 3).cov_a(), model.cov_a());
  EXPECT_TRUE(contains(invalid_argument_of([&] { (void)model.resolved(6, 3); }),
                       "`noise_std_a` has 3 values but A has 6 columns"));
  EXPECT_TRUE(contains(invalid_argument_of([&] { (void)model.resolved(3, 2); }),
                       "`noise_std_b` has 3 values but B has 2 columns"));
}

TEST(NoiseModelTest, OneStandardDeviationPerSideIsCompletedToTheDataSizes) {
  const NoiseModel model = NoiseModel::from_std(0.5, 2.0);
  EXPECT_FALSE(model.is_resolved());
  EXPECT_TRUE(model.a_is_positive_definite());
  EXPECT_TRUE(model.b_is_positive_definite());
  const NoiseModel resolved = model.resolved(4, 2);
  EXPECT_EQ(resolved.cov_a(), MatrixXd(0.25 * MatrixXd::Identity(4, 4)));
  EXPECT_EQ(resolved.cov_b(), MatrixXd(4.0 * MatrixXd::Identity(2, 2)));
  const NoiseModel exact_a = NoiseModel::from_std(0.0, 1.0);
  EXPECT_TRUE(exact_a.a_is_zero());
  EXPECT_TRUE(exact_a.resolved(3, 3).a_is_zero());
}

TEST(NoiseModelTest, BadStandardDeviationsNameTheOption) {
  EXPECT_TRUE(contains(invalid_argument_of([] { NoiseModel::from_std(VectorXd(), VectorXd::Ones(2)); }),
                       "`noise_std_a` is empty"));
  EXPECT_TRUE(contains(invalid_argument_of([] { NoiseModel::from_std(-0.1, 1.0); }), "`noise_std_a` is -0.1"));
  EXPECT_TRUE(contains(invalid_argument_of([] {
                         NoiseModel::from_std(VectorXd::Ones(2), (VectorXd(2) << 1.0, NAN).finished());
                       }),
                       "`noise_std_b` value 2 is nan"));
  EXPECT_TRUE(contains(invalid_argument_of([] { NoiseModel::from_std(1.0, INFINITY); }), "`noise_std_b`"));
}

TEST(NoiseModelTest, BadCovariancesNameTheOption) {
  const MatrixXd good = MatrixXd::Identity(2, 2);
  EXPECT_TRUE(contains(invalid_argument_of([&] { NoiseModel::from_cov(MatrixXd(2, 3).setZero(), good); }),
                       "`noise_cov_a` is 2x3: a covariance matrix is square"));
  EXPECT_TRUE(contains(invalid_argument_of([&] { NoiseModel::from_cov(good, MatrixXd()); }), "`noise_cov_b` is empty"));
  const MatrixXd asymmetric = (MatrixXd(2, 2) << 1.0, 0.3, 0.2, 1.0).finished();
  EXPECT_TRUE(contains(invalid_argument_of([&] { NoiseModel::from_cov(asymmetric, good); }),
                       "`noise_cov_a` is not symmetric: entry (1, 2) is 0.3 but entry (2, 1) is 0.2"));
  const MatrixXd indefinite = (MatrixXd(2, 2) << 1.0, 2.0, 2.0, 1.0).finished();  // eigenvalues -1, 3
  EXPECT_TRUE(contains(invalid_argument_of([&] { NoiseModel::from_cov(good, indefinite); }),
                       "`noise_cov_b` is not positive semidefinite: its smallest eigenvalue is -1"));
  MatrixXd with_nan = good;
  with_nan(1, 0) = NAN;
  EXPECT_TRUE(contains(invalid_argument_of([&] { NoiseModel::from_cov(with_nan, good); }),
                       "`noise_cov_a` entry (2, 1) is nan"));
  // Rounding-level asymmetry (a matrix written with 17 digits after arithmetic) is accepted, and
  // its symmetric part kept.
  MatrixXd nearly = (MatrixXd(2, 2) << 2.0, 0.5, 0.5, 1.0).finished();
  nearly(0, 1) += 1e-14;
  const NoiseModel model = NoiseModel::from_cov(nearly, good);
  EXPECT_EQ(model.cov_a(), model.cov_a().transpose());
  EXPECT_TRUE(model.a_is_positive_definite());
  EXPECT_TRUE(contains(invalid_argument_of([&] { (void)model.resolved(3, 2); }),
                       "`noise_cov_a` is 2x2 but A has 3 columns: it must be 3x3"));
  // A positive semidefinite, singular covariance is a covariance (exact directions).
  const MatrixXd singular = (MatrixXd(2, 2) << 1.0, 1.0, 1.0, 1.0).finished();
  const NoiseModel semidefinite = NoiseModel::from_cov(singular, good);
  EXPECT_FALSE(semidefinite.a_is_positive_definite());
  EXPECT_FALSE(semidefinite.a_is_zero());
  EXPECT_EQ(semidefinite.option_b(), "`noise_cov_b`");
}

TEST(NoiseModelTest, NoiseRatioAndANoiseModelAreNotCombined) {
  FitOptions options;
  options.noise = NoiseModel::from_std(1.0, 2.0);
  std::string error;
  EXPECT_TRUE(options.is_valid(&error)) << error;
  options.noise_ratio = 2.0;
  ASSERT_FALSE(options.is_valid(&error));
  EXPECT_TRUE(contains(error, "`noise_ratio`")) << error;
  EXPECT_TRUE(contains(error, "`noise_std_a`")) << error;
}

// The moments of rows with a large offset: the two-pass covariance (mean first, then centered
// products) is the accurate reference; the textbook sum of squares minus N mean^2 loses all
// digits at an offset of 1e8 with unit spread.
TEST(RestMomentsTest, StableUnderALargeOffsetAndIndependentOfTheBlocks) {
  Generator g(330);
  MatrixXd rows = g.gaussian(1000, 3);
  rows.rowwise() += Eigen::RowVector3d(1e8, -3e7, 5.0);
  const Eigen::RowVector3d mean = rows.colwise().mean();
  const MatrixXd centered = rows.rowwise() - mean;
  const MatrixXd reference = centered.transpose() * centered / 999.0;
  for (Index block : {1000, 7, 128}) {
    detail::RowMoments moments;
    for (Index start = 0; start < rows.rows(); start += block) {
      moments.add(rows.middleRows(start, std::min(block, rows.rows() - start)));
    }
    EXPECT_EQ(moments.rows(), 1000u);
    // Each block's mean is exact to a few eps of 1e8 (1e-8 of the unit spread): far below 1e-6.
    EXPECT_LT(relative_error(moments.covariance(), reference), 1e-6) << "blocks of " << block;
    EXPECT_LT((moments.mean() - mean.transpose()).norm(), 1e-6);
  }
}

// E[S] = Sigma for the sample covariance with divisor N - 1 of Gaussian rows. Each entry's
// estimate has variance (Sigma_ii Sigma_jj + Sigma_ij^2) / (N - 1), so the mean of R replicates
// has standard error sqrt of that over R; every entry must lie within kDeviations of them. With
// 6 entries and 4.5 standard errors a false alarm has probability about 4e-5; the biased divisor
// N would miss by Sigma / N, 10 standard errors here (checked below, so the test can fail).
TEST(RestMomentsTest, RestCovarianceIsUnbiased) {
  constexpr int kReplicates = 4000;
  constexpr Index kRows = 20;
  constexpr double kDeviations = 4.5;
  const MatrixXd sigma = (MatrixXd(3, 3) << 2.0, 0.6, -0.3, 0.6, 1.0, 0.2, -0.3, 0.2, 0.5).finished();
  const MatrixXd L = Eigen::LLT<MatrixXd>(sigma).matrixL();
  Random random(331);
  MatrixXd sum = MatrixXd::Zero(3, 3);
  for (int r = 0; r < kReplicates; ++r) {
    MatrixXd z(kRows, 3);
    for (Index j = 0; j < 3; ++j)
      for (Index i = 0; i < kRows; ++i) z(i, j) = random.normal();
    const MatrixXd rest_a = z * L.transpose();
    const MatrixXd rest_b = (5.0 + 0.1 * z.array()).matrix();  // a constant load: not noise
    sum += NoiseModel::from_rest(rest_a, rest_b).cov_a();
  }
  const MatrixXd mean = sum / kReplicates;
  const MatrixXd biased = mean * (kRows - 1.0) / kRows;  // what the divisor N would give
  int biased_outside = 0;
  for (Index j = 0; j < 3; ++j)
    for (Index i = 0; i <= j; ++i) {
      const double se =
          std::sqrt((sigma(i, i) * sigma(j, j) + sigma(i, j) * sigma(i, j)) / (kRows - 1.0) / kReplicates);
      EXPECT_LE(std::abs(mean(i, j) - sigma(i, j)), kDeviations * se) << i << ", " << j;
      if (std::abs(biased(i, j) - sigma(i, j)) > kDeviations * se) ++biased_outside;
    }
  EXPECT_GE(biased_outside, 3);  // the diagonal at least: the test tells the divisors apart
}

TEST(RestModelTest, WarnsAboutAShortRestSegmentAndAccelerationsFarFromZero) {
  Generator g(332);
  // 2000 rows at rest, zero-mean accelerations: no warning; the load's mean is kept as reported.
  MatrixXd rest_b = 0.3 * g.gaussian(2000, 6);
  rest_b.rowwise() += Eigen::RowVectorXd::Constant(6, 50.0);
  const NoiseModel quiet = NoiseModel::from_rest(0.1 * g.gaussian(2000, 6), rest_b);
  EXPECT_TRUE(quiet.warnings().empty());
  EXPECT_EQ(quiet.source(), NoiseSource::Rest);
  EXPECT_EQ(quiet.rest_rows(), 2000u);
  EXPECT_NEAR(quiet.rest_mean_b()(3), 50.0, 0.1);
  EXPECT_EQ(quiet.option_a(), "`rest_a`");
  // 30 rows for 6 columns: fewer than 10 per column.
  const NoiseModel short_segment = NoiseModel::from_rest(0.1 * g.gaussian(30, 6), g.gaussian(30, 6));
  ASSERT_EQ(short_segment.warnings().size(), 1u);
  EXPECT_TRUE(contains(short_segment.warnings()[0].text, "the rest segment has 30 rows, fewer than 10 per column (60"));
  // Column 3 of A moving (mean 1, spread 0.1).
  MatrixXd moving = 0.1 * g.gaussian(500, 4);
  moving.col(2).array() += 1.0;
  const NoiseModel not_at_rest = NoiseModel::from_rest(moving, g.gaussian(500, 4));
  ASSERT_EQ(not_at_rest.warnings().size(), 1u);
  EXPECT_TRUE(contains(not_at_rest.warnings()[0].text, "in column(s) 3 (mean 0.99")) << not_at_rest.warnings()[0].text;
}

TEST(RestModelTest, BadRestRowsNameTheOption) {
  EXPECT_TRUE(contains(invalid_argument_of([] { NoiseModel::from_rest(MatrixXd::Ones(1, 2), MatrixXd::Ones(1, 2)); }),
                       "`rest_a` has 1 row(s)"));
  EXPECT_TRUE(contains(invalid_argument_of([] { NoiseModel::from_rest(MatrixXd::Ones(5, 2), MatrixXd::Ones(4, 2)); }),
                       "`rest_b` has 4 rows but `rest_a` has 5"));
  MatrixXd with_nan = MatrixXd::Ones(5, 2);
  with_nan(3, 1) = NAN;
  EXPECT_TRUE(contains(invalid_argument_of([&] { NoiseModel::from_rest(MatrixXd::Ones(5, 2), with_nan); }),
                       "`rest_b` holds NaN"));
  const NoiseModel model = NoiseModel::from_rest(MatrixXd::Random(20, 2), MatrixXd::Random(20, 3));
  EXPECT_TRUE(contains(invalid_argument_of([&] { (void)model.resolved(3, 3); }),
                       "the rest rows of A (`rest_a`) have 2 columns but A has 3"));
}

class RestFilesTest : public test::ScratchDirectory {};

TEST_F(RestFilesTest, FilesStreamedInBlocksGiveTheInMemoryCovariances) {
  Generator g(333);
  const MatrixXd rest_a = 0.2 * g.gaussian(257, 3);
  MatrixXd rest_b = g.gaussian(257, 3);
  rest_b.rowwise() += Eigen::RowVector3d(100.0, -20.0, 3.0);
  const std::string a_path = Path("rest_A.csv"), b_path = Path("rest_B.npy");
  io::write_csv(a_path, rest_a);
  io::write_npy(b_path, rest_b);
  const NoiseModel in_memory = NoiseModel::from_rest(rest_a, rest_b);
  for (Index block : {7, 1 << 15}) {
    const NoiseModel from_files = NoiseModel::from_rest_files(a_path, b_path, {}, block);
    EXPECT_LT(relative_error(from_files.cov_a(), in_memory.cov_a()), 1e-13) << block;
    EXPECT_LT(relative_error(from_files.cov_b(), in_memory.cov_b()), 1e-13) << block;
    EXPECT_EQ(from_files.rest_rows(), 257u);
    EXPECT_EQ(from_files.rest_a_path(), a_path);
    EXPECT_EQ(from_files.rest_b_path(), b_path);
  }
}

TEST_F(RestFilesTest, BadRestFilesAreDataErrorsNamingTheFile) {
  const std::string one_row = Write("one.csv", "1,2\n");
  const std::string good = Write("good.csv", "1,2\n3,4\n5,7\n");
  const std::string three_rows_3 = Write("wide.csv", "1,2,3\n3,4,5\n5,7,1\n");
  const std::string four_rows = Write("four.csv", "1,2\n3,4\n5,7\n0,0\n");
  auto data_error_of = [](auto call) -> std::string {
    try {
      call();
    } catch (const io::DataError& e) {
      return e.what();
    }
    return "";
  };
  std::string message = data_error_of([&] { NoiseModel::from_rest_files(one_row, good); });
  EXPECT_TRUE(contains(message, one_row) && contains(message, "`rest_a`")) << message;
  message = data_error_of([&] { NoiseModel::from_rest_files(good, four_rows); });
  EXPECT_TRUE(contains(message, four_rows) && contains(message, "are 4 but those of A")) << message;
  message = data_error_of([&] { NoiseModel::from_rest_files(good, Path("missing.csv")); });
  EXPECT_TRUE(contains(message, "missing.csv")) << message;
  // Another column count than the data's: refused naming the rest file when the model meets them.
  const NoiseModel model = NoiseModel::from_rest_files(three_rows_3, good);
  message = data_error_of([&] { (void)model.resolved(2, 2); });
  EXPECT_TRUE(contains(message, three_rows_3) && contains(message, "have 3 columns but A has 2")) << message;
  EXPECT_TRUE(contains(invalid_argument_of([&] { NoiseModel::from_rest_files(good, good, {}, 0); }),
                       "`block_rows` must be at least 1"));
}

}  // namespace
}  // namespace spdfit
