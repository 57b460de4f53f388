// Numerical stress for nearest_spd and solve: sizes 1..20, condition numbers up to 1e12 and
// beyond, scales 1e-150..1e150, zero rows and columns, exact and near singularity, denormal
// entries. Each answer is finite and satisfies its defining conditions, or the call fails clearly.
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>

#include "spdfit/linear_system.hpp"
#include "spdfit/nearest_spd.hpp"
#include "stress_support.hpp"

namespace spdfit {
namespace {

using test::Generator;
using test::kEps;

constexpr double kScales[] = {1e-310, 1e-150, 1e-30, 1.0, 1e30, 1e150};

// A symmetric eigensolver is backward stable: the eigenvalues it reports are those of a matrix
// within c n eps ||S|| of S. This factor is c.
constexpr double kEigenFactor = 20.0;

// The minimum-norm least-squares solution from an SVD is backward stable; with singular values
// edited below max(m, n) eps sigma_max, the normal equations hold to
// c (m + n) eps ||A|| (||r|| + ||A|| ||x|| + ||b||) and x lies in the row space to c (m + n) eps
// ||x||, with no condition number (as in test_stress_estimators.cpp). This factor is c.
constexpr double kBackwardFactor = 20.0;

// ---- nearest_spd -------------------------------------------------------------------------------

// A square matrix whose symmetric part has eigenvalues of both signs over `cond`, scaled.
MatrixXd indefinite(Generator& g, Index n, double cond, double scale) {
  const MatrixXd W = g.orthonormal(n, n);
  VectorXd lambda = Generator::log_spaced(n, cond);
  for (Index i = 0; i < n; ++i) {
    if (g.uniform(0, 1) < 0.4) lambda(i) = -lambda(i);
  }
  const MatrixXd skew = g.gaussian(n, n);
  return scale * (W * lambda.asDiagonal() * W.transpose() + 0.1 * (skew - skew.transpose()));
}

// The projection onto {Y = Y^T, Y >= min_eig I} is characterized by (Higham 1988): Y symmetric,
// Y - min_eig I positive semidefinite, Y - S positive semidefinite (eigenvalues only raised), and
// (Y - S)(Y - min_eig I) = 0 (raised eigenvalues end exactly at min_eig). Checked in units where
// ||X|| is about one.
void check_nearest(const MatrixXd& X, double min_eig, const NearestSpdResult& r, const std::string& where) {
  ASSERT_TRUE(test::all_finite(r.X)) << where;
  EXPECT_TRUE(r.X == r.X.transpose()) << where;
  EXPECT_FALSE(std::isnan(r.distance)) << where;
  const int e = test::unit_exponent(X);
  const Index n = X.rows();
  const MatrixXd x = test::scaled_by_power_of_two(X, -e);
  const MatrixXd y = test::scaled_by_power_of_two(r.X, -e);
  const double floor = std::ldexp(min_eig, -e);
  const MatrixXd s = 0.5 * (x + x.transpose());
  // Denormal input: the answer is on the denormal grid, whose spacing is large against entries of 1e-310.
  const double grid = std::ldexp(test::kDenormalStep, -e);
  const double tolerance = kEigenFactor * static_cast<double>(n) * (kEps * std::max(s.norm(), floor) + grid);
  const MatrixXd shifted = y - floor * MatrixXd::Identity(n, n);
  const auto min_eigenvalue = [](const MatrixXd& M) {
    return Eigen::SelfAdjointEigenSolver<MatrixXd>(0.5 * (M + M.transpose()), Eigen::EigenvaluesOnly).eigenvalues()(0);
  };
  EXPECT_GE(min_eigenvalue(shifted), -tolerance) << where;
  EXPECT_GE(min_eigenvalue(y - s), -tolerance) << where;
  EXPECT_LE(((y - s) * shifted).norm(), tolerance * std::max(1.0, s.norm())) << where;
}

TEST(NearestSpdStress, ProjectsAnythingFinite) {
  Generator g(77);
  for (Index n = 1; n <= 20; ++n) {
    for (double scale : kScales) {
      const double cond = std::pow(10.0, g.uniform(0, 12));
      MatrixXd X = indefinite(g, n, cond, scale);
      const int kind = static_cast<int>(g.uniform(0, 4));
      if (kind == 1) X.col(n / 2).setZero();              // a zero column
      if (kind == 2) X.setZero();                         // nothing at all
      if (kind == 3) X(0, n - 1) = 1e-320;                // a denormal entry
      for (double relative_floor : {0.0, 1e-12, 1e-6}) {
        const double min_eig = relative_floor * X.cwiseAbs().maxCoeff();
        const std::string where = "n " + std::to_string(n) + ", scale " + test::format(scale) + ", kind " +
                                  std::to_string(kind) + ", floor " + std::to_string(relative_floor);
        NearestSpdResult r;
        ASSERT_NO_THROW(r = nearest_spd(X, min_eig)) << where;
        check_nearest(X, min_eig, r, where);
      }
    }
  }
}

TEST(NearestSpdStress, EntriesNearTheLargestDouble) {
  MatrixXd X(2, 2);
  X << 1e308, -1.7e308, -1.7e308, 1e308;
  const NearestSpdResult r = nearest_spd(X);
  check_nearest(X, 0.0, r, "near DBL_MAX");
}

// ---- solve -------------------------------------------------------------------------------------

struct SolveCase {
  std::string name;
  MatrixXd A, B;
};

SolveCase make_solve_case(Generator& g, Index m, Index n, int kind) {
  SolveCase c;
  const Index k = std::min(m, n);
  const double cond = kind == 3 ? std::pow(10.0, g.uniform(15, 17)) : std::pow(10.0, g.uniform(0, 12));
  c.A = g.orthonormal(m, k) * Generator::log_spaced(k, cond).asDiagonal() * g.orthonormal(n, k).transpose();
  const Index p = 1 + static_cast<Index>(g.uniform(0, 3));
  c.B = g.gaussian(m, p);
  if (kind == 1) c.A.col(n / 2).setZero();                             // a zero column
  if (kind == 2 && m > 1) c.A.row(m - 1) = c.A.row(0);                 // exactly singular rows
  if (kind == 4) c.B = c.A * g.gaussian(n, p);                         // consistent
  if (kind == 5) c.A(0, 0) = c.B(0, 0) = 1e-320;                       // denormal entries
  if (kind == 6) c.B.setZero();                                        // zero right-hand side
  const double scale_a = kScales[static_cast<int>(g.uniform(0, 6)) % 6];
  const double scale_b = kScales[static_cast<int>(g.uniform(0, 6)) % 6];
  c.A *= scale_a;
  c.B *= scale_b;
  c.name = std::to_string(m) + "x" + std::to_string(n) + ", cond " + test::format(cond) + ", kind " +
           std::to_string(kind) + ", scales " + test::format(scale_a) + " / " + test::format(scale_b);
  return c;
}

void check_solve(const SolveCase& c) {
  LinearSystemResult r;
  ASSERT_NO_THROW(r = solve(c.A, c.B)) << c.name;
  if (!r.ok()) {
    // The one failure on finite data: a solution that does not fit in a double.
    EXPECT_NE(r.message.find("overflows the range"), std::string::npos) << c.name << ": " << r.message;
    EXPECT_EQ(r.solution.size(), 0) << c.name;
    return;
  }
  ASSERT_TRUE(test::all_finite(r.solution)) << c.name;
  ASSERT_TRUE(test::all_finite(r.null_space)) << c.name;
  ASSERT_TRUE(test::all_finite(r.range)) << c.name;
  ASSERT_TRUE(test::all_finite(r.singular_values)) << c.name;
  EXPECT_FALSE(std::isnan(r.residual_norm)) << c.name;
  EXPECT_FALSE(std::isnan(r.condition_number) || std::isnan(r.reciprocal_condition_number)) << c.name;
  for (const ColumnClassification& column : r.columns) {
    EXPECT_FALSE(std::isnan(column.residual_norm) || std::isnan(column.backward_error)) << c.name;
  }
  const test::UnitProblem u = test::in_units(c.A, c.B, r.solution);
  const Index m = c.A.rows(), n = c.A.cols();
  const double residual = (u.a * u.x - u.b).norm();
  const double scale = u.a.norm() * (residual + u.a.norm() * u.x.norm() + u.b.norm());
  const double cutoff = kBackwardFactor * static_cast<double>(m + n) * kEps;
  EXPECT_LE((u.a.transpose() * (u.a * u.x - u.b)).norm(), cutoff * scale + u.a.norm() * u.representation_error())
      << c.name;
  // Minimum norm: no component in the null space (notes 002, eq. 3.21).
  EXPECT_LE((r.null_space.transpose() * u.x).norm(),
            cutoff * u.x.norm() + std::sqrt(static_cast<double>(u.x.size())) * u.x_step)
      << c.name;
}

TEST(SolveStress, AnswersFinitelyAtEveryShapeAndScale) {
  Generator g(4242);
  for (Index m = 1; m <= 20; m += 1) {
    for (const Index n : {Index{1}, m / 2 + 1, m, m + 3}) {
      for (int kind = 0; kind <= 6; ++kind) {
        const SolveCase c = make_solve_case(g, m, n, kind);
        SCOPED_TRACE(c.name);
        check_solve(c);
      }
    }
  }
}

}  // namespace
}  // namespace spdfit
