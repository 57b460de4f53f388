// Physical identification of a hexapod's payload (hexapod/physical.hpp): the model against a
// point-mass body's kinetic energy, the derivatives against finite differences, identifiability,
// exact recovery from noise-free data, the KKT conditions, consistency near the triangle
// inequality's boundary, and the errors.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "hexapod/physical_model.hpp"
#include "hexapod/physical_solver.hpp"
#include "hexapod_support.hpp"
#include "spdfit/hexapod/model.hpp"
#include "spdfit/hexapod/physical.hpp"
#include "spdfit/hexapod/simulate.hpp"
#include "spdfit/random.hpp"
#include "test_support.hpp"

namespace spdfit {
namespace {

using hexapod::Geometry;
using hexapod::Matrix6d;
using hexapod::PhysicalOptions;
using hexapod::StrutMasses;
using hexapod::Vector6d;
using test::Generator;

// Noise-free data are fitted to rounding: the parameters come back to this relative accuracy
// (the goal is 1e-9; rounding in the solves with J and the 36 x p least squares is ~1e-13).
constexpr double kRecoveryTolerance = 1e-9;

// A rigid body made of point masses, and its mass properties computed directly.
struct PointMasses {
  std::vector<double> m;
  std::vector<Eigen::Vector3d> r;  // in {P}
};

PointMasses random_points(Generator& g, int count) {
  PointMasses body;
  for (int k = 0; k < count; ++k) {
    body.m.push_back(g.uniform(0.1, 2.0));
    body.r.emplace_back(g.uniform(-0.1, 0.15), g.uniform(-0.12, 0.1), g.uniform(-0.05, 0.08));
  }
  return body;
}

RigidBodyInertia mass_properties(const PointMasses& body) {
  RigidBodyInertia out;
  for (std::size_t k = 0; k < body.m.size(); ++k) {
    out.mass += body.m[k];
    out.center_of_mass += body.m[k] * body.r[k];
  }
  out.center_of_mass /= out.mass;
  for (std::size_t k = 0; k < body.m.size(); ++k) {
    const Eigen::Vector3d d = body.r[k] - out.center_of_mass;
    out.inertia += body.m[k] * (d.squaredNorm() * Eigen::Matrix3d::Identity() - d * d.transpose());
  }
  return out;
}

// A payload with its centre of mass off {P}'s origin and an inertia unlike the nominal one.
RigidBodyInertia offset_payload(const Geometry& geometry) {
  RigidBodyInertia p;
  p.mass = 1.3 * geometry.payload_mass;
  p.center_of_mass = Eigen::Vector3d(0.012, -0.007, 0.021);
  Eigen::Matrix3d I;
  I << 0.13, 0.004, -0.002, 0.004, 0.09, 0.006, -0.002, 0.006, 0.11;
  p.inertia = I;
  return p;
}

// Noise-free data B = A M_p with a well-conditioned A.
void noise_free(Generator& g, const Matrix6d& Mp, Eigen::Index m, Eigen::MatrixXd& A, Eigen::MatrixXd& B) {
  A = g.gaussian(m, 6) * 3.0;
  B = A * Mp;
}

double relative(double x, double y) { return std::abs(x - y) / std::abs(y); }

TEST(HexapodPhysical, PayloadMassMatrixIsTheKineticEnergyOfThePointMasses) {
  // (1/2) x_dot^T ^B M_x x_dot = sum_k (1/2) m_k |v + w x R r_k|^2 for the twist [v; w] of {P}'s
  // origin: the centre-of-mass offset's cross terms and the parallel-axis term included.
  Generator g(3401);
  for (int repeat = 0; repeat < 5; ++repeat) {
    const Geometry geometry = test::random_geometry(g);
    const PointMasses body = random_points(g, 7);
    const Matrix6d Mx = hexapod::payload_mass_matrix(geometry, mass_properties(body));
    for (int t = 0; t < 5; ++t) {
      const Vector6d x_dot = Vector6d(g.gaussian(6, 1));
      double expected = 0.0;
      for (std::size_t k = 0; k < body.m.size(); ++k) {
        const Eigen::Vector3d velocity =
            x_dot.head<3>() + x_dot.tail<3>().cross(geometry.payload_rotation * body.r[k]);
        expected += 0.5 * body.m[k] * velocity.squaredNorm();
      }
      EXPECT_NEAR(0.5 * x_dot.dot(Mx * x_dot), expected, 1e-13 * expected);
    }
  }
}

TEST(HexapodPhysical, OffsetPayloadWithZeroOffsetIsTheNominalModel) {
  const Geometry geometry = hexapod::cubic_geometry();
  EXPECT_LT((hexapod::joint_space_mass_matrix(geometry, hexapod::nominal_payload(geometry)) -
             hexapod::joint_space_mass_matrix(geometry))
                .norm(),
            1e-13 * hexapod::joint_space_mass_matrix(geometry).norm());
}

TEST(HexapodPhysical, LinearModelReproducesTheMassMatrix) {
  Generator g(3402);
  for (StrutMasses struts : {StrutMasses::Geometry, StrutMasses::Common, StrutMasses::Each}) {
    const Geometry geometry = test::random_geometry(g);
    const hexapod::detail::PhysicalModel model = hexapod::detail::physical_model(geometry, struts);
    const RigidBodyInertia payload = mass_properties(random_points(g, 5));
    Geometry with_struts = geometry;
    Eigen::VectorXd s;
    if (struts == StrutMasses::Common) {
      s = Eigen::VectorXd::Constant(1, 0.4);
      with_struts.strut_mass.setConstant(0.4);
    } else if (struts == StrutMasses::Each) {
      s = Eigen::VectorXd(g.gaussian(6, 1)).cwiseAbs();
      with_struts.strut_mass = s;
    }
    const auto theta = hexapod::detail::parameters_of(model, payload, s);
    const Matrix6d expected = hexapod::joint_space_mass_matrix(with_struts, payload);
    EXPECT_LT((hexapod::detail::model_mass_matrix(model, theta) - expected).norm(), 1e-12 * expected.norm());
    // And back.
    const RigidBodyInertia back = hexapod::detail::payload_of(model, theta);
    EXPECT_NEAR(back.mass, payload.mass, 1e-14 * payload.mass);
    EXPECT_LT((back.center_of_mass - payload.center_of_mass).norm(), 1e-13 * payload.center_of_mass.norm());
    EXPECT_LT((back.inertia - payload.inertia).norm(), 1e-12 * payload.inertia.norm());
  }
}

TEST(HexapodPhysical, GradientAndHessianAreTheDerivativesOfTheCriterion) {
  Generator g(3403);
  const Geometry geometry = test::random_geometry(g);
  for (auto criterion : {hexapod::PhysicalCriterion::ErrorsInVariables, hexapod::PhysicalCriterion::LeastSquares}) {
    const auto model = hexapod::detail::physical_model(geometry, StrutMasses::Each);
    Eigen::MatrixXd A, B;
    noise_free(g, hexapod::joint_space_mass_matrix(geometry), 40, A, B);
    A += 0.3 * g.gaussian(40, 6);
    B += 0.3 * g.gaussian(40, 6);
    Eigen::MatrixXd Sa = g.spd(6, 5.0), Sb = g.spd(6, 3.0);
    auto data = hexapod::detail::physical_data(TriangularFactor::from_data(A, B), model, criterion, Sa, Sb);
    const auto theta = hexapod::detail::parameters_of(model, offset_payload(geometry),
                                                      Eigen::VectorXd::Constant(6, 0.3));
    const auto theta_s = (theta * data.theta_scale).eval();
    ASSERT_TRUE(hexapod::detail::set_normalization(data, model, theta_s));
    hexapod::detail::Evaluation ev, plus, minus;
    ASSERT_TRUE(hexapod::detail::evaluate(data, model, theta_s, 2, ev));
    // Central differences: truncation ~h^2 f''', rounding ~eps f / h; h = 1e-5 relative.
    const double h = 1e-5 * theta_s.norm();
    for (int a = 0; a < model.parameters; ++a) {
      auto tp = theta_s, tm = theta_s;
      tp(a) += h;
      tm(a) -= h;
      ASSERT_TRUE(hexapod::detail::evaluate(data, model, tp, 1, plus));
      ASSERT_TRUE(hexapod::detail::evaluate(data, model, tm, 1, minus));
      EXPECT_NEAR((plus.f - minus.f) / (2 * h), ev.g(a), 1e-6 * ev.g.norm()) << "gradient " << a;
      const auto column = ((plus.g - minus.g) / (2 * h)).eval();
      EXPECT_LT((column - ev.H.col(a)).norm(), 1e-6 * ev.H.norm()) << "Hessian column " << a;
    }
  }
}

TEST(HexapodPhysical, CubicHexapodConfoundsACommonStrutMass) {
  const Geometry geometry = hexapod::cubic_geometry();
  const hexapod::PhysicalDesign fixed = hexapod::physical_design(geometry, StrutMasses::Geometry);
  EXPECT_EQ(fixed.parameters, 10);
  EXPECT_EQ(fixed.rank, 10);
  EXPECT_TRUE(std::isfinite(fixed.condition));
  EXPECT_TRUE(fixed.confounded.empty());
  const hexapod::PhysicalDesign common = hexapod::physical_design(geometry, StrutMasses::Common);
  EXPECT_EQ(common.parameters, 11);
  EXPECT_EQ(common.rank, 10);  // J^T J = diag(2 I, ...) is itself a rigid body's mass matrix
  EXPECT_FALSE(std::isfinite(common.condition));
  EXPECT_NE(common.confounded.find("adding 1 kg to every strut's moving mass"), std::string::npos)
      << common.confounded;
  EXPECT_NE(common.confounded.find("mass 2 kg"), std::string::npos) << common.confounded;

  // Identification refuses it, naming the combination.
  Generator g(3404);
  Eigen::MatrixXd A, B;
  noise_free(g, hexapod::joint_space_mass_matrix(geometry), 30, A, B);
  PhysicalOptions options;
  options.strut_masses = StrutMasses::Common;
  try {
    hexapod::identify_physical(A, B, geometry, options);
    FAIL() << "a confounded strut mass was estimated";
  } catch (const std::invalid_argument& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("`strut_masses` = common cannot be estimated on this geometry"), std::string::npos)
        << message;
    EXPECT_NE(message.find("rank 10"), std::string::npos) << message;
  }
}

TEST(HexapodPhysical, AsymmetricHexapodIdentifiesEachStrutMass) {
  Generator g(3405);
  const Geometry geometry = test::random_geometry(g);
  for (StrutMasses struts : {StrutMasses::Geometry, StrutMasses::Common, StrutMasses::Each}) {
    const hexapod::PhysicalDesign design = hexapod::physical_design(geometry, struts);
    EXPECT_EQ(design.rank, design.parameters) << to_string(struts) << ": " << design.confounded;
    EXPECT_TRUE(std::isfinite(design.condition));
  }
}

TEST(HexapodPhysical, RecoversEveryParameterFromNoiseFreeData) {
  Generator g(3406);
  struct Case {
    Geometry geometry;
    StrutMasses struts;
  };
  Geometry common = test::random_geometry(g);
  common.strut_mass.setConstant(0.45);  // one mass the model with a common strut mass can hold
  const Case cases[] = {{hexapod::cubic_geometry(), StrutMasses::Geometry},
                        {test::random_geometry(g), StrutMasses::Each},
                        {common, StrutMasses::Common}};
  for (const Case& c : cases) {
    const RigidBodyInertia truth = offset_payload(c.geometry);
    const Matrix6d Mp = hexapod::joint_space_mass_matrix(c.geometry, truth);
    Eigen::MatrixXd A, B;
    noise_free(g, Mp, 60, A, B);
    for (auto criterion : {hexapod::PhysicalCriterion::ErrorsInVariables, hexapod::PhysicalCriterion::LeastSquares}) {
      PhysicalOptions options;
      options.strut_masses = c.struts;
      options.criterion = criterion;
      const hexapod::PhysicalEstimate e = hexapod::identify_physical(A, B, c.geometry, options);
      const std::string what = std::string(to_string(c.struts)) + " " + std::string(to_string(criterion));
      ASSERT_TRUE(e.ok()) << e.message;
      EXPECT_TRUE(e.converged) << what;
      EXPECT_TRUE(e.physically_consistent) << what;
      EXPECT_LT(relative(e.payload.mass, truth.mass), kRecoveryTolerance) << what;
      for (int i = 0; i < 3; ++i) {
        EXPECT_LT(relative(e.payload.center_of_mass(i), truth.center_of_mass(i)), kRecoveryTolerance) << what;
        for (int j = 0; j < 3; ++j) {
          EXPECT_LT(std::abs(e.payload.inertia(i, j) - truth.inertia(i, j)), kRecoveryTolerance * truth.inertia.norm())
              << what;
        }
      }
      EXPECT_LT((e.strut_mass - c.geometry.strut_mass.head(e.strut_mass.size())).norm(),
                kRecoveryTolerance * c.geometry.strut_mass.norm())
          << what;
      EXPECT_LT((e.M_p - Mp).norm(), kRecoveryTolerance * Mp.norm()) << what;
    }
  }
}

TEST(HexapodPhysical, EstimateSatisfiesTheKktConditions) {
  // Noisy data on the thesis' set-up: the certificate's numbers are at rounding level.
  const Geometry geometry = hexapod::cubic_geometry();
  hexapod::SimulationOptions simulation;
  simulation.samples = 200;
  simulation.noise_var = 3.2 * 3.2 / 12.0;
  for (std::uint64_t seed = 1; seed <= 5; ++seed) {
    const hexapod::Measurements data =
        hexapod::simulate(geometry, offset_payload(geometry), simulation, seed);
    const hexapod::PhysicalEstimate e = hexapod::identify_physical(data.A, data.B, geometry);
    ASSERT_TRUE(e.ok()) << e.message;
    EXPECT_TRUE(e.converged);
    EXPECT_GE(e.certificate.primal_min_eig, 0.0);
    EXPECT_GE(e.certificate.dual_min_eig, -1e-10);
    EXPECT_LT(e.certificate.stationarity, 1e-9);
    EXPECT_LT(std::abs(e.certificate.complementarity), 1e-10);
    EXPECT_LT(e.start_certificate.duality_gap, 1e-10);
  }
}

TEST(HexapodPhysical, StaysConsistentWhereTheUnconstrainedFitDoesNot) {
  // A thin rod along x: principal moments (tiny, I, I) nearly meet the triangle inequality
  // (the second moments across the rod are 1e-4 of the one along it).
  const Geometry geometry = hexapod::cubic_geometry();
  RigidBodyInertia rod;
  rod.mass = geometry.payload_mass;
  const double length = 0.45, thickness = 0.0045;
  const double along = rod.mass * length * length / 12.0, across = rod.mass * thickness * thickness / 12.0;
  rod.inertia = Eigen::Vector3d(2 * across, along + across, along + across).asDiagonal();
  hexapod::SimulationOptions simulation;
  simulation.samples = 100;
  simulation.noise_var = 3.2 * 3.2 / 12.0;
  int unconstrained_inconsistent = 0;
  for (std::uint64_t seed = 1; seed <= 20; ++seed) {
    const hexapod::Measurements data = hexapod::simulate(geometry, rod, simulation, seed);
    PhysicalOptions options;
    const hexapod::PhysicalEstimate physical = hexapod::identify_physical(data.A, data.B, geometry, options);
    ASSERT_TRUE(physical.ok()) << physical.message;
    EXPECT_TRUE(physical.physically_consistent) << "seed " << seed;
    // On the boundary to rounding: P's eigenvalues are ~10 kg, rounding ~1e-15 of that.
    EXPECT_GE(physical.pseudo_inertia_min_eig, -1e-13);
    // Every principal moment at most the sum of the other two (to rounding).
    const Eigen::Vector3d I = physical.principal.moments;
    EXPECT_LE(I(2), I(0) + I(1) + 64 * test::kEps * I(2)) << "seed " << seed;
    options.consistent = false;
    const hexapod::PhysicalEstimate grey = hexapod::identify_physical(data.A, data.B, geometry, options);
    ASSERT_TRUE(grey.ok());
    if (!grey.physically_consistent) ++unconstrained_inconsistent;
  }
  EXPECT_GT(unconstrained_inconsistent, 0);
}

TEST(HexapodPhysical, RefusesDataThatCannotIdentifyTheParameters) {
  Generator g(3407);
  const Geometry geometry = hexapod::cubic_geometry();
  Eigen::MatrixXd A, B;
  noise_free(g, hexapod::joint_space_mass_matrix(geometry), 2, A, B);
  try {
    hexapod::identify_physical(A, B, geometry);
    FAIL() << "two rows identified ten parameters";
  } catch (const std::invalid_argument& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("the data cannot identify the payload's"), std::string::npos) << message;
    EXPECT_NE(message.find("A has rank 2 of 6 (m = 2 rows)"), std::string::npos) << message;
  }
}

TEST(HexapodPhysical, RefusesBadInput) {
  const Geometry geometry = hexapod::cubic_geometry();
  Eigen::MatrixXd A = Eigen::MatrixXd::Random(20, 6), B = Eigen::MatrixXd::Random(20, 5);
  EXPECT_THROW(hexapod::identify_physical(A, B, geometry), std::invalid_argument);
  B = Eigen::MatrixXd::Random(20, 6);
  Geometry bad = geometry;
  bad.payload_points.col(1) = bad.payload_points.col(0);
  bad.base_points.col(1) = bad.base_points.col(0);
  EXPECT_THROW(hexapod::identify_physical(A, B, bad), std::invalid_argument);
  PhysicalOptions options;
  options.noise_cov_a = -Eigen::MatrixXd::Identity(6, 6);
  try {
    hexapod::identify_physical(A, B, geometry, options);
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("`noise_cov_a` must be positive semidefinite"), std::string::npos);
  }
  options = {};
  options.bootstrap = 3;
  EXPECT_THROW(hexapod::identify_physical(TriangularFactor::from_data(A, B), geometry, options),
               std::invalid_argument);
}

TEST(HexapodPhysical, BootstrapGivesIntervalsThatHoldTheEstimate) {
  const Geometry geometry = hexapod::cubic_geometry();
  hexapod::SimulationOptions simulation;
  simulation.samples = 300;
  simulation.noise_var = 0.86;
  const hexapod::Measurements data = hexapod::simulate(geometry, offset_payload(geometry), simulation, 7);
  PhysicalOptions options;
  options.bootstrap = 50;
  options.threads = 2;
  const hexapod::PhysicalEstimate e = hexapod::identify_physical(data.A, data.B, geometry, options);
  ASSERT_TRUE(e.ok());
  ASSERT_TRUE(e.bootstrap.has_value());
  const hexapod::PhysicalBootstrap& b = *e.bootstrap;
  EXPECT_EQ(b.failed, 0);
  EXPECT_GT(b.mass.standard_errors(0, 0), 0.0);
  EXPECT_LE(b.mass.lower(0, 0), b.mass.upper(0, 0));
  EXPECT_EQ(b.M_p.standard_errors.rows(), 6);
  EXPECT_EQ(b.M_p_eigenvalues.estimate.size(), 6);
  ASSERT_TRUE(b.modes_hz.has_value());
  EXPECT_EQ(b.strut_mass.standard_errors(0, 0), 0.0);  // from the geometry: not estimated
  // The same numbers on one thread: replicates are keyed by (seed, r).
  options.threads = 1;
  const hexapod::PhysicalEstimate one = hexapod::identify_physical(data.A, data.B, geometry, options);
  EXPECT_EQ(one.bootstrap->mass.standard_errors, b.mass.standard_errors);
  EXPECT_EQ(one.bootstrap->M_p.upper, b.M_p.upper);
}

}  // namespace
}  // namespace spdfit
