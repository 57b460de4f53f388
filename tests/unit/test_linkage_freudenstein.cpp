// The Freudenstein equation, link lengths, position analysis and Grashof types (notes 002, 3.3.3).
#include <gtest/gtest.h>

#include "linkage_support.hpp"
#include "spdfit/linkage/analysis.hpp"
#include "spdfit/linkage/freudenstein.hpp"
#include "spdfit/linkage/grashof.hpp"

namespace spdfit::linkage {
namespace {

using test::kDeg;
using test::kEps;
using test::kPi;

// Angles and lengths computed from O(1) data through a few trigonometric calls: relative
// accuracy of a few hundred eps at worst.
constexpr double kTight = 256 * kEps;

TEST(Freudenstein, ParametersAndLengthsRoundTrip) {
  for (const auto& known : test::known_linkages()) {
    const Eigen::Vector3d k = freudenstein_parameters(known.bar);
    std::string problem;
    const auto bar = link_lengths(k, &problem);
    ASSERT_TRUE(bar) << known.name << ": " << problem;
    EXPECT_NEAR(bar->a1, 1.0, kTight);
    EXPECT_NEAR(bar->a2, known.bar.a2, kTight) << known.name;
    EXPECT_NEAR(bar->a3, known.bar.a3, kTight) << known.name;
    EXPECT_NEAR(bar->a4, known.bar.a4, kTight) << known.name;
  }
}

TEST(Freudenstein, ParametersAreScaleFree) {
  const FourBar bar{2.0, 0.8, 2.2, 1.8};
  const FourBar unit{1.0, 0.4, 1.1, 0.9};
  EXPECT_LT((freudenstein_parameters(bar) - freudenstein_parameters(unit)).norm(), kTight);
}

TEST(Freudenstein, NoRealLinkageIsReported) {
  std::string problem;
  EXPECT_FALSE(link_lengths(Eigen::Vector3d(1.0, -2.0, 1.0), &problem));
  EXPECT_NE(problem.find("negative input link a2"), std::string::npos) << problem;
  EXPECT_FALSE(link_lengths(Eigen::Vector3d(1.0, 2.0, 0.0), &problem));
  EXPECT_NE(problem.find("infinite output link a4"), std::string::npos) << problem;
  // a2 = a4 = 1: a3^2 = 3 - 2 k1 <= 0 for k1 >= 1.5.
  EXPECT_FALSE(link_lengths(Eigen::Vector3d(1.6, 1.0, 1.0), &problem));
  EXPECT_NE(problem.find("a3^2"), std::string::npos) << problem;
  EXPECT_FALSE(link_lengths(Eigen::Vector3d(std::nan(""), 1.0, 1.0), &problem));
  EXPECT_THROW(freudenstein_parameters(FourBar{1.0, -1.0, 1.0, 1.0}), std::invalid_argument);
}

// The output angle closes the loop: the coupler joins the crank tip to the output link's tip.
TEST(Freudenstein, OutputAngleClosesTheLoopOnBothBranches) {
  for (const auto& known : test::known_linkages()) {
    const FourBar& bar = known.bar;
    const Eigen::Vector3d k = freudenstein_parameters(bar);
    const auto [lo, hi] = test::sweep_range(bar);
    for (int branch : {1, -1}) {
      for (int i = 0; i <= 20; ++i) {
        const double psi = lo + (hi - lo) * i / 20;
        const auto phi = output_angle(k, psi, branch);
        ASSERT_TRUE(phi) << known.name << " psi " << psi;
        EXPECT_NEAR(freudenstein_residual(k, psi, *phi), 0.0, 64 * kEps * k.norm());
        const Eigen::Vector2d A(bar.a2 * std::cos(psi), bar.a2 * std::sin(psi));
        const Eigen::Vector2d B(bar.a1 + bar.a4 * std::cos(*phi), bar.a4 * std::sin(*phi));
        EXPECT_NEAR((B - A).norm(), bar.a3, 1e-12) << known.name;
      }
    }
  }
}

TEST(Freudenstein, BranchesMeetAtDeadPoints) {
  const FourBar rocker{1.0, 0.9, 1.1, 0.4};  // rocker-crank: the input has limits
  const Eigen::Vector3d k = freudenstein_parameters(rocker);
  const std::vector<double> dead = dead_points(rocker);
  ASSERT_EQ(dead.size(), 4u);
  for (double psi : dead) {
    const double mu = transmission_angle(rocker, psi);
    EXPECT_TRUE(std::abs(mu) < 1e-6 || std::abs(mu - kPi) < 1e-6) << mu;
    const auto plus = output_angle(k, psi, 1), minus = output_angle(k, psi, -1);
    ASSERT_TRUE(plus && minus);
    EXPECT_NEAR(wrap_angle(*plus - *minus), 0.0, 1e-6);  // sqrt(eps): arccos at +-1
    EXPECT_NEAR(freudenstein_dphi(k, psi, *plus), 0.0, 1e-6);
  }
  // Beyond a limit the input cannot go: no output angle, no transmission angle.
  int outside = 0;
  for (int i = 0; i < 360; ++i) {
    const double psi = i * kDeg;
    const bool can = !std::isnan(transmission_angle(rocker, psi));
    EXPECT_EQ(can, output_angle(k, psi, 1).has_value()) << psi;
    outside += !can;
  }
  EXPECT_GT(outside, 0);
}

TEST(Grashof, KnownTypes) {
  for (const auto& known : test::known_linkages()) {
    EXPECT_EQ(grashof_type(known.bar), known.type) << known.name;
  }
  EXPECT_EQ(grashof_type(FourBar{1.0, 0.5, 1.0, 0.5}), GrashofType::ChangePoint);  // parallelogram
  EXPECT_STREQ(to_string(GrashofType::CrankRocker), "crank-rocker");
  EXPECT_STREQ(to_string(GrashofType::TripleRocker), "triple-rocker");
  EXPECT_THROW(grashof_type(FourBar{1.0, 0.0, 1.0, 1.0}), std::invalid_argument);
}

TEST(Analysis, CrankTurnsFullyWithoutDeadPoints) {
  const FourBar bar{1.0, 0.4, 1.1, 0.9};
  Eigen::VectorXd psi = Eigen::VectorXd::LinSpaced(73, 0.0, 2 * kPi);
  const Analysis a = analyze(bar, psi);
  EXPECT_EQ(a.grashof, GrashofType::CrankRocker);
  EXPECT_TRUE(a.input_fully_rotates);
  EXPECT_TRUE(a.dead_points.empty());
  for (const AnalysisSample& s : a.samples) {
    ASSERT_TRUE(s.phi_plus && s.phi_minus && s.transmission_angle);
  }
  // Unwrapped along psi: consecutive samples 5 degrees apart move the output by well under 90 deg.
  for (std::size_t i = 1; i < a.samples.size(); ++i) {
    EXPECT_LT(std::abs(*a.samples[i].phi_plus - *a.samples[i - 1].phi_plus), 0.5 * kPi);
  }
  ASSERT_TRUE(a.transmission);
  EXPECT_GT(a.transmission->min, 0.0);
  EXPECT_LT(a.transmission->max, kPi);
  // The extreme transmission angles of a crank-rocker are at psi = 0 and psi = 180 degrees.
  EXPECT_NEAR(a.transmission->min, std::min(transmission_angle(bar, 0.0), transmission_angle(bar, kPi)),
              1e-14);
  EXPECT_NEAR(a.transmission->max, std::max(transmission_angle(bar, 0.0), transmission_angle(bar, kPi)),
              1e-14);
}

TEST(Analysis, RockerInputHasLimitsAndGaps) {
  const FourBar bar{1.0, 0.9, 1.1, 0.4};
  Eigen::VectorXd psi = Eigen::VectorXd::LinSpaced(361, -kPi, kPi);
  const Analysis a = analyze(bar, psi);
  EXPECT_FALSE(a.input_fully_rotates);
  EXPECT_EQ(a.dead_points.size(), 4u);
  int gaps = 0;
  for (const AnalysisSample& s : a.samples) gaps += !s.phi_plus;
  EXPECT_GT(gaps, 0);
  EXPECT_LT(gaps, 361);
}

TEST(MotionCheck, DeadPointInsideTheRangeIsABranchDefect) {
  const FourBar bar{1.0, 0.9, 1.1, 0.4};
  const Eigen::Vector3d k = freudenstein_parameters(bar);
  const auto [lo, hi] = test::sweep_range(bar);
  Eigen::VectorXd psi(3), phi(3);
  psi << lo, 0.5 * (lo + hi), hi;
  for (int i = 0; i < 3; ++i) phi(i) = *output_angle(k, psi(i), 1);
  MotionCheck check = check_motion(bar, psi, phi, 1);
  EXPECT_FALSE(check.branch_defect) << check.branch_defect_reason;
  EXPECT_TRUE(check.dead_points.empty());
  // Prescribe one output on the other branch: the classic branch defect.
  phi(1) = *output_angle(k, psi(1), -1);
  check = check_motion(bar, psi, phi, 1);
  EXPECT_TRUE(check.branch_defect);
  EXPECT_NE(check.branch_defect_reason.find("nearer to the other assembly branch"), std::string::npos);
  // Sweep past a limit: the range contains a dead point.
  const double past = hi + 0.25 * (hi - lo);
  Eigen::VectorXd psi2(2), phi2(2);
  psi2 << lo, past;
  phi2 << phi(0), phi(0);
  check = check_motion(bar, psi2, phi2, 1);
  EXPECT_TRUE(check.branch_defect);
  EXPECT_FALSE(check.dead_points.empty());
  // The limit is passed with mu = 0 or pi.
  EXPECT_TRUE(check.transmission.min < 1e-12 || check.transmission.max > kPi - 1e-12);
}

// Regression (fuzz/regressions/linkage_pairs/oom-583fb19...): prescribed angles spanning 1e40 rad
// made transmission_angle_range list a candidate angle for every turn, until 2 GB ran out.
TEST(Freudenstein, TransmissionRangeOverManyTurnsIsOneTurns) {
  const FourBar crank{1.0, 0.4, 1.1, 0.9};
  const AngleRange turn = transmission_angle_range(crank, 0.0, 2.0 * kPi);
  for (const auto& [lo, hi] :
       {std::pair{-1.1e33, 2.7e40}, std::pair{-3.0, 3.5}, std::pair{1e15, 1e15 + 7.0}}) {
    const AngleRange r = transmission_angle_range(crank, lo, hi);
    EXPECT_DOUBLE_EQ(r.min, turn.min) << lo << ".." << hi;
    EXPECT_DOUBLE_EQ(r.max, turn.max) << lo << ".." << hi;
  }
}

}  // namespace
}  // namespace spdfit::linkage
