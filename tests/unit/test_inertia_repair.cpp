// repair_inertia (inertia_repair.hpp): the closed-form eigenvalue clip of the second moment, its
// optimality conditions, a consistent inertia unchanged, the JSON format, and URDF files repaired
// in place with everything else kept.
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <cmath>
#include <string>

#include "spdfit/inertia_repair.hpp"
#include "spdfit/io.hpp"
#include "spdfit/rigid_body.hpp"
#include "test_support.hpp"

namespace spdfit {
namespace {

using test::Generator;

RigidBodyInertia body_with_moments(const Eigen::Vector3d& moments, const Eigen::Matrix3d& axes) {
  RigidBodyInertia b;
  b.mass = 2.5;
  b.center_of_mass = Eigen::Vector3d(0.1, -0.2, 0.05);
  b.inertia = axes * moments.asDiagonal() * axes.transpose();
  b.inertia = 0.5 * (b.inertia + b.inertia.transpose()).eval();
  return b;
}

Eigen::Matrix3d rotation(Generator& g) {
  Eigen::Matrix3d Q = g.orthonormal(3, 3);
  if (Q.determinant() < 0) Q.col(0) *= -1.0;
  return Q;
}

TEST(InertiaRepair, SecondMomentAndPseudoInertiaAreConsistentDefinitions) {
  Generator g(3501);
  const RigidBodyInertia b = body_with_moments(Eigen::Vector3d(0.3, 0.4, 0.5), rotation(g));
  EXPECT_LT((inertia_from_second_moment(second_moment(b.inertia)) - b.inertia).norm(), 1e-15);
  const RigidBodyInertia back = rigid_body_from_pseudo_inertia(pseudo_inertia(b));
  EXPECT_NEAR(back.mass, b.mass, 1e-15);
  EXPECT_LT((back.center_of_mass - b.center_of_mass).norm(), 1e-15);
  EXPECT_LT((back.inertia - b.inertia).norm(), 1e-14);
}

TEST(InertiaRepair, ConsistentInertiaComesBackUnchanged) {
  Generator g(3502);
  const RigidBodyInertia b = body_with_moments(Eigen::Vector3d(0.3, 0.4, 0.5), rotation(g));
  const InertiaRepairResult r = repair_inertia(b);
  EXPECT_FALSE(r.changed);
  EXPECT_EQ(r.distance, 0.0);
  EXPECT_EQ(r.repaired.inertia, b.inertia);  // bit for bit
  EXPECT_EQ(r.repaired.mass, b.mass);
  EXPECT_EQ(r.repaired.center_of_mass, b.center_of_mass);
}

TEST(InertiaRepair, IsTheEigenvalueClipOfTheSecondMoment) {
  // Principal moments (0.1, 0.2, 0.5) break the triangle inequality: 0.5 > 0.1 + 0.2.
  Generator g(3503);
  for (int repeat = 0; repeat < 20; ++repeat) {
    const Eigen::Matrix3d axes = rotation(g);
    const Eigen::Vector3d moments(g.uniform(0.05, 0.2), g.uniform(0.1, 0.3), g.uniform(0.5, 0.9));
    const RigidBodyInertia b = body_with_moments(moments, axes);
    for (double rel : {0.0, 1e-6, 1e-3}) {
      InertiaRepairOptions options;
      options.min_eig_rel = rel;
      options.metric = InertiaMetric::SecondMoment;  // the clip of Sigma (the default is the inertia metric)
      const InertiaRepairResult r = repair_inertia(b, options);
      ASSERT_TRUE(r.changed);
      // The reference: Sigma = (1/2) tr(I) 1 - I, clipped in its own eigenbasis.
      const Eigen::Matrix3d sigma = 0.5 * b.inertia.trace() * Eigen::Matrix3d::Identity() - b.inertia;
      const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(sigma);
      const double floor = rel * eig.eigenvalues().cwiseAbs().maxCoeff();
      const Eigen::Matrix3d clipped =
          eig.eigenvectors() * eig.eigenvalues().cwiseMax(floor).asDiagonal() * eig.eigenvectors().transpose();
      const Eigen::Matrix3d expected = clipped.trace() * Eigen::Matrix3d::Identity() - clipped;
      EXPECT_LT((r.repaired.inertia - expected).norm(), 1e-14 * expected.norm());
      EXPECT_NEAR(r.floor, floor, 1e-16);
      EXPECT_NEAR(r.distance, (expected - b.inertia).norm(), 1e-14);
      // Mass and centre of mass kept; the triangle inequality holds by the floor's margin.
      EXPECT_EQ(r.repaired.mass, b.mass);
      EXPECT_EQ(r.repaired.center_of_mass, b.center_of_mass);
      const Eigen::Vector3d I = r.principal_moments;
      // (I_i + I_j - I_k = 2 sigma_k, to the rounding of the moments.)
      EXPECT_GE(I(0) + I(1) - I(2), 2 * floor - 8 * test::kEps * I(2));
      // The KKT conditions of the projection, from the returned inertia.
      EXPECT_GE(r.certificate.primal_min_eig, -1e-15);
      EXPECT_GE(r.certificate.dual_min_eig, -1e-15);
      EXPECT_LT(std::abs(r.certificate.complementarity), 1e-15);
      // Nearest: no consistent inertia with the same floor is closer (random consistent ones).
      for (int t = 0; t < 20; ++t) {
        const Eigen::Matrix3d other = body_with_moments(
            Eigen::Vector3d(g.uniform(0.2, 0.5), g.uniform(0.2, 0.5), g.uniform(0.2, 0.5)), rotation(g)).inertia;
        const Eigen::Matrix3d other_sigma = second_moment(other);
        if (Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(other_sigma).eigenvalues()(0) < floor) continue;
        EXPECT_GE((other_sigma - sigma).norm(), (clipped - sigma).norm());
      }
    }
  }
}

TEST(InertiaRepair, PassesAStrictTriangleCheckAfterRoundingToSevenDigits) {
  // A thin rod whose moments exactly meet the inequality (I_x = 0): consistent but on the boundary;
  // with the default floor it leaves with a margin that survives printing to 7 digits.
  RigidBodyInertia rod;
  rod.mass = 1.0;
  rod.inertia = Eigen::Vector3d(0.0, 0.1, 0.1).asDiagonal();
  const InertiaRepairResult r = repair_inertia(rod);
  EXPECT_TRUE(r.changed);
  Eigen::Vector3d I;
  char text[64];
  for (int i = 0; i < 3; ++i) {
    std::snprintf(text, sizeof text, "%.7g", r.principal_moments(i));
    I(i) = std::stod(text);
  }
  EXPECT_LT(I(2), I(0) + I(1));
  EXPECT_GT(I(0), 0.0);
}

TEST(InertiaRepair, RefusesMalformedBodies) {
  RigidBodyInertia b;
  b.mass = -1.0;
  b.inertia = Eigen::Matrix3d::Identity();
  EXPECT_THROW(repair_inertia(b), std::invalid_argument);
  b.mass = 1.0;
  b.inertia(0, 1) = 0.3;  // not symmetric
  try {
    repair_inertia(b);
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("inertia is not symmetric"), std::string::npos);
  }
  b.inertia(0, 1) = 0.0;
  InertiaRepairOptions options;
  options.min_eig_rel = 1.0;
  EXPECT_THROW(repair_inertia(b, options), std::invalid_argument);
}

TEST(InertiaRepair, JsonRoundTrip) {
  const std::string text = R"({"_note": "from CAD", "mass": 2.0, "center_of_mass": [0.1, 0, 0],
    "inertia": [[0.1, 0, 0], [0, 0.2, 0], [0, 0, 0.5]]})";
  const RigidBodyInertia b = parse_rigid_body(text, "in.json");
  const InertiaRepairResult r = repair_inertia(b);
  ASSERT_TRUE(r.changed);
  const RigidBodyInertia back = parse_rigid_body(inertia_repair_json(r).substr(0), "out.json");
  EXPECT_EQ(back.mass, r.repaired.mass);
  EXPECT_EQ(back.center_of_mass, r.repaired.center_of_mass);
  EXPECT_EQ(back.inertia, r.repaired.inertia);  // numbers round-trip exactly
}

TEST(InertiaRepair, JsonErrorsNameTheFileAndKey) {
  auto message = [](const std::string& text) {
    try {
      parse_rigid_body(text, "body.json");
    } catch (const io::DataError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_NE(message(R"({"mass": 1, "center_of_mass": [0, 0, 0]})").find("body.json: missing key \"inertia\""),
            std::string::npos);
  EXPECT_NE(message(R"({"mass": "one", "center_of_mass": [0,0,0], "inertia": [[1,0,0],[0,1,0],[0,0,1]]})")
                .find("mass must be a number"),
            std::string::npos);
  EXPECT_NE(message(R"({"mass": 1, "center_of_mass": [0,0], "inertia": [[1,0,0],[0,1,0],[0,0,1]]})")
                .find("center_of_mass must be [x, y, z]"),
            std::string::npos);
  EXPECT_NE(message(R"({"mass": 1, "com": [0,0,0]})").find("unknown key \"com\""), std::string::npos);
  EXPECT_NE(message("{\"mass\": 1,\n \"inertia\": }").find("body.json:2:"), std::string::npos);
  EXPECT_NE(message(R"({"mass": 0, "center_of_mass": [0,0,0], "inertia": [[1,0,0],[0,1,0],[0,0,1]]})")
                .find("mass must be positive"),
            std::string::npos);
}

const char* kUrdf = R"(<?xml version="1.0"?>
<!-- two links: one consistent, one not -->
<robot name="arm">
  <link name="base">
    <inertial>
      <origin xyz="0 0 0.1" rpy="0 0 0"/>
      <mass value="1.5"/>
      <inertia ixx="0.1" ixy="0" ixz="0" iyy="0.1" iyz="0" izz="0.15"/>
    </inertial>
    <visual><geometry><box size="1 1 1" /></geometry></visual>
  </link>
  <link name='forearm'>
    <inertial>
      <mass value="2"/>
      <inertia ixx='1e-3' ixy="0.0" ixz="0.0" iyy="1e-3" iyz="0.0" izz="5e-3"></inertia>
    </inertial>
  </link>
  <link name="tool"/>
  <joint name="elbow" type="revolute"><parent link="base"/><child link="forearm"/></joint>
</robot>
)";

TEST(InertiaRepair, UrdfRepairsOnlyTheInconsistentLinkAndKeepsEverythingElse) {
  const UrdfRepairResult r = repair_urdf(kUrdf, "arm.urdf");
  ASSERT_EQ(r.links.size(), 2u);
  EXPECT_EQ(r.links[0].link, "base");
  EXPECT_FALSE(r.links[0].result.changed);
  EXPECT_EQ(r.links[1].link, "forearm");
  EXPECT_TRUE(r.links[1].result.changed);
  EXPECT_EQ(r.links[1].line, 15u);
  EXPECT_EQ(r.changed(), 1u);
  // Everything but the forearm's <inertia> line is byte for byte the input.
  const std::string in = kUrdf;
  const std::size_t line_start = in.find("      <inertia ixx='1e-3'");
  const std::size_t line_end = in.find('\n', line_start);
  EXPECT_EQ(r.text.substr(0, line_start), in.substr(0, line_start));
  const std::string tail = in.substr(line_end);
  EXPECT_EQ(r.text.substr(r.text.size() - tail.size()), tail);
  // The repaired file reads back as consistent, with the repaired numbers exactly.
  const UrdfRepairResult again = repair_urdf(r.text, "repaired.urdf");
  EXPECT_EQ(again.changed(), 0u);
  EXPECT_EQ(again.text, r.text);
  EXPECT_EQ(again.links[1].result.input.inertia, r.links[1].result.repaired.inertia);
}

TEST(InertiaRepair, UrdfErrorsNameTheFileLineAndLink) {
  auto message = [](const std::string& text) {
    try {
      repair_urdf(text, "bad.urdf");
    } catch (const io::DataError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_NE(message("<robot><link name=\"a\"><inertial><mass value=\"x\"/>"
                    "<inertia ixx=\"1\" ixy=\"0\" ixz=\"0\" iyy=\"1\" iyz=\"0\" izz=\"1\"/></inertial></link></robot>")
                .find("bad.urdf:1: link \"a\": <mass value> must be a finite number"),
            std::string::npos);
  EXPECT_NE(message("<robot>\n<link name=\"a\">\n<inertial><mass value=\"1\"/>\n"
                    "<inertia ixx=\"1\" ixy=\"0\" ixz=\"0\" iyy=\"1\" izz=\"1\"/></inertial></link></robot>")
                .find("bad.urdf:4: link \"a\": <inertia iyz> is missing"),
            std::string::npos);
  EXPECT_NE(message("<robot><link name=\"a\"><inertial><mass value=\"1\"/></inertial></link></robot>")
                .find("<inertial> has no <inertia>"),
            std::string::npos);
  EXPECT_NE(message("<robot><link></robot>").find("not valid XML"), std::string::npos);
  EXPECT_NE(message("<sdf/>").find("root element must be <robot>"), std::string::npos);
}

}  // namespace
}  // namespace spdfit
