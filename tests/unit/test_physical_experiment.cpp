// The physical-identification experiment (experiment/physical.hpp) on the thesis' set-up: the
// estimator's mean error of M_p is at most 0.6 times the best generic method's at m = 12, 30, 100
// and 1000 (by more than three standard errors of the ratio), every estimate is physically
// consistent, and for a thin rod the unconstrained grey-box fit is not.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "spdfit/experiment/physical.hpp"

namespace spdfit {
namespace {

// The ratio of the mean errors of a to b over the same trials, and its standard error by the delta
// method with the pairs' covariance (trials where either failed are left out).
std::pair<double, double> ratio_of_means(const std::vector<double>& a, const std::vector<double>& b) {
  double sa = 0, sb = 0, n = 0;
  for (std::size_t k = 0; k < a.size(); ++k) {
    if (std::isnan(a[k]) || std::isnan(b[k])) continue;
    sa += a[k];
    sb += b[k];
    ++n;
  }
  const double ma = sa / n, mb = sb / n;
  double vaa = 0, vbb = 0, vab = 0;
  for (std::size_t k = 0; k < a.size(); ++k) {
    if (std::isnan(a[k]) || std::isnan(b[k])) continue;
    vaa += (a[k] - ma) * (a[k] - ma);
    vbb += (b[k] - mb) * (b[k] - mb);
    vab += (a[k] - ma) * (b[k] - mb);
  }
  vaa /= (n - 1) * n;
  vbb /= (n - 1) * n;
  vab /= (n - 1) * n;
  const double r = ma / mb;
  return {r, r * std::sqrt(vaa / (ma * ma) + vbb / (mb * mb) - 2 * vab / (ma * mb))};
}

TEST(PhysicalExperiment, BeatsTheBestGenericMethodByTheGoalsMargin) {
#ifdef SPDFIT_TEST_SANITIZED
  GTEST_SKIP() << "a statistical Monte Carlo test: run in the plain build (a second there, minutes under the sanitizers)";
#endif
  experiment::PhysicalExperimentOptions options;  // built-in hexapod, width-3.2 noise, m = 12 ... 1000
  options.variants = {"physical"};
  experiment::MonteCarloOptions monte_carlo;
  monte_carlo.trials = 1000;
  monte_carlo.seed = 34;
  const experiment::PhysicalExperimentResult r = experiment::run_physical_experiment(options, monte_carlo);
  ASSERT_EQ(r.rows.size(), 4u);
  for (const experiment::PhysicalExperimentRow& row : r.rows) {
    const auto& spde = row.methods[0];
    const auto& spd_tls = row.methods[1];
    const auto& physical = row.methods[2];
    ASSERT_EQ(physical.name, "physical");
    const auto& best = spde.summary.mean < spd_tls.summary.mean ? spde : spd_tls;
    const auto [ratio, se] = ratio_of_means(physical.errors, best.errors);
    EXPECT_LT(ratio + 3 * se, 0.6) << "m = " << row.samples << ": " << ratio << " +- " << se << " against "
                                   << best.name;
    EXPECT_EQ(physical.summary.failures, 0u);
    EXPECT_EQ(physical.inconsistent, 0u) << "m = " << row.samples;
  }
}

TEST(PhysicalExperiment, ThinRodIsConsistentWhereTheGreyBoxIsNot) {
#ifdef SPDFIT_TEST_SANITIZED
  GTEST_SKIP() << "a statistical Monte Carlo test: run in the plain build (a second there, minutes under the sanitizers)";
#endif
  experiment::PhysicalExperimentOptions options;
  RigidBodyInertia rod;
  rod.mass = 11.973;
  const double length = 0.45, thickness = 0.0045;
  const double across = rod.mass * thickness * thickness / 12.0, along = rod.mass * length * length / 12.0;
  rod.inertia = Eigen::Vector3d(2 * across, along + across, along + across).asDiagonal();
  options.payload = rod;
  options.samples = {30, 300};
  options.methods = {};
  options.variants = {"physical", "grey-box-tls"};
  experiment::MonteCarloOptions monte_carlo;
  monte_carlo.trials = 100;
  const experiment::PhysicalExperimentResult r = experiment::run_physical_experiment(options, monte_carlo);
  for (const experiment::PhysicalExperimentRow& row : r.rows) {
    EXPECT_EQ(row.methods[0].inconsistent, 0u) << "m = " << row.samples;
    EXPECT_GT(row.methods[1].inconsistent, 90u) << "m = " << row.samples;
    // Consistency costs nothing here: the constrained estimate is the more accurate one.
    EXPECT_LT(row.methods[0].summary.mean, row.methods[1].summary.mean) << "m = " << row.samples;
  }
}

TEST(PhysicalExperiment, RejectsBadOptions) {
  experiment::PhysicalExperimentOptions options;
  experiment::MonteCarloOptions monte_carlo;
  monte_carlo.trials = 2;
  options.variants = {"physics"};
  EXPECT_THROW(experiment::run_physical_experiment(options, monte_carlo), std::invalid_argument);
  options.variants = {"physical:common"};  // the cubic hexapod confounds a common strut mass
  EXPECT_THROW(experiment::run_physical_experiment(options, monte_carlo), std::invalid_argument);
  options.variants = {"physical"};
  options.samples = {5};
  EXPECT_THROW(experiment::run_physical_experiment(options, monte_carlo), std::invalid_argument);
  EXPECT_TRUE(experiment::physical_variant("grey-box-ls:each").has_value());
  EXPECT_FALSE(experiment::physical_variant("grey-box-ls:geometry").has_value());
}

}  // namespace
}  // namespace spdfit
