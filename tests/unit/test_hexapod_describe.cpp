// hexapod::describe, the one model description the CLI and Python format, against independent
// decompositions; and the seeded simulate, which is trial 0 of the thesis experiment's generator.
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <Eigen/SVD>
#include <cmath>

#include "spdfit/hexapod/geometry.hpp"
#include "spdfit/hexapod/model.hpp"
#include "spdfit/hexapod/simulate.hpp"
#include "spdfit/random.hpp"

namespace spdfit::hexapod {
namespace {

constexpr double kEps = 2.220446049250313e-16;

TEST(HexapodDescribe, ReportsTheModelFunctionsAndTheirDecompositions) {
  const Geometry g = cubic_geometry();
  const ModelDescription d = describe(g);
  EXPECT_EQ(d.jacobian, jacobian(g));
  EXPECT_EQ(d.mass_matrix, joint_space_mass_matrix(g));
  EXPECT_EQ(d.payload_mass_matrix, payload_mass_matrix(g));
  EXPECT_EQ(d.modes_hz, modal_frequencies_hz(g));
  EXPECT_EQ(d.strut_lengths, strut_lengths(g));
  EXPECT_EQ(d.strut_directions, strut_directions(g));

  // Eigenvalues: ascending, and each one an eigenvalue of M_p (det(M - lambda I) ~ 0 through the
  // smallest singular value of M - lambda I), summing to the trace.
  const Matrix6d& M = d.mass_matrix;
  for (int i = 0; i < 6; ++i) {
    if (i > 0) {
      EXPECT_LE(d.mass_matrix_eigenvalues(i - 1), d.mass_matrix_eigenvalues(i));
    }
    const Matrix6d shifted = M - d.mass_matrix_eigenvalues(i) * Matrix6d::Identity();
    EXPECT_LT(Eigen::JacobiSVD<Matrix6d>(shifted).singularValues()(5), 100 * kEps * M.norm());
  }
  EXPECT_NEAR(d.mass_matrix_eigenvalues.sum(), M.trace(), 100 * kEps * M.norm());

  // cond(J) from the eigenvalues of J^T J (squared singular values).
  const Vector6d lambda = Eigen::SelfAdjointEigenSolver<Matrix6d>(d.jacobian.transpose() * d.jacobian).eigenvalues();
  EXPECT_NEAR(d.jacobian_condition, std::sqrt(lambda(5) / lambda(0)), 1e-10 * d.jacobian_condition);
}

TEST(HexapodDescribe, RejectsAnInvalidGeometry) {
  Geometry g = cubic_geometry();
  g.payload_mass = -1.0;
  EXPECT_THROW(describe(g), std::invalid_argument);
}

TEST(HexapodSimulate, TheSeededOverloadIsTrialZerosGenerator) {
  SimulationOptions options;
  options.noise_var = 0.86;
  const Eigen::MatrixXd M = thesis_mass_matrix();
  Random random(trial_seed(7, 0));
  const Measurements expected = simulate(M, options, random);
  const Measurements seeded = simulate(M, options, std::uint64_t{7});
  EXPECT_EQ(seeded.A, expected.A);
  EXPECT_EQ(seeded.B, expected.B);
  EXPECT_NE(simulate(M, options, std::uint64_t{8}).A, expected.A);
}

}  // namespace
}  // namespace spdfit::hexapod
