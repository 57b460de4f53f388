// The physical results read back from their JSON (render/physical_from_json.cpp): for results
// with every optional part (bootstraps, undetermined combinations, a null inertia, offsets, a
// failure), to_json(from_json(text)) is text byte for byte, so every key written is read; and a
// document of another kind is refused naming the class and the key.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <stdexcept>
#include <string>

#include "spdfit/experiment/physical.hpp"
#include "spdfit/hexapod/physical.hpp"
#include "spdfit/hexapod/render.hpp"
#include "spdfit/hexapod/simulate.hpp"
#include "spdfit/inertia_repair.hpp"
#include "spdfit/payload/design.hpp"
#include "spdfit/payload/identify.hpp"
#include "spdfit/physical/regress.hpp"

namespace spdfit {
namespace {

Eigen::Vector3d cross(const Eigen::Vector3d& a, const Eigen::Vector3d& b) { return a.cross(b); }

// Static (gravity alone) or moving poses of a 1.3 kg payload: the sensor's readings (the load on
// it, plus a bias and noise) and the signals.
payload::PayloadSignals payload_signals(bool moving, int samples, std::uint64_t seed) {
  std::mt19937_64 random(seed);
  std::normal_distribution<double> normal;
  const double m = 1.3;
  const Eigen::Vector3d c(0.02, -0.01, 0.06);
  Eigen::Matrix3d I_c;
  I_c << 0.004, 0.0002, 0.0, 0.0002, 0.005, 0.0001, 0.0, 0.0001, 0.003;
  const Eigen::Matrix3d I_S = I_c + m * (c.squaredNorm() * Eigen::Matrix3d::Identity() - c * c.transpose());
  payload::PayloadSignals s;
  s.wrench.resize(samples, 6);
  s.gravity.resize(samples, 3);
  if (moving) {
    s.accel.resize(samples, 3);
    s.omega.resize(samples, 3);
    s.alpha.resize(samples, 3);
  }
  for (int i = 0; i < samples; ++i) {
    Eigen::Vector3d g(normal(random), normal(random), normal(random));
    g *= 9.80665 / g.norm();
    Eigen::Vector3d a = Eigen::Vector3d::Zero(), w = Eigen::Vector3d::Zero(), al = Eigen::Vector3d::Zero();
    if (moving) {
      for (int k = 0; k < 3; ++k) {
        a(k) = 2.0 * normal(random);
        w(k) = normal(random);
        al(k) = 5.0 * normal(random);
      }
      s.accel.row(i) = a.transpose();
      s.omega.row(i) = w.transpose();
      s.alpha.row(i) = al.transpose();
    }
    const Eigen::Vector3d sf = a - g;  // the specific force
    const Eigen::Vector3d f = m * sf + cross(al, m * c) + cross(w, cross(w, m * c));
    const Eigen::Vector3d t = I_S * al + cross(w, I_S * w) + cross(m * c, sf);
    s.gravity.row(i) = g.transpose();
    for (int k = 0; k < 3; ++k) {
      s.wrench(i, k) = -f(k) + 0.2 + 1e-3 * normal(random);
      s.wrench(i, 3 + k) = -t(k) - 0.01 + 1e-4 * normal(random);
    }
  }
  return s;
}

TEST(PhysicalFromJson, PayloadEstimatesRoundTrip) {
  for (const bool moving : {false, true}) {
    for (const int bootstrap : {0, 25}) {
      payload::IdentifyRequest request;
      request.bootstrap = bootstrap;
      request.threads = 1;
      const payload::PayloadEstimate e = payload::identify(payload_signals(moving, 40, 3), request);
      ASSERT_TRUE(e.ok()) << e.message;
      const std::string text = payload::to_json(e);
      const auto back = from_json<payload::PayloadEstimate>(text);
      EXPECT_EQ(payload::to_json(back), text) << "moving " << moving << ", bootstrap " << bootstrap;
      EXPECT_EQ(back.mass, e.mass);
      EXPECT_EQ(back.moving, moving);
    }
  }
  // Two gravity directions leave a combination undetermined: it is named, and read back.
  payload::PayloadSignals two = payload_signals(false, 20, 5);
  for (Eigen::Index i = 0; i < two.gravity.rows(); ++i) {
    const Eigen::Vector3d g = i % 2 ? Eigen::Vector3d(0, 0, -9.80665) : Eigen::Vector3d(0, -9.80665, 0);
    two.gravity.row(i) = g.transpose();
    two.wrench.row(i).head<3>() = (1.3 * g).transpose();
    two.wrench.row(i).tail<3>() = (cross(Eigen::Vector3d(0.02, -0.01, 0.06) * 1.3, -g)).transpose();
  }
  const payload::PayloadEstimate e = payload::identify(two, payload::IdentifyRequest{});
  ASSERT_TRUE(e.ok()) << e.message;
  ASSERT_FALSE(e.identifiability.undetermined.empty());
  EXPECT_EQ(payload::to_json(from_json<payload::PayloadEstimate>(payload::to_json(e))), payload::to_json(e));
}

TEST(PhysicalFromJson, PayloadDesignRoundTrips) {
  std::mt19937_64 random(7);
  std::normal_distribution<double> normal;
  Eigen::Matrix<double, 3, Eigen::Dynamic> g(3, 60);
  for (Eigen::Index j = 0; j < g.cols(); ++j) {
    g.col(j) = Eigen::Vector3d(normal(random), normal(random), normal(random));
    g.col(j) *= 9.80665 / g.col(j).norm();
  }
  payload::DesignRequest request;
  request.poses = 6;
  request.random = 40;
  const payload::DesignResult r = payload::design(g, request);
  const std::string text = payload::to_json(r);
  EXPECT_EQ(payload::to_json(from_json<payload::DesignResult>(text)), text);
}

TEST(PhysicalFromJson, RegressionsRoundTrip) {
  std::mt19937_64 random(11);
  std::normal_distribution<double> normal;
  Eigen::MatrixXd Y(80, 21);
  for (Eigen::Index i = 0; i < Y.rows(); ++i) {
    for (Eigen::Index j = 0; j < Y.cols(); ++j) Y(i, j) = normal(random);
  }
  Y.col(13) = Y.col(2);  // body 2's m c_x confounded with body 1's m c_y: an undetermined combination
  Eigen::VectorXd phi(21);
  phi << 2.0, 0.02, -0.04, 0.06, 0.1, 0.001, 0.002, 0.12, 0.003, 0.09, 1.5, 0.01, 0.0, 0.03, 0.05, 0.0, 0.0, 0.06,
      0.0, 0.04, 0.3;
  Eigen::MatrixXd tau = Y * phi;
  for (Eigen::Index i = 0; i < tau.rows(); ++i) tau(i, 0) += 0.01 * normal(random);
  for (const int bootstrap : {0, 20}) {
    physical::RegressRequest request;
    request.bodies = 2;
    request.bootstrap = bootstrap;
    const physical::RegressResult r = physical::regress(Y, tau, request);
    ASSERT_TRUE(r.ok()) << r.message;
    ASSERT_FALSE(r.identifiability.undetermined.empty());
    const std::string text = physical::to_json(r);
    EXPECT_EQ(physical::to_json(from_json<physical::RegressResult>(text)), text) << "bootstrap " << bootstrap;
  }
}

TEST(PhysicalFromJson, HexapodPhysicalEstimatesRoundTrip) {
  const hexapod::Geometry geometry = hexapod::cubic_geometry();
  hexapod::SimulationOptions simulation;
  simulation.samples = 120;
  simulation.noise_var = 0.5;
  RigidBodyInertia payload;
  payload.mass = 1.3 * geometry.payload_mass;
  payload.center_of_mass = Eigen::Vector3d(0.012, -0.007, 0.021);
  payload.inertia << 0.13, 0.004, -0.002, 0.004, 0.09, 0.006, -0.002, 0.006, 0.11;
  const hexapod::Measurements data = hexapod::simulate(geometry, payload, simulation, 4);
  hexapod::PhysicalOptions plain, boot, offsets;
  boot.bootstrap = 20;
  boot.threads = 1;
  offsets.intercept = true;
  offsets.robust = RobustLoss::Huber;
  for (const hexapod::PhysicalOptions& options : {plain, boot, offsets}) {
    const hexapod::PhysicalEstimate e = hexapod::identify_physical(data.A, data.B, geometry, options);
    ASSERT_TRUE(e.ok()) << e.message;
    const std::string text = hexapod::physical_json(e);
    EXPECT_EQ(hexapod::physical_json(from_json<hexapod::PhysicalEstimate>(text)), text);
  }
  hexapod::PhysicalEstimate failed;
  failed.status = Status::NumericalFailure;
  failed.message = "the optimizer failed";
  failed.warnings.emplace_back(Code::NotConverged, "not converged");
  const auto back = from_json<hexapod::PhysicalEstimate>(hexapod::physical_json(failed));
  EXPECT_EQ(back.message, failed.message);
  EXPECT_EQ(hexapod::physical_json(back), hexapod::physical_json(failed));
}

TEST(PhysicalFromJson, InertiaRepairsAndExperimentsRoundTrip) {
  RigidBodyInertia body;
  body.mass = 2.0;
  body.center_of_mass = Eigen::Vector3d(0.01, 0.0, -0.02);
  body.inertia = Eigen::Vector3d(0.1, 0.2, 0.5).asDiagonal();
  const InertiaRepairResult r = repair_inertia(body, InertiaRepairOptions{});
  ASSERT_TRUE(r.changed);
  EXPECT_EQ(inertia_repair_json(from_json<InertiaRepairResult>(inertia_repair_json(r))), inertia_repair_json(r));

  experiment::PhysicalExperimentOptions options;
  options.samples = {12, 20};
  options.methods = {Method::Spde};
  options.variants = {"physical", "grey-box-ls"};
  options.payload = RigidBodyInertia{14.0, Eigen::Vector3d(0.01, 0.0, 0.02), Eigen::Vector3d(0.1, 0.12, 0.09).asDiagonal()};
  experiment::MonteCarloOptions monte_carlo;
  monte_carlo.trials = 3;
  monte_carlo.threads = 1;
  const experiment::PhysicalExperimentResult result = experiment::run_physical_experiment(options, monte_carlo);
  const std::string text = experiment::to_json(result);
  EXPECT_EQ(experiment::to_json(from_json<experiment::PhysicalExperimentResult>(text)), text);
}

TEST(PhysicalFromJson, AnotherDocumentIsRefusedNamingTheClassAndKey) {
  try {
    from_json<payload::PayloadEstimate>(R"({"status": "success", "model": "static"})");
    FAIL() << "no exception";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("payload::PayloadEstimate"), std::string::npos) << e.what();
  }
  EXPECT_THROW(from_json<physical::RegressResult>("[1, 2]"), std::invalid_argument);
  EXPECT_THROW(from_json<InertiaRepairResult>("not json"), std::invalid_argument);
  try {
    from_json<experiment::PhysicalExperimentResult>(R"({"experiment": "thesis"})");
    FAIL() << "no exception";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("'experiment'"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace spdfit
