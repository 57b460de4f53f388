// The Monte Carlo machinery: every trial runs once with its own generator, results do not depend
// on the number of threads, errors propagate; and the summary statistics.
#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <vector>

#include "spdfit/experiment/monte_carlo.hpp"
#include "spdfit/experiment/paper.hpp"
#include "spdfit/experiment/statistics.hpp"
#include "spdfit/experiment/thesis.hpp"

namespace spdfit {
namespace {

using namespace spdfit::experiment;

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

TEST(MonteCarlo, RunsEveryTrialOnceWithItsOwnSeed) {
  for (unsigned threads : {1u, 3u, 8u}) {
    MonteCarloOptions options;
    options.trials = 1000;
    options.seed = 9;
    options.threads = threads;
    std::vector<std::atomic<int>> calls(options.trials);
    std::vector<double> first_draw(options.trials);
    run_trials(options, [&](std::size_t k, Random& random) {
      ++calls[k];
      first_draw[k] = random.uniform();
    });
    for (std::size_t k = 0; k < options.trials; ++k) {
      EXPECT_EQ(calls[k], 1) << "trial " << k;
      EXPECT_EQ(first_draw[k], Random(trial_seed(9, k)).uniform()) << "trial " << k;
    }
  }
}

TEST(MonteCarlo, ReportsProgressAndRethrowsTheFirstError) {
  MonteCarloOptions options;
  options.trials = 50;
  options.threads = 2;
  std::size_t last_done = 0, last_total = 0;
  options.progress = [&](std::size_t done, std::size_t total) {
    last_done = done;
    last_total = total;
  };
  run_trials(options, [](std::size_t, Random&) {});
  EXPECT_EQ(last_done, 50u);
  EXPECT_EQ(last_total, 50u);
  EXPECT_THROW(run_trials(options,
                          [](std::size_t k, Random&) {
                            if (k == 17) throw std::runtime_error("trial 17 failed");
                          }),
               std::runtime_error);
  options.trials = 0;
  EXPECT_THROW(run_trials(options, [](std::size_t, Random&) {}), std::invalid_argument);
}

TEST(MonteCarlo, ThesisExperimentIsIndependentOfTheThreadCount) {
  ThesisExperimentOptions options;
  options.simulation.noise_var = 0.86;
  MonteCarloOptions monte_carlo;
  monte_carlo.trials = 200;
  monte_carlo.seed = 2024;
  monte_carlo.threads = 1;
  const ThesisExperimentResult one = run_thesis_experiment(options, monte_carlo);
  for (unsigned threads : {2u, 5u}) {
    monte_carlo.threads = threads;
    const ThesisExperimentResult many = run_thesis_experiment(options, monte_carlo);
    for (std::size_t i = 0; i < one.methods.size(); ++i) {
      for (std::size_t k = 0; k < monte_carlo.trials; ++k) {
        const double a = one.methods[i].errors[k], b = many.methods[i].errors[k];
        EXPECT_TRUE(a == b || (std::isnan(a) && std::isnan(b))) << "method " << i << ", trial " << k;
      }
    }
  }
}

TEST(MonteCarlo, Paper2x2IsIndependentOfTheThreadCount) {
  Paper2x2Options options;
  options.std_a = 1.0;
  MonteCarloOptions monte_carlo;
  monte_carlo.trials = 300;
  monte_carlo.threads = 1;
  const EntryExperimentResult one = run_paper_2x2(options, monte_carlo);
  monte_carlo.threads = 4;
  const EntryExperimentResult four = run_paper_2x2(options, monte_carlo);
  for (std::size_t i = 0; i < one.methods.size(); ++i) {
    EXPECT_TRUE(one.methods[i].errors.cwiseEqual(four.methods[i].errors).all() ||
                (one.methods[i].errors.hasNaN() && four.methods[i].errors.hasNaN()));
    EXPECT_TRUE(one.methods[i].mae == four.methods[i].mae);
  }
}

TEST(Statistics, SummarizeKnownValues) {
  const Summary s = summarize({4.0, 1.0, kNaN, 3.0, 2.0});
  EXPECT_EQ(s.count, 4u);
  EXPECT_EQ(s.failures, 1u);
  EXPECT_DOUBLE_EQ(s.mean, 2.5);
  EXPECT_DOUBLE_EQ(s.std, std::sqrt(5.0 / 3.0));
  EXPECT_DOUBLE_EQ(s.median, 2.5);
  EXPECT_EQ(s.min, 1.0);
  EXPECT_EQ(s.max, 4.0);
  EXPECT_DOUBLE_EQ(s.standard_error(), std::sqrt(5.0 / 3.0) / 2.0);
  EXPECT_EQ(summarize({5.0, 1.0, 3.0}).median, 3.0);
  EXPECT_EQ(summarize({7.0}).std, 0.0);
  EXPECT_TRUE(std::isnan(summarize({kNaN}).mean));
}

TEST(Statistics, PairedComparisonAndEntries) {
  const PairedComparison c = compare_paired({1.0, 2.0, 3.0, kNaN}, {2.0, 2.5, 2.0, 1.0});
  EXPECT_EQ(c.count, 3u);
  EXPECT_DOUBLE_EQ(c.mean_difference, (-1.0 - 0.5 + 1.0) / 3.0);
  EXPECT_DOUBLE_EQ(c.fraction_lower, 2.0 / 3.0);
  EXPECT_THROW(compare_paired({1.0}, {1.0, 2.0}), std::invalid_argument);

  const auto entries = upper_triangle_entries(6);
  EXPECT_EQ(entries.size(), 21u);
  EXPECT_EQ(entries[5], std::make_pair(Eigen::Index(0), Eigen::Index(5)));
  EXPECT_EQ(entries[6], std::make_pair(Eigen::Index(1), Eigen::Index(1)));

  Eigen::MatrixXd errors(3, 2);
  errors << 1.0, -2.0, -3.0, 2.0, kNaN, kNaN;
  const EntryStatistics s = summarize_entries(Method::Spde, errors);
  EXPECT_EQ(s.count, 2u);
  EXPECT_EQ(s.failures, 1u);
  EXPECT_DOUBLE_EQ(s.mae(0), 2.0);
  EXPECT_DOUBLE_EQ(s.bias(0), -1.0);
  EXPECT_DOUBLE_EQ(s.std(0), std::sqrt(8.0));
  EXPECT_DOUBLE_EQ(s.bias(1), 0.0);
}

}  // namespace
}  // namespace spdfit
