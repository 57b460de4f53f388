// Function-generator synthesis: exact recovery from known linkages, the design error against an
// independent least-squares solve, Gauss-Newton on the structural error, precision points,
// branch defects, dial zeros, and bad input (notes 002, sections 3.3.3-3.6).
#include <gtest/gtest.h>

#include <Eigen/SVD>

#include "linkage_support.hpp"
#include "spdfit/linkage/design_error.hpp"
#include "spdfit/linkage/pairs_file.hpp"
#include "spdfit/linkage/synthesis.hpp"

namespace spdfit::linkage {
namespace {

using test::Generator;
using test::kDeg;
using test::kEps;
using test::kPi;

const VectorXd kNoWeights;

// Exact pairs are reproduced to rounding amplified by cond(S) (at most a few hundred here).
constexpr double kExact = 1e-10;

// ds/dk at k on `branch` (eq. 3.16): D^-1 S at the generated angles.
MatrixXd structural_jacobian(const Eigen::Vector3d& k, const VectorXd& psi, const VectorXd& generated) {
  MatrixXd J = synthesis_matrix(psi, generated);
  for (Index i = 0; i < psi.size(); ++i) J.row(i) /= freudenstein_dphi(k, psi(i), generated(i));
  return J;
}

TEST(Synthesis, RecoversKnownLinkagesFromExactPairs) {
  for (const auto& known : test::known_linkages()) {
    for (int branch : {1, -1}) {
      VectorXd psi, phi;
      test::exact_pairs(known.bar, branch, 15, psi, phi);
      const SynthesisResult r = synthesize(psi, phi, kNoWeights);
      ASSERT_TRUE(r.ok()) << known.name << ": " << r.message;
      const Eigen::Vector3d k = freudenstein_parameters(known.bar);
      EXPECT_LT((r.design.k - k).norm(), kExact * k.norm()) << known.name;
      ASSERT_TRUE(r.design.lengths);
      EXPECT_NEAR(r.design.lengths->a2, known.bar.a2, kExact) << known.name;
      EXPECT_NEAR(r.design.lengths->a3, known.bar.a3, kExact) << known.name;
      EXPECT_NEAR(r.design.lengths->a4, known.bar.a4, kExact) << known.name;
      EXPECT_LT(r.design.design_error_norm, kExact);
      EXPECT_LT(r.design.structural_error_max, kExact);
      EXPECT_EQ(r.branch, branch) << known.name;
      EXPECT_LT((r.structural.k - k).norm(), kExact * k.norm()) << known.name;
      EXPECT_LE(r.structural.iterations, 1);
      ASSERT_TRUE(r.structural.check);
      EXPECT_EQ(r.structural.check->grashof, known.type) << known.name;
      EXPECT_FALSE(r.structural.check->branch_defect)
          << known.name << ": " << r.structural.check->branch_defect_reason;
    }
  }
}

// min ||W^(1/2) (S k - b)|| solved independently by the SVD of the weighted matrix.
TEST(Synthesis, DesignErrorEqualsAnIndependentWeightedLeastSquaresSolution) {
  Generator g(7);
  const FourBar bar{1.0, 0.4, 1.1, 0.9};
  VectorXd psi, phi;
  test::exact_pairs(bar, 1, 25, psi, phi);
  for (Index i = 0; i < phi.size(); ++i) phi(i) += 0.5 * kDeg * g.normal();
  VectorXd w(psi.size());
  for (Index i = 0; i < w.size(); ++i) w(i) = g.uniform(0.2, 5.0);
  const DesignErrorSolution d = design_error_synthesis(psi, phi, w);
  const MatrixXd Sw = w.cwiseSqrt().asDiagonal() * synthesis_matrix(psi, phi);
  const VectorXd bw = w.cwiseSqrt().asDiagonal() * synthesis_rhs(psi, phi);
  Eigen::JacobiSVD<MatrixXd> svd(Sw, Eigen::ComputeThinU | Eigen::ComputeThinV);
  const Eigen::Vector3d k = svd.solve(bw);
  EXPECT_LT((d.k - k).norm(), 64 * kEps * d.condition_number * k.norm());
  EXPECT_NEAR(d.design_error_norm, (bw - Sw * k).norm(), 1e-12);
  EXPECT_NEAR(d.condition_number, svd.singularValues()(0) / svd.singularValues()(2),
              1e-10 * d.condition_number);
  EXPECT_EQ(d.rank, 3);
  EXPECT_FALSE(d.used_svd);
  // A heavy weight pulls the design error at its position down.
  VectorXd heavy = VectorXd::Ones(psi.size());
  heavy(3) = 1e4;
  const Eigen::Vector3d k1 = design_error_synthesis(psi, phi, kNoWeights).k;
  const Eigen::Vector3d k2 = design_error_synthesis(psi, phi, heavy).k;
  const MatrixXd S = synthesis_matrix(psi, phi);
  const VectorXd b = synthesis_rhs(psi, phi);
  EXPECT_LT(std::abs((b - S * k2)(3)), 0.1 * std::abs((b - S * k1)(3)));
}

TEST(Synthesis, RankDeficientSynthesisMatrixUsesTheEditedSvd) {
  // Every position with the same output angle: the columns 1 and cos(phi) are parallel.
  VectorXd psi = VectorXd::LinSpaced(6, 10 * kDeg, 60 * kDeg), phi = VectorXd::Constant(6, 80 * kDeg);
  const DesignErrorSolution d = design_error_synthesis(psi, phi, kNoWeights);
  EXPECT_EQ(d.rank, 2);
  EXPECT_TRUE(d.used_svd);
  EXPECT_TRUE(std::isinf(d.condition_number) || d.condition_number > 1e15);
}

// Gauss-Newton minimizes the structural error: lower than the design solution's whenever the
// data are not generated exactly, and the normality condition S^T D^-1 s = 0 holds (notes 3.6.1).
TEST(Synthesis, GaussNewtonLowersTheStructuralErrorOfInexactData) {
  Generator g(8);
  int cases = 0;
  for (const auto& known : test::known_linkages()) {
    for (double noise_deg : {0.05, 0.3, 1.0}) {
      // The middle 60% of the sweep, so that noisy outputs do not ask for inputs past a limit.
      VectorXd psi, phi;
      test::exact_pairs(known.bar, 1, 21, psi, phi, 0.6);
      for (Index i = 0; i < phi.size(); ++i) phi(i) += noise_deg * kDeg * g.normal();
      const SynthesisResult r = synthesize(psi, phi, kNoWeights);
      ASSERT_TRUE(r.ok()) << known.name << " " << noise_deg << ": " << r.message;
      EXPECT_GT(r.design.structural_error_rms, 1e-6);
      EXPECT_LT(r.structural.structural_error_rms, r.design.structural_error_rms)
          << known.name << " " << noise_deg;
      EXPECT_GE(r.structural.iterations, 1);
      const VectorXd s = phi - r.structural.phi_generated;
      const MatrixXd J = structural_jacobian(r.structural.k, psi, r.structural.phi_generated);
      EXPECT_LT((J.transpose() * s).norm(), 1e-8 * J.norm() * s.norm()) << known.name << " " << noise_deg;
      ++cases;
    }
  }
  EXPECT_EQ(cases, 15);
}

TEST(Synthesis, GaussNewtonLowersTheStructuralErrorOfPrescribedFunctions) {
  std::vector<PrescribedPairs> problems = {
      steering_pairs(0.5, -30 * kDeg, 30 * kDeg, 21, Spacing::Uniform),
      steering_pairs(0.5, -30 * kDeg, 30 * kDeg, 21, Spacing::Chebyshev),
      function_pairs("log10", 1.0, 10.0, 0.0, 60 * kDeg, 0.0, 60 * kDeg, 15, Spacing::Chebyshev),
      function_pairs("exp", 0.0, 1.0, 0.0, 90 * kDeg, 0.0, 90 * kDeg, 15, Spacing::Uniform),
  };
  // Dial zeros near those --fit-dial-zeros finds, so that the design linkages are real.
  std::vector<DialZeros> zeros = {trapezoid_dial_zeros(0.5),
                                  trapezoid_dial_zeros(0.5),
                                  {35 * kDeg, 105 * kDeg},
                                  {-120 * kDeg, -140 * kDeg}};
  for (std::size_t p = 0; p < problems.size(); ++p) {
    SynthesisOptions options;
    options.alpha = zeros[p].alpha;
    options.beta = zeros[p].beta;
    const SynthesisResult r = synthesize(problems[p].delta_psi, problems[p].delta_phi, kNoWeights, options);
    ASSERT_TRUE(r.ok()) << p << ": " << r.message;
    EXPECT_LT(r.structural.structural_error_rms, r.design.structural_error_rms) << p;
    EXPECT_LE(r.structural.structural_error_max, r.design.structural_error_max * 1.5) << p;
  }
}

// The worked example of docs/linkage.md: rho = 0.5, 21 uniform positions over -30..30 degrees,
// the trapezoid dial zeros. The numbers were also checked by an independent NumPy computation
// (tests/linkage/test_synthesize.py).
TEST(Synthesis, SteeringWorkedExample) {
  const PrescribedPairs p = steering_pairs(0.5, -30 * kDeg, 30 * kDeg, 21, Spacing::Uniform);
  SynthesisOptions options;
  const DialZeros zeros = trapezoid_dial_zeros(0.5);
  EXPECT_NEAR(zeros.alpha / kDeg, 75.963756532, 1e-8);
  EXPECT_NEAR(zeros.beta / kDeg, 104.036243468, 1e-8);
  options.alpha = zeros.alpha;
  options.beta = zeros.beta;
  const SynthesisResult r = synthesize(p.delta_psi, p.delta_phi, kNoWeights, options);
  ASSERT_TRUE(r.ok()) << r.message;
  EXPECT_LT((r.design.k - Eigen::Vector3d(1.69259278, 1.66655770, 1.65662059)).norm(), 1e-7);
  EXPECT_LT((r.structural.k - Eigen::Vector3d(1.96307066, 2.20197577, 2.19606530)).norm(), 1e-7);
  EXPECT_NEAR(r.design.structural_error_rms / kDeg, 0.7313, 1e-4);
  EXPECT_NEAR(r.structural.structural_error_rms / kDeg, 0.3900, 1e-4);
  EXPECT_EQ(r.structural.check->grashof, GrashofType::TripleRocker);
  EXPECT_FALSE(r.structural.check->branch_defect);
}

TEST(Synthesis, ThreePairsArePrecisionPoints) {
  const PrescribedPairs p =
      function_pairs("log10", 1.0, 10.0, 0.0, 60 * kDeg, 0.0, 60 * kDeg, 3, Spacing::Chebyshev);
  SynthesisOptions options;
  options.alpha = 35 * kDeg;
  options.beta = 105 * kDeg;
  const SynthesisResult r = synthesize(p.delta_psi, p.delta_phi, kNoWeights, options);
  ASSERT_TRUE(r.ok()) << r.message;
  EXPECT_TRUE(r.precision_point);
  EXPECT_LT(r.design.design_error_norm, 1e-14);
  EXPECT_LT(r.structural.structural_error_max, kExact);
  EXPECT_EQ(r.structural.iterations, 0);
  EXPECT_EQ(r.structural.k, r.design.k);
}

TEST(Synthesis, ThreePairsOnDifferentBranchesAreABranchDefect) {
  const FourBar bar{1.0, 0.4, 1.1, 0.9};
  const Eigen::Vector3d k = freudenstein_parameters(bar);
  VectorXd psi(3), phi(3);
  psi << 20 * kDeg, 80 * kDeg, 140 * kDeg;
  phi << *output_angle(k, psi(0), 1), *output_angle(k, psi(1), -1), *output_angle(k, psi(2), 1);
  const SynthesisResult r = synthesize(psi, phi, kNoWeights);
  ASSERT_TRUE(r.ok()) << r.message;
  // The Freudenstein equation does not see branches: k is recovered exactly ...
  EXPECT_LT((r.design.k - k).norm(), kExact);
  // ... but the linkage cannot reach all three positions on one branch.
  ASSERT_TRUE(r.structural.check);
  EXPECT_TRUE(r.structural.check->branch_defect);
  EXPECT_GT(r.structural.structural_error_max, 1 * kDeg);
  EXPECT_FALSE(r.warnings.empty());
}

// Pairs from a known linkage measured from unknown dial zeros: the fit finds them (eq. 3.7).
TEST(Synthesis, FitsKnownDialZeros) {
  struct Case {
    FourBar bar;
    double alpha_deg, beta_deg;
    int m;
  };
  for (const Case& c :
       {Case{{1.0, 0.4, 1.1, 0.9}, 35.0, 110.0, 12}, Case{{1.0, 0.4, 1.1, 0.9}, -70.0, 20.0, 5},
        Case{{1.0, 2.0, 2.2, 1.8}, 10.0, -40.0, 9}}) {
    const Eigen::Vector3d k = freudenstein_parameters(c.bar);
    const double alpha = c.alpha_deg * kDeg, beta = c.beta_deg * kDeg;
    VectorXd dpsi = VectorXd::LinSpaced(c.m, 0.0, 100 * kDeg), dphi(c.m);
    for (int i = 0; i < c.m; ++i) dphi(i) = wrap_angle(*output_angle(k, alpha + dpsi(i), 1) - beta);
    SynthesisOptions options;
    options.fit_dial_zeros = true;
    const SynthesisResult r = synthesize(dpsi, dphi, kNoWeights, options);
    ASSERT_TRUE(r.ok()) << r.message;
    EXPECT_EQ(r.precision_point, c.m == 5);
    EXPECT_NEAR(wrap_angle(r.structural.dial_zeros.alpha - alpha), 0.0, 1e-8) << c.alpha_deg;
    EXPECT_NEAR(wrap_angle(r.structural.dial_zeros.beta - beta), 0.0, 1e-8) << c.beta_deg;
    EXPECT_LT((r.structural.k - k).norm(), 1e-8);
    EXPECT_LT(r.structural.structural_error_max, 1e-8);
  }
}

TEST(Synthesis, NoRealLinkageIsAStatus) {
  // Output angles turned by 180 degrees: k3 changes sign, a negative output link.
  const FourBar bar{1.0, 0.4, 1.1, 0.9};
  VectorXd psi, phi;
  test::exact_pairs(bar, 1, 9, psi, phi);
  phi.array() += kPi;
  const SynthesisResult r = synthesize(psi, phi, kNoWeights);
  EXPECT_EQ(r.status, SynthesisStatus::NoRealLinkage);
  EXPECT_NE(r.message.find("negative output link a4"), std::string::npos) << r.message;
  EXPECT_FALSE(r.design.lengths);
}

TEST(Synthesis, UnreachableInputsAreAStatus) {
  const PrescribedPairs p = steering_pairs(0.5, -40 * kDeg, 40 * kDeg, 21, Spacing::Uniform);
  SynthesisOptions options;
  options.alpha = trapezoid_dial_zeros(0.5).alpha;
  options.beta = trapezoid_dial_zeros(0.5).beta;
  const SynthesisResult r = synthesize(p.delta_psi, p.delta_phi, kNoWeights, options);
  EXPECT_EQ(r.status, SynthesisStatus::NotAssemblable);
  EXPECT_NE(r.message.find("cannot be assembled"), std::string::npos) << r.message;
}

TEST(Synthesis, IterationLimitIsAClearError) {
  const PrescribedPairs p = steering_pairs(0.5, -30 * kDeg, 30 * kDeg, 21, Spacing::Uniform);
  SynthesisOptions options;
  options.alpha = trapezoid_dial_zeros(0.5).alpha;
  options.beta = trapezoid_dial_zeros(0.5).beta;
  options.gauss_newton.max_iterations = 2;
  const SynthesisResult r = synthesize(p.delta_psi, p.delta_phi, kNoWeights, options);
  EXPECT_EQ(r.status, SynthesisStatus::Diverged);
  EXPECT_NE(r.message.find("did not converge in 2 iterations"), std::string::npos) << r.message;
  EXPECT_TRUE(r.design.lengths);  // the design solution is still there
}

TEST(Synthesis, BadInputThrows) {
  VectorXd two = VectorXd::LinSpaced(2, 0.0, 1.0);
  EXPECT_THROW(synthesize(two, two, kNoWeights), std::invalid_argument);
  VectorXd psi = VectorXd::LinSpaced(4, 0.0, 1.0), phi = psi;
  SynthesisOptions dial;
  dial.fit_dial_zeros = true;
  EXPECT_THROW(synthesize(psi, phi, kNoWeights, dial), std::invalid_argument);  // 5 needed
  EXPECT_THROW(synthesize(psi, VectorXd::LinSpaced(5, 0.0, 1.0), kNoWeights), std::invalid_argument);
  phi(2) = std::nan("");
  EXPECT_THROW(synthesize(psi, phi, kNoWeights), std::invalid_argument);
  phi(2) = 0.5;
  EXPECT_THROW(synthesize(psi, phi, VectorXd::Ones(3)), std::invalid_argument);
  VectorXd w = VectorXd::Ones(4);
  w(1) = -1.0;
  EXPECT_THROW(synthesize(psi, phi, w), std::invalid_argument);
  SynthesisOptions bad;
  bad.gauss_newton.tolerance = 0.0;
  EXPECT_THROW(synthesize(psi, phi, kNoWeights, bad), std::invalid_argument);
}

TEST(PrescribedFunction, SteeringPairsSatisfyTheSteeringCondition) {
  const PrescribedPairs p = steering_pairs(0.5, -40 * kDeg, 40 * kDeg, 17, Spacing::Chebyshev);
  for (Index i = 0; i < p.delta_psi.size(); ++i) {
    EXPECT_NEAR(steering_condition(p.delta_psi(i), p.delta_phi(i), 0.5), 0.0, 4 * kEps);
  }
  EXPECT_NEAR(steering_output(0.0, 0.5), 0.0, 0.0);
  // cot(dpsi) - cot(dphi) = rho (Ackermann).
  const double dpsi = 20 * kDeg, dphi = steering_output(dpsi, 0.5);
  EXPECT_NEAR(1 / std::tan(dpsi) - 1 / std::tan(dphi), 0.5, 1e-14);
}

TEST(PrescribedFunction, SpacingAndMapping) {
  const VectorXd u = spaced_points(-1.0, 1.0, 5, Spacing::Uniform);
  EXPECT_EQ(u(0), -1.0);
  EXPECT_EQ(u(4), 1.0);
  EXPECT_NEAR(u(2), 0.0, kEps);
  const VectorXd c = spaced_points(0.0, 2.0, 3, Spacing::Chebyshev);
  EXPECT_NEAR(c(0), 1.0 - std::cos(kPi / 6), 1e-15);
  EXPECT_NEAR(c(1), 1.0, 1e-15);
  EXPECT_NEAR(c(2), 1.0 + std::cos(kPi / 6), 1e-15);
  const PrescribedPairs p =
      function_pairs("log10", 1.0, 10.0, 0.0, 90 * kDeg, 10 * kDeg, 70 * kDeg, 4, Spacing::Uniform);
  EXPECT_NEAR(p.delta_psi(0), 0.0, 1e-15);
  EXPECT_NEAR(p.delta_psi(3), 90 * kDeg, 1e-15);
  EXPECT_NEAR(p.delta_phi(0), 10 * kDeg, 1e-15);
  EXPECT_NEAR(p.delta_phi(3), 70 * kDeg, 1e-15);
  EXPECT_NEAR(p.delta_phi(1), 10 * kDeg + std::log10(4.0) * 60 * kDeg, 1e-15);
  EXPECT_THROW(function_pairs("nope", 1, 2, 0, 1, 0, 1, 4, Spacing::Uniform), std::invalid_argument);
  EXPECT_THROW(function_pairs("log10", -1, 2, 0, 1, 0, 1, 4, Spacing::Uniform), std::invalid_argument);
  EXPECT_THROW(function_pairs("cos", -1, 1, 0, 1, 0, 1, 4, Spacing::Uniform),
               std::invalid_argument);  // f(lo) == f(hi)
  EXPECT_THROW(spaced_points(1.0, 1.0, 3, Spacing::Uniform), std::invalid_argument);
}

// Regression (fuzz/regressions/linkage_pairs/crash-ff05885...): garbled pairs on which the error
// keeps falling as k runs off to infinity. Gauss-Newton took the huge steps as "rounding-level"
// tail steps and returned ||k|| ~ 1e137 as a success; now it is a divergence, with a message.
TEST(Synthesis, ParametersRunningOffToInfinityAreADivergence) {
  const PrescribedPairs pairs = parse_pairs(R"(# the crank-rocker's o
37.5,76.079
50,76.875
62.5,80.606
7,113.219
150,118.013
162.5,122.777
175,926.318
25,107.702
137.5,113.219
# the crank-rocker's o
37.5,76.079
50,76.875
62.5,80.606
7,113.219
150,118.013
162.5,122.777
175,926.318
25,107.702
137.5,113.219
150,118.013
162.5,122.777
175,926.318
187.5,130.944
200,132.507
212.5,135.570
21,5236.435
237.5,8
187.5,130.944
200,132.508
212.5,135.570
21,5236.435
237.5,136.872
1250150,118.013
162.5,122.777
175,926.318
187.5,130.944
200,135236.435
237.5,8
187.5,130.944
200,132.508
212.5,135.570
21,5236.435
237.5,136.872
12506,6.758
262.5,135.732
275,135.096
287.5,130.926
300,127.121
)",
                                            "crash.csv");
  const SynthesisResult r = synthesize(pairs.delta_psi, pairs.delta_phi, VectorXd());
  EXPECT_EQ(r.status, SynthesisStatus::Diverged) << r.structural.k.transpose();
  EXPECT_NE(r.message.find("ran off"), std::string::npos) << r.message;
}

}  // namespace
}  // namespace spdfit::linkage
