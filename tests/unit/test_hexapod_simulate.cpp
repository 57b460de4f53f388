// The random source and the thesis' data generator (000, appendix B): the draws have the
// distributions, variances and order they are documented to have, and are reproducible.
//
// Statistical checks use fixed seeds and a tolerance of kSigmas standard errors of the
// statistic, with the standard error computed from the distribution's known moments (not
// from the run being tested).
#include <gtest/gtest.h>

#include <cmath>
#include <set>

#include "spdfit/hexapod/simulate.hpp"
#include "spdfit/random.hpp"

namespace spdfit {
namespace {

using hexapod::Measurements;
using hexapod::NoiseDistribution;
using hexapod::SimulationOptions;

// Four standard errors: a correct generator fails such a check with probability 6e-5.
constexpr double kSigmas = 4.0;

// Mean and variance of the entries of M (population variance: the mean is known to be 0 but
// estimated anyway, which costs nothing at this size).
struct Moments {
  double mean, variance;
};
Moments moments(const Eigen::MatrixXd& M) {
  const double mean = M.mean();
  return {mean, (M.array() - mean).square().mean()};
}

TEST(Random, TrialSeedsAreDistinctAndDependOnBothArguments) {
  std::set<std::uint64_t> seen;
  for (std::uint64_t seed = 0; seed < 20; ++seed)
    for (std::uint64_t trial = 0; trial < 500; ++trial) seen.insert(trial_seed(seed, trial));
  EXPECT_EQ(seen.size(), 20u * 500u);
  EXPECT_NE(trial_seed(1, 2), trial_seed(2, 1));
  EXPECT_EQ(trial_seed(7, 3), trial_seed(7, 3));
}

TEST(Random, UniformAndNormalHaveTheirMoments) {
  Random random(11);
  constexpr int kCount = 200000;
  double sum = 0, sum_sq = 0, normal_sum = 0, normal_sq = 0, normal_fourth = 0;
  for (int k = 0; k < kCount; ++k) {
    const double u = random.uniform();
    ASSERT_GE(u, 0.0);
    ASSERT_LT(u, 1.0);
    sum += u;
    sum_sq += u * u;
    const double z = random.normal();
    normal_sum += z;
    normal_sq += z * z;
    normal_fourth += z * z * z * z;
  }
  const double n = kCount;
  // Uniform[0, 1): mean 1/2 (sd of one draw 1/sqrt(12)), E u^2 = 1/3 (sd sqrt(1/5 - 1/9)).
  EXPECT_NEAR(sum / n, 0.5, kSigmas * std::sqrt(1.0 / 12.0 / n));
  EXPECT_NEAR(sum_sq / n, 1.0 / 3.0, kSigmas * std::sqrt((1.0 / 5.0 - 1.0 / 9.0) / n));
  // Normal: mean 0 (sd 1), E z^2 = 1 (sd sqrt 2), E z^4 = 3 (sd sqrt(105 - 9)).
  EXPECT_NEAR(normal_sum / n, 0.0, kSigmas / std::sqrt(n));
  EXPECT_NEAR(normal_sq / n, 1.0, kSigmas * std::sqrt(2.0 / n));
  EXPECT_NEAR(normal_fourth / n, 3.0, kSigmas * std::sqrt(96.0 / n));
}

TEST(Random, SameSeedSameNumbers) {
  Random a(5), b(5), c(6);
  bool differs = false;
  for (int k = 0; k < 100; ++k) {
    const double x = a.normal();
    EXPECT_EQ(x, b.normal());
    differs = differs || x != c.normal();
  }
  EXPECT_TRUE(differs);
}

TEST(HexapodSimulate, FollowsTheThesisGeneratorDrawOrder) {
  // A_true, then A's noise, then B's noise, each column by column, as the M-file.
  SimulationOptions options;
  options.samples = 4;
  options.noise_var = 0.5;
  const Eigen::MatrixXd truth = hexapod::thesis_mass_matrix();
  Random random(21), replay(21);
  const Measurements data = hexapod::simulate(truth, options, random);
  const double h_signal = 5.0, h_noise = std::sqrt(1.5);
  for (Eigen::Index j = 0; j < 6; ++j)
    for (Eigen::Index i = 0; i < 4; ++i) EXPECT_EQ(data.A_true(i, j), replay.uniform(-h_signal, h_signal));
  for (Eigen::Index j = 0; j < 6; ++j)
    for (Eigen::Index i = 0; i < 4; ++i)
      EXPECT_EQ(data.A(i, j), data.A_true(i, j) + replay.uniform(-h_noise, h_noise));
  EXPECT_TRUE(data.B_true == data.A_true * truth);
  for (Eigen::Index j = 0; j < 6; ++j)
    for (Eigen::Index i = 0; i < 4; ++i)
      EXPECT_EQ(data.B(i, j), data.B_true(i, j) + replay.uniform(-h_noise, h_noise));
}

TEST(HexapodSimulate, SignalAndNoiseHaveTheRequestedVariances) {
  const Eigen::MatrixXd truth = hexapod::thesis_mass_matrix();
  for (NoiseDistribution distribution : {NoiseDistribution::Uniform, NoiseDistribution::Gaussian}) {
    for (double noise_var : {0.082, 1.28}) {
      SimulationOptions options;
      options.samples = 20000;
      options.noise_var = noise_var;
      options.signal_var = 4.0;
      options.distribution = distribution;
      Random random(31);
      const Measurements data = hexapod::simulate(truth, options, random);
      const double count = static_cast<double>(data.A.size());
      // The variance of one squared draw: uniform 4/5 V^2 (E x^4 = 9/5 V^2), Gaussian 2 V^2.
      const double fourth = distribution == NoiseDistribution::Uniform ? 0.8 : 2.0;
      for (const Eigen::MatrixXd& noise :
           {Eigen::MatrixXd(data.A - data.A_true), Eigen::MatrixXd(data.B - data.B_true)}) {
        const Moments m = moments(noise);
        EXPECT_NEAR(m.mean, 0.0, kSigmas * std::sqrt(noise_var / count));
        EXPECT_NEAR(m.variance, noise_var, kSigmas * std::sqrt(fourth / count) * noise_var);
        if (distribution == NoiseDistribution::Uniform) {
          EXPECT_LE(noise.cwiseAbs().maxCoeff(), std::sqrt(3.0 * noise_var) * (1 + 1e-15));
        }
      }
      // The signal is uniform whatever the noise: on [-2 sqrt 3, 2 sqrt 3] for S = 4.
      const Moments signal = moments(data.A_true);
      EXPECT_NEAR(signal.variance, 4.0, kSigmas * std::sqrt(0.8 / count) * 4.0);
      EXPECT_LE(data.A_true.cwiseAbs().maxCoeff(), std::sqrt(12.0));
    }
  }
}

TEST(HexapodSimulate, ForceNoiseCanHaveItsOwnVariance) {
  SimulationOptions options;
  options.samples = 20000;
  options.noise_var = 0.1;
  options.force_noise_var = 2.0;
  Random random(35);
  const Measurements data = hexapod::simulate(hexapod::thesis_mass_matrix(), options, random);
  const double count = static_cast<double>(data.A.size());
  EXPECT_NEAR(moments(data.A - data.A_true).variance, 0.1, kSigmas * std::sqrt(0.8 / count) * 0.1);
  EXPECT_NEAR(moments(data.B - data.B_true).variance, 2.0, kSigmas * std::sqrt(0.8 / count) * 2.0);
  options.force_noise_var = -1.0;
  EXPECT_THROW(hexapod::simulate(hexapod::thesis_mass_matrix(), options, random), std::invalid_argument);
}

TEST(HexapodSimulate, DefaultSignalIsUniformOnMinusFiveToFive) {
  SimulationOptions options;
  options.samples = 5000;
  Random random(41);
  const Measurements data = hexapod::simulate(hexapod::thesis_mass_matrix(), options, random);
  EXPECT_LT(data.A_true.maxCoeff(), 5.0);
  EXPECT_GE(data.A_true.minCoeff(), -5.0);
  EXPECT_GT(data.A_true.maxCoeff(), 4.99);  // 30000 draws reach within 0.01 of the ends
  EXPECT_LT(data.A_true.minCoeff(), -4.99);
  EXPECT_TRUE(data.A == data.A_true);  // noise_var 0
}

TEST(HexapodSimulate, IsReproducibleFromTheSeed) {
  SimulationOptions options;
  options.noise_var = 0.86;
  options.distribution = NoiseDistribution::Gaussian;
  Random a(51), b(51), c(52);
  const Measurements x = hexapod::simulate(hexapod::thesis_mass_matrix(), options, a);
  const Measurements y = hexapod::simulate(hexapod::thesis_mass_matrix(), options, b);
  const Measurements z = hexapod::simulate(hexapod::thesis_mass_matrix(), options, c);
  EXPECT_TRUE(x.A == y.A && x.B == y.B);
  EXPECT_FALSE(x.A == z.A);
}

TEST(HexapodSimulate, RejectsInvalidOptions) {
  Random random(1);
  SimulationOptions options;
  options.noise_var = -1.0;
  EXPECT_THROW(hexapod::simulate(hexapod::thesis_mass_matrix(), options, random), std::invalid_argument);
  options = {};
  options.samples = 0;
  EXPECT_THROW(hexapod::simulate(hexapod::thesis_mass_matrix(), options, random), std::invalid_argument);
  options = {};
  options.signal_var = 0.0;
  EXPECT_THROW(hexapod::simulate(hexapod::thesis_mass_matrix(), options, random), std::invalid_argument);
  EXPECT_THROW(hexapod::simulate(Eigen::MatrixXd::Zero(2, 3), SimulationOptions{}, random),
               std::invalid_argument);
}

TEST(HexapodSimulate, ThesisMassMatrixIsEquation6_1) {
  const Eigen::MatrixXd M = hexapod::thesis_mass_matrix();
  EXPECT_EQ(M(0, 0), 4.6881);
  EXPECT_EQ(M(2, 5), 1.7984);
  EXPECT_EQ(M(3, 4), 0.6114);
  EXPECT_EQ(M(5, 0), 0.6110);
  EXPECT_LE((M - M.transpose()).cwiseAbs().maxCoeff(), 0.0);  // symmetric as printed
}

}  // namespace
}  // namespace spdfit
