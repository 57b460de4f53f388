// A noise model everywhere a fit runs: auto's choice with and without one (and its promise of a
// positive definite estimate), the bootstrap (both schemes), fit_files (whole and streamed, with
// rest files), hexapod::identify, the simulator's per-channel noise and rest rows, and the thesis
// experiment with noise models.
#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <string>

#include "estimators/auto_settle.hpp"
#include "file_test_support.hpp"
#include "spdfit/auto.hpp"
#include "spdfit/experiment/thesis.hpp"
#include "spdfit/fit.hpp"
#include "spdfit/fit_files.hpp"
#include "spdfit/hexapod/identify.hpp"
#include "spdfit/hexapod/simulate.hpp"
#include "spdfit/io.hpp"
#include "spdfit/noise_model.hpp"
#include "spdfit/symmetric_procrustes.hpp"
#include "test_support.hpp"

namespace spdfit {
namespace {

using Eigen::Index;
using Eigen::MatrixXd;
using Eigen::VectorXd;
using test::relative_error;

bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

VectorXd values(std::initializer_list<double> list) {
  VectorXd v(static_cast<Index>(list.size()));
  Index i = 0;
  for (double x : list) v(i++) = x;
  return v;
}

const VectorXd kStdA = values({0.2, 0.4, 0.8, 0.2, 0.4, 0.8});
const VectorXd kStdB = values({3.0, 1.0, 0.3, 3.0, 1.0, 0.3});

// docs/guide.md's noise-model set-up: the thesis' hexapod with per-channel Gaussian noise and a
// rest segment.
hexapod::Measurements hexapod_data(Index m, const VectorXd& std_a, const VectorXd& std_b, std::uint64_t seed,
                                   Index rest = 0) {
  hexapod::SimulationOptions options;
  options.samples = m;
  options.distribution = hexapod::NoiseDistribution::Gaussian;
  options.noise_std_a = std_a;
  options.noise_std_b = std_b;
  options.rest_samples = rest;
  return hexapod::simulate(hexapod::thesis_mass_matrix(), options, seed);
}

FitOptions with_noise(const NoiseModel& model) {
  FitOptions options;
  options.noise = model;
  return options;
}

// ---- auto -------------------------------------------------------------------------------------

TEST(AutoWithANoiseModel, ChoosesTheLikelihoodFitWeightedPsdLsOrSpdeAndNamesTheSource) {
  // Noise in both, many rows: the maximum-likelihood fit.
  const hexapod::Measurements both = hexapod_data(1000, kStdA, kStdB, 1, 2000);
  const FitResult ml = auto_fit(both.A, both.B, with_noise(NoiseModel::from_std(kStdA, kStdB)));
  ASSERT_TRUE(ml.ok()) << ml.message;
  EXPECT_EQ(ml.method, Method::SpdTotalLeastSquares);
  EXPECT_EQ(ml.diagnostics.reason->code, "many_samples");
  EXPECT_TRUE(contains(ml.diagnostics.reason->text, "`noise_std_a`")) << ml.diagnostics.reason->text;
  EXPECT_TRUE(contains(ml.diagnostics.reason->text, "maximum-likelihood"));
  // The same from the rest segment: its source named, with its rows.
  const FitResult rest = auto_fit(both.A, both.B, with_noise(NoiseModel::from_rest(both.rest_A, both.rest_B)));
  ASSERT_TRUE(rest.ok());
  EXPECT_EQ(rest.method, Method::SpdTotalLeastSquares);
  EXPECT_TRUE(contains(rest.diagnostics.reason->text, "rest segment (2000 rows of `rest_a` and `rest_b`)"));
  ASSERT_TRUE(rest.diagnostics.noise_model);
  EXPECT_EQ(rest.diagnostics.noise_model->source(), NoiseSource::Rest);
  // A exact: weighted psd-ls, positive definite (auto's floor).
  const hexapod::Measurements b_only = hexapod_data(1000, VectorXd::Zero(6), kStdB, 2);
  const FitResult weighted = auto_fit(b_only.A, b_only.B, with_noise(NoiseModel::from_std(VectorXd::Zero(6), kStdB)));
  ASSERT_TRUE(weighted.ok());
  EXPECT_EQ(weighted.method, Method::PsdLeastSquares);
  EXPECT_EQ(weighted.diagnostics.reason->code, "noise_in_b");
  EXPECT_TRUE(weighted.diagnostics.positive_definite);
  EXPECT_TRUE(weighted.warnings.empty());
  // Noise in A a thousand times below its signal and B noisy: negligible, so weighted psd-ls too.
  const VectorXd tiny = VectorXd::Constant(6, 1e-4);
  const hexapod::Measurements quiet_a = hexapod_data(200, tiny, kStdB, 3);
  const FitResult negligible = auto_fit(quiet_a.A, quiet_a.B, with_noise(NoiseModel::from_std(tiny, kStdB)));
  ASSERT_TRUE(negligible.ok());
  EXPECT_EQ(negligible.diagnostics.reason->code, "noise_in_b");
  EXPECT_TRUE(contains(negligible.diagnostics.reason->text, "too small to matter"));
  // Few rows and much noise in A: spde, without the model, saying so.
  const VectorXd loud = VectorXd::Constant(6, 1.0);
  const hexapod::Measurements few = hexapod_data(12, loud, loud, 4);
  const FitResult small = auto_fit(few.A, few.B, with_noise(NoiseModel::from_std(loud, loud)));
  ASSERT_TRUE(small.ok());
  EXPECT_EQ(small.method, Method::Spde);
  EXPECT_EQ(small.diagnostics.reason->code, "few_samples");
  EXPECT_TRUE(contains(small.diagnostics.reason->text, "spde has no noise model"));
  ASSERT_FALSE(small.warnings.empty());
  EXPECT_TRUE(contains(small.warnings.back().text, "spde ran without the noise model"));
  EXPECT_TRUE(small.diagnostics.noise_model);  // the model auto chose by
}

TEST(AutoWithoutANoiseModel, SaysWhatItAssumedAndHowToGiveAModel) {
  const hexapod::Measurements data = hexapod_data(100, kStdA, kStdB, 5);
  const FitResult r = auto_fit(data.A, data.B);
  ASSERT_TRUE(r.ok());
  const std::string& text = r.diagnostics.reason->text;
  EXPECT_TRUE(contains(text, "it assumed equal noise in every column of A and B, in the units given")) << text;
  EXPECT_TRUE(contains(text, "`rest_a` and `rest_b`")) << text;
  EXPECT_FALSE(r.diagnostics.noise_model);
  FitOptions ratio;
  ratio.noise_ratio = 4.0;
  EXPECT_TRUE(contains(auto_fit(data.A, data.B, ratio).diagnostics.reason->text, "`noise_ratio` = 4 times it"));
}

// auto's promise: a positive definite estimate, or a warning that it is not (a fallback that
// failed, which on real data only an eigensolver failure causes, so it is given here).
TEST(AutoSettle, KeepsItsPromiseOrWarns) {
  test::Generator g(500);
  // An indefinite procrustes estimate: a truth with a negative eigenvalue, little noise.
  const MatrixXd A = g.gaussian(40, 3);
  const MatrixXd B = A * (MatrixXd(3, 3) << 1.0, 0.0, 0.0, 0.0, 2.0, 0.0, 0.0, 0.0, -0.5).finished() +
                     0.01 * g.gaussian(40, 3);
  const FitResult indefinite = symmetric_procrustes(A, B);
  ASSERT_TRUE(indefinite.ok());
  ASSERT_FALSE(indefinite.diagnostics.positive_definite);
  FitResult failed_fallback;
  failed_fallback.method = Method::PsdLeastSquares;
  failed_fallback.status = Status::NumericalFailure;
  failed_fallback.message = "psd-ls: an eigendecomposition did not converge";
  AutoReason reason{"many_samples", "text"};
  const FitResult kept = detail::auto_settle(indefinite, failed_fallback, reason, 1e-8);
  EXPECT_TRUE(kept.ok());
  EXPECT_EQ(kept.X, indefinite.X);
  ASSERT_FALSE(kept.warnings.empty());
  EXPECT_TRUE(contains(kept.warnings.back().text, "auto: the estimate is not positive definite")) << kept.warnings.back().text;
  EXPECT_TRUE(contains(kept.warnings.back().text, "an eigendecomposition did not converge"));
  // A failed first method and a failed fallback: the first failure, saying the fallback failed.
  FitResult failed_first;
  failed_first.method = Method::SpdTotalLeastSquares;
  failed_first.status = Status::NumericalFailure;
  failed_first.message = "spd-tls: no minimizer";
  const FitResult both_failed = detail::auto_settle(failed_first, failed_fallback, reason, 1e-8);
  EXPECT_FALSE(both_failed.ok());
  EXPECT_TRUE(contains(both_failed.message, "spd-tls: no minimizer; psd-ls, auto's fallback, did not give"));
  // A fallback that works replaces the first, with reason "boundary".
  FitOptions floored;
  floored.min_eig = 1e-3;
  const FitResult good_fallback = fit(A, B, Method::PsdLeastSquares, floored);
  const FitResult replaced = detail::auto_settle(indefinite, good_fallback, reason, 1e-3);
  EXPECT_EQ(replaced.method, Method::PsdLeastSquares);
  EXPECT_EQ(reason.code, "boundary");
}

// ---- the bootstrap, both schemes ----------------------------------------------------------------

TEST(BootstrapWithANoiseModel, ReplicatesFitWithTheModel) {
  const hexapod::Measurements data = hexapod_data(300, kStdA, kStdB, 6);
  FitOptions options = with_noise(NoiseModel::from_std(kStdA, kStdB));
  options.bootstrap = 40;
  options.threads = 2;
  for (Method method : {Method::SpdTotalLeastSquares, Method::Auto, Method::TotalLeastSquares}) {
    const FitResult r = fit(data.A, data.B, method, options);
    ASSERT_TRUE(r.ok() && r.bootstrap) << r.message;
    EXPECT_EQ(r.bootstrap->failed, 0) << to_string(method);
    EXPECT_TRUE((r.bootstrap->standard_errors.array() > 0).all()) << to_string(method);
  }
  // auto keeping spde (few rows) with a model: the replicates run spde without it, as the fit did.
  const VectorXd loud = VectorXd::Constant(6, 1.0);
  const hexapod::Measurements few = hexapod_data(12, loud, loud, 7);
  FitOptions few_options = with_noise(NoiseModel::from_std(loud, loud));
  few_options.bootstrap = 30;
  const FitResult spde_kept = fit(few.A, few.B, Method::Auto, few_options);
  ASSERT_TRUE(spde_kept.ok() && spde_kept.bootstrap);
  EXPECT_EQ(spde_kept.method, Method::Spde);
  EXPECT_LT(spde_kept.bootstrap->failed, 30);
}

class NoiseFilesTest : public test::ScratchDirectory {};

TEST_F(NoiseFilesTest, FitFilesCarriesTheModelWholeStreamedAndWithTheStreamingBootstrap) {
  const hexapod::Measurements data = hexapod_data(5000, kStdA, kStdB, 8, 2000);
  const std::string a = Path("A.npy"), b = Path("B.csv"), rest_a = Path("rest_A.csv"), rest_b = Path("rest_B.npy");
  io::write_npy(a, data.A);
  io::write_csv(b, data.B);
  io::write_csv(rest_a, data.rest_A);
  io::write_npy(rest_b, data.rest_B);
  const FitOptions options = with_noise(NoiseModel::from_rest_files(rest_a, rest_b));
  const FitResult whole = fit_files(a, b, Method::Auto, options);
  ASSERT_TRUE(whole.ok()) << whole.message;
  EXPECT_EQ(whole.method, Method::SpdTotalLeastSquares);
  EXPECT_EQ(whole.X, fit(data.A, io::read_matrix(b), Method::Auto, options).X);
  StreamOptions stream;
  stream.block_rows = 700;
  const FitResult streamed = fit_files(a, b, Method::Auto, options, stream);
  ASSERT_TRUE(streamed.ok());
  EXPECT_LT(relative_error(streamed.X, whole.X), 1e-9);
  FitOptions bootstrap = options;
  bootstrap.bootstrap = 20;
  // Too few rows for the Poisson groups: resampled in memory, with the noise model.
  const FitResult resampled = fit_files(a, b, Method::SpdTotalLeastSquares, bootstrap, stream);
  ASSERT_TRUE(resampled.ok() && resampled.bootstrap);
  EXPECT_EQ(resampled.bootstrap->scheme, "multinomial");
  EXPECT_TRUE(resampled.diagnostics.noise_model);
}

TEST_F(NoiseFilesTest, AModelTheDataOrMethodCannotUseIsRefusedBeforeThePass) {
  const hexapod::Measurements data = hexapod_data(50, kStdA, kStdB, 9, 100);
  const std::string a = Path("A.csv"), b = Path("B.csv");
  io::write_csv(a, data.A);
  io::write_csv(b, data.B);
  // Rest rows of 5 columns: a DataError naming the rest file, whole or streamed.
  const std::string rest_a = Path("rest_A.csv"), rest_b = Path("rest_B.csv");
  io::write_csv(rest_a, data.rest_A.leftCols(5));
  io::write_csv(rest_b, data.rest_B);
  const FitOptions options = with_noise(NoiseModel::from_rest_files(rest_a, rest_b));
  for (bool streamed : {false, true}) {
    try {
      (void)fit_files(a, b, Method::SpdTotalLeastSquares, options,
                      streamed ? std::optional<StreamOptions>(StreamOptions{}) : std::nullopt);
      ADD_FAILURE() << "no error";
    } catch (const io::DataError& e) {
      EXPECT_EQ(e.source(), rest_a);
      EXPECT_TRUE(contains(e.what(), "have 5 columns but A has 6")) << e.what();
    }
  }
  // spde with a model: refused before any file is read (here, files that do not exist).
  EXPECT_THROW((void)fit_files(Path("none.csv"), Path("none2.csv"), Method::Spde,
                               with_noise(NoiseModel::from_std(1.0, 1.0))),
               std::invalid_argument);
}

// ---- hexapod::identify -----------------------------------------------------------------------------

TEST(IdentifyWithANoiseModel, EveryMethodGetsItAndSpdeSaysItRanWithout) {
  const hexapod::Measurements data = hexapod_data(500, kStdA, kStdB, 10);
  hexapod::IdentifyOptions options;
  options.truth = hexapod::thesis_mass_matrix();
  options.fit.noise = NoiseModel::from_std(kStdA, kStdB);
  const std::vector<hexapod::MethodIdentification> all = hexapod::identify(data.A, data.B, options);
  ASSERT_EQ(all.size(), kAllMethods.size());
  for (const hexapod::MethodIdentification& m : all) {
    ASSERT_TRUE(m.result.ok()) << to_string(m.result.method) << ": " << m.result.message;
    if (m.result.method == Method::Spde) {
      EXPECT_FALSE(m.result.diagnostics.noise_model);
      EXPECT_TRUE(contains(m.result.warnings.back().text, "ran without the noise model"));
    } else {
      EXPECT_TRUE(m.result.diagnostics.noise_model) << to_string(m.result.method);
    }
    if (m.result.method == Method::SpdTotalLeastSquares) {
      EXPECT_LT(relative_error(m.result.X, fit(data.A, data.B, Method::SpdTotalLeastSquares, options.fit).X), 1e-12);
    }
  }
}

// ---- the simulator and the experiment ------------------------------------------------------------

// Per-channel noise has the standard deviations asked for: each column's sample variance of
// A - A_true over m rows has a relative standard error sqrt(2 / m) (Gaussian), 4 of them allowed.
TEST(SimulatePerChannel, NoiseHasTheStandardDeviationsAskedForAndRestRowsTheirs) {
  for (auto distribution : {hexapod::NoiseDistribution::Gaussian, hexapod::NoiseDistribution::Uniform}) {
    hexapod::SimulationOptions options;
    options.samples = 20000;
    options.distribution = distribution;
    options.noise_std_a = kStdA;
    options.noise_std_b = kStdB;
    options.rest_samples = 20000;
    const hexapod::Measurements data = hexapod::simulate(hexapod::thesis_mass_matrix(), options, 11);
    const MatrixXd noise_a = data.A - data.A_true, noise_b = data.B - data.B_true;
    const double tolerance = 4.0 * std::sqrt(2.0 / 20000.0);  // relative, on variances (Gaussian's is the larger)
    for (Index j = 0; j < 6; ++j) {
      EXPECT_NEAR(noise_a.col(j).squaredNorm() / 20000.0 / (kStdA(j) * kStdA(j)), 1.0, tolerance) << j;
      EXPECT_NEAR(noise_b.col(j).squaredNorm() / 20000.0 / (kStdB(j) * kStdB(j)), 1.0, tolerance) << j;
    }
    // The rest rows: zero accelerations and a constant load, with the same noise.
    const NoiseModel rest = NoiseModel::from_rest(data.rest_A, data.rest_B);
    for (Index j = 0; j < 6; ++j) {
      EXPECT_NEAR(rest.cov_a()(j, j) / (kStdA(j) * kStdA(j)), 1.0, tolerance) << j;
      EXPECT_NEAR(rest.cov_b()(j, j) / (kStdB(j) * kStdB(j)), 1.0, tolerance) << j;
    }
    // No static load unless one is asked for (rest_force, `hexapod simulate --preload`): noise about 0.
    EXPECT_LT(rest.rest_mean_b().norm(), 0.2);
  }
}

TEST(SimulatePerChannel, OneValuePerSideIsTheVarianceAndUnitsScaleB) {
  hexapod::SimulationOptions by_variance;
  by_variance.samples = 30;
  by_variance.noise_var = 0.49;
  by_variance.force_noise_var = 4.0;
  hexapod::SimulationOptions by_std = by_variance;
  by_std.noise_var = 0.0;
  by_std.force_noise_var.reset();
  by_std.noise_std_a = VectorXd::Constant(1, 0.7);
  by_std.noise_std_b = VectorXd::Constant(1, 2.0);
  const MatrixXd M = hexapod::thesis_mass_matrix();
  const hexapod::Measurements a = hexapod::simulate(M, by_variance, 12), b = hexapod::simulate(M, by_std, 12);
  // The same draws in the same order (the noise's width computed another way: to rounding).
  EXPECT_LT(relative_error(b.A, a.A), 1e-15);
  EXPECT_LT(relative_error(b.B, a.B), 1e-15);
  EXPECT_EQ(b.rest_A.rows(), 0);
  by_std.scale_b = 1e-3;
  const hexapod::Measurements kn = hexapod::simulate(M, by_std, 12);
  EXPECT_EQ(kn.A, b.A);
  EXPECT_LT(relative_error(kn.B, 1e-3 * b.B), 1e-15);
  const NoiseModel truth = hexapod::true_noise_model(by_std, 6).resolved(6, 6);
  EXPECT_LT(relative_error(truth.cov_b(), MatrixXd(4e-6 * MatrixXd::Identity(6, 6))), 1e-15);
  // Misuse: both ways of giving A's noise, a wrong length.
  hexapod::SimulationOptions both = by_std;
  both.noise_var = 1.0;
  EXPECT_FALSE(both.is_valid());
  hexapod::SimulationOptions wrong = by_std;
  wrong.noise_std_a = VectorXd::Ones(4);
  EXPECT_THROW((void)hexapod::simulate(M, wrong, 1), std::invalid_argument);
}

TEST(ThesisExperimentWithNoiseModels, RunsEveryMethodWithEveryModelButSpde) {
  experiment::ThesisExperimentOptions options;
  options.simulation.samples = 200;
  options.simulation.distribution = hexapod::NoiseDistribution::Gaussian;
  options.simulation.noise_std_a = kStdA;
  options.simulation.noise_std_b = kStdB;
  options.simulation.rest_samples = 500;
  options.methods = {Method::Spde, Method::PsdLeastSquares, Method::SpdTotalLeastSquares};
  options.noise_models = {experiment::FitNoise::None, experiment::FitNoise::True, experiment::FitNoise::Rest};
  experiment::MonteCarloOptions monte_carlo;
  monte_carlo.trials = 8;
  monte_carlo.seed = 3;
  const experiment::ThesisExperimentResult result = experiment::run_thesis_experiment(options, monte_carlo);
  ASSERT_EQ(result.methods.size(), 7u);  // spde once
  EXPECT_THROW((void)result.of(Method::Spde, experiment::FitNoise::True), std::invalid_argument);
  // The numbers are the fits': trial 0 of spd-tls with the true covariances.
  Random random(trial_seed(3, 0));
  const hexapod::Measurements data = hexapod::simulate(hexapod::thesis_mass_matrix(), options.simulation, random);
  const FitResult r = fit(data.A, data.B, Method::SpdTotalLeastSquares,
                          with_noise(hexapod::true_noise_model(options.simulation, 6)));
  EXPECT_NEAR(result.of(Method::SpdTotalLeastSquares, experiment::FitNoise::True).errors[0],
              (r.X - hexapod::thesis_mass_matrix()).norm(), 1e-9);
  const FitResult rest = fit(data.A, data.B, Method::SpdTotalLeastSquares,
                             with_noise(NoiseModel::from_rest(data.rest_A, data.rest_B)));
  EXPECT_NEAR(result.of(Method::SpdTotalLeastSquares, experiment::FitNoise::Rest).errors[0],
              (rest.X - hexapod::thesis_mass_matrix()).norm(), 1e-9);
  // Knowing the noise helps: the likelihood fit beats unweighted psd-ls (0.33 against 0.62 here;
  // docs/guide.md's table has 0.476 against 0.727 at m = 100).
  EXPECT_LT(result.of(Method::SpdTotalLeastSquares, experiment::FitNoise::True).summary.mean,
            result.of(Method::PsdLeastSquares, experiment::FitNoise::None).summary.mean);
  // A rest model needs rest rows.
  options.simulation.rest_samples = 0;
  EXPECT_THROW((void)experiment::run_thesis_experiment(options, monte_carlo), std::invalid_argument);
}

}  // namespace
}  // namespace spdfit
