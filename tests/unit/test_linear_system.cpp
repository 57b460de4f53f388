// solve(A, B): the six classified systems of notes 002 section 3.3.2 (in their equations as
// written), the projective classification on other shapes, and the SVD quantities against an
// independent pseudo-inverse.
#include <gtest/gtest.h>

#include <Eigen/QR>
#include <Eigen/SVD>

#include "spdfit/linear_system.hpp"
#include "test_support.hpp"

namespace spdfit {
namespace {

using test::Generator;
using test::kEps;
using test::relative_error;

MatrixXd rows3(std::initializer_list<double> values) {
  MatrixXd A(3, 3);
  auto it = values.begin();
  for (Index i = 0; i < 3; ++i)
    for (Index j = 0; j < 3; ++j) A(i, j) = *it++;
  return A;
}

VectorXd vec(std::initializer_list<double> values) {
  VectorXd v(static_cast<Index>(values.size()));
  Index i = 0;
  for (double x : values) v(i++) = x;
  return v;
}

bool contains(const std::string& text, const std::string& fragment) { return text.find(fragment) != std::string::npos; }

// Solutions of consistent systems satisfy A x = b to the backward-stable bound
// eps ||A|| ||x|| times a small constant (3 unknowns, an SVD and a product).
constexpr double kResidualFactor = 64 * kEps;

// Example 1: unique finite solution x = (21, 10, -2) / 13.
TEST(LinearSystemNotes, Example1UniqueFiniteSolution) {
  const MatrixXd A = rows3({5, -1, 2, -2, 6, 9, -7, 5, -3});
  const VectorXd b = vec({7, 0, -7});
  const LinearSystemResult r = solve(A, b);
  EXPECT_TRUE(r.consistent);
  EXPECT_EQ(r.rank, 3);
  EXPECT_EQ(r.nullity, 0);
  EXPECT_EQ(r.finite_solution_dimension, 0);
  EXPECT_EQ(r.at_infinity_dimension, -1);
  EXPECT_LT(relative_error(r.solution, vec({21, 10, -2}) / 13.0), 16 * kEps * r.condition_number);
  EXPECT_EQ(r.null_space.cols(), 0);
  EXPECT_EQ(r.range.cols(), 3);
  EXPECT_TRUE(r.warnings.empty());
  EXPECT_TRUE(contains(r.explanation, "exactly one point in common"));
}

// Example 2: the line x = (6 - 3t, 2 - 7t, 4t) / 4.
TEST(LinearSystemNotes, Example2LineOfFiniteSolutions) {
  const MatrixXd A = rows3({5, -1, 2, -2, 6, 9, 15, -3, 6});
  const VectorXd b = vec({7, 0, 21});
  const LinearSystemResult r = solve(A, b);
  EXPECT_TRUE(r.consistent);
  EXPECT_EQ(r.rank, 2);
  EXPECT_EQ(r.finite_solution_dimension, 1);
  EXPECT_EQ(r.at_infinity_dimension, 0);
  EXPECT_LT(r.residual_norm, kResidualFactor * A.norm() * r.solution.norm());
  // The null space is the line's direction (-3, -7, 4); the minimum-norm point is orthogonal to it.
  ASSERT_EQ(r.null_space.cols(), 1);
  const VectorXd direction = vec({-3, -7, 4}).normalized();
  EXPECT_NEAR(std::abs(r.null_space.col(0).dot(direction)), 1.0, 1e-14);
  EXPECT_NEAR(r.solution.col(0).dot(direction), 0.0, 1e-14);
  // And it lies on the notes' line: x - (6, 2, 0)/4 is parallel to the direction.
  const VectorXd offset = r.solution.col(0) - vec({1.5, 0.5, 0});
  EXPECT_LT((offset - offset.dot(direction) * direction).norm(), 1e-14);
  EXPECT_TRUE(contains(r.explanation, "a line of finite points in common"));
  EXPECT_TRUE(contains(r.explanation, "one point at infinity"));
}

// Example 3: three coincident planes, a plane of solutions 5x - y + 2z = 7.
TEST(LinearSystemNotes, Example3PlaneOfFiniteSolutions) {
  const MatrixXd A = rows3({5, -1, 2, 10, -2, 4, -15, 3, -6});
  const VectorXd b = vec({7, 14, -21});
  const LinearSystemResult r = solve(A, b);
  EXPECT_TRUE(r.consistent);
  EXPECT_EQ(r.rank, 1);
  EXPECT_EQ(r.finite_solution_dimension, 2);
  EXPECT_EQ(r.at_infinity_dimension, 1);
  EXPECT_NEAR(vec({5, -1, 2}).dot(r.solution.col(0)), 7.0, 1e-13);
  EXPECT_LT((A * r.null_space).norm(), kResidualFactor * A.norm());
  EXPECT_TRUE(contains(r.explanation, "the planes coincide"));
}

// Example 4 as its equations have it: three parallel planes, a line at infinity in common.
TEST(LinearSystemNotes, Example4ParallelPlanesMeetInALineAtInfinity) {
  const MatrixXd A = rows3({5, -1, 2, -10, 2, -4, 15, -3, 6});
  const VectorXd b = vec({7, -5, -5});
  const LinearSystemResult r = solve(A, b);
  EXPECT_FALSE(r.consistent);
  EXPECT_EQ(r.rank, 1);
  EXPECT_EQ(r.finite_solution_dimension, -1);
  EXPECT_EQ(r.at_infinity_dimension, 1);
  EXPECT_TRUE(contains(r.explanation, "no finite point in common"));
  EXPECT_TRUE(contains(r.explanation, "a line at infinity"));
  // The least-squares solution satisfies the normal equations A^T (A x - b) = 0.
  EXPECT_LT((A.transpose() * (A * r.solution - b)).norm(),
            kResidualFactor * A.norm() * (A.norm() * r.solution.norm() + b.norm()));
}

// The matrix printed for example 4 (a 6 where the equations have a 2) is a different system:
// rank 2, and its parallel first and third planes meet the second in parallel lines.
TEST(LinearSystemNotes, Example4AsPrintedIsADifferentSystem) {
  const MatrixXd A = rows3({5, -1, 2, -10, 6, -4, 15, -3, 6});
  const LinearSystemResult r = solve(A, vec({7, -5, -5}));
  EXPECT_EQ(r.rank, 2);
  EXPECT_FALSE(r.consistent);
  EXPECT_EQ(r.at_infinity_dimension, 0);
}

// Example 5: two parallel planes cut by a third: one point at infinity.
TEST(LinearSystemNotes, Example5OnePointAtInfinity) {
  const MatrixXd A = rows3({5, -1, 2, -2, 6, 9, -10, 2, -4});
  const LinearSystemResult r = solve(A, vec({7, 0, 18}));
  EXPECT_FALSE(r.consistent);
  EXPECT_EQ(r.rank, 2);
  EXPECT_EQ(r.finite_solution_dimension, -1);
  EXPECT_EQ(r.at_infinity_dimension, 0);
  EXPECT_TRUE(contains(r.explanation, "parallel lines meet at one point at infinity"));
}

// Example 6: three planes whose pairwise lines of intersection are parallel.
TEST(LinearSystemNotes, Example6NoFiniteSolution) {
  const MatrixXd A = rows3({5, -1, 2, -2, 6, 9, 0, 8, 14});
  const LinearSystemResult r = solve(A, vec({-12, 0, 8}));
  EXPECT_FALSE(r.consistent);
  EXPECT_EQ(r.rank, 2);
  EXPECT_EQ(r.finite_solution_dimension, -1);
  EXPECT_EQ(r.at_infinity_dimension, 0);
  // The point at infinity is the common direction of the lines: the null space of A.
  ASSERT_EQ(r.null_space.cols(), 1);
  EXPECT_LT((A * r.null_space).norm(), kResidualFactor * A.norm());
  EXPECT_FALSE(r.warnings.empty());  // singular: reciprocal condition number below 1e-12
}

TEST(LinearSystem, UnderdeterminedPlanesMeetInALine) {
  MatrixXd A(2, 3);
  A << 1, 0, 0, 0, 1, 0;
  const LinearSystemResult r = solve(A, vec({1, 2}));
  EXPECT_EQ(r.shape, SystemShape::Underdetermined);
  EXPECT_TRUE(r.consistent);
  EXPECT_EQ(r.rank, 2);
  EXPECT_EQ(r.nullity, 1);
  EXPECT_EQ(r.finite_solution_dimension, 1);
  EXPECT_EQ(r.at_infinity_dimension, 0);
  EXPECT_LT(relative_error(r.solution, vec({1, 2, 0})), 4 * kEps);
  ASSERT_EQ(r.null_space.rows(), 3);
  ASSERT_EQ(r.null_space.cols(), 1);
  EXPECT_NEAR(std::abs(r.null_space(2, 0)), 1.0, 4 * kEps);
}

TEST(LinearSystem, OverdeterminedConsistentAndInconsistent) {
  Generator g(41);
  const MatrixXd A = g.gaussian(12, 4);
  const VectorXd x = g.gaussian(4, 1);
  LinearSystemResult r = solve(A, A * x);
  EXPECT_EQ(r.shape, SystemShape::Overdetermined);
  EXPECT_TRUE(r.consistent);
  EXPECT_EQ(r.finite_solution_dimension, 0);
  EXPECT_LT(relative_error(r.solution, x), 64 * kEps * r.condition_number);
  EXPECT_LT(r.columns[0].backward_error, 16 * kEps);

  const VectorXd b = g.gaussian(12, 1);
  r = solve(A, b);
  EXPECT_FALSE(r.consistent);
  EXPECT_EQ(r.at_infinity_dimension, -1);  // full column rank: no point at infinity either
  EXPECT_LT((A.transpose() * (A * r.solution - b)).norm(), 64 * kEps * A.norm() * (A.norm() * r.solution.norm() + b.norm()));
  EXPECT_TRUE(contains(r.explanation, "no point in common, finite or at infinity"));
}

TEST(LinearSystem, OneByOne) {
  LinearSystemResult r = solve(MatrixXd::Constant(1, 1, 2.0), VectorXd::Constant(1, 4.0));
  EXPECT_TRUE(r.consistent);
  EXPECT_EQ(r.solution(0, 0), 2.0);
  EXPECT_EQ(r.condition_number, 1.0);

  r = solve(MatrixXd::Zero(1, 1), VectorXd::Constant(1, 1.0));  // 0 x = 1: only the point at infinity
  EXPECT_FALSE(r.consistent);
  EXPECT_EQ(r.rank, 0);
  EXPECT_EQ(r.at_infinity_dimension, 0);
  EXPECT_EQ(r.solution(0, 0), 0.0);
  EXPECT_TRUE(std::isinf(r.condition_number));
  EXPECT_EQ(r.reciprocal_condition_number, 0.0);

  r = solve(MatrixXd::Zero(1, 1), VectorXd::Zero(1));  // 0 x = 0: every x
  EXPECT_TRUE(r.consistent);
  EXPECT_EQ(r.finite_solution_dimension, 1);
}

TEST(LinearSystem, SeveralRightHandSidesAreClassifiedOneByOne) {
  const MatrixXd A = rows3({5, -1, 2, -2, 6, 9, 15, -3, 6});  // example 2's matrix, rank 2
  MatrixXd B(3, 2);
  B.col(0) = vec({7, 0, 21});   // consistent (example 2)
  B.col(1) = vec({7, 0, 20});   // not: the third plane moved off the first
  const LinearSystemResult r = solve(A, B);
  ASSERT_EQ(r.columns.size(), 2u);
  EXPECT_TRUE(r.columns[0].consistent);
  EXPECT_FALSE(r.columns[1].consistent);
  EXPECT_FALSE(r.consistent);
  EXPECT_EQ(r.finite_solution_dimension, -1);
  EXPECT_EQ(r.columns[0].finite_solution_dimension, 1);
  EXPECT_EQ(r.at_infinity_dimension, 0);
  EXPECT_EQ(r.solution.cols(), 2);
  EXPECT_TRUE(contains(r.explanation, "Right-hand side 2"));
}

TEST(LinearSystem, ConsistencyDoesNotDependOnTheScaleOfB) {
  const MatrixXd A = rows3({5, -1, 2, -2, 6, 9, 15, -3, 6});
  for (double scale : {1e-200, 1e-8, 1.0, 1e8, 1e200}) {
    EXPECT_TRUE(solve(A, scale * vec({7, 0, 21})).consistent) << scale;
    EXPECT_FALSE(solve(A, scale * vec({7, 0, 20})).consistent) << scale;
  }
}

TEST(LinearSystem, ThresholdEditsSmallSingularValues) {
  Generator g(42);
  const MatrixXd A = g.with_singular_values(6, vec({1.0, 1e-10}));
  const VectorXd b = g.gaussian(6, 1);
  const LinearSystemResult exact = solve(A, b);
  EXPECT_EQ(exact.rank, 2);
  EXPECT_NEAR(exact.condition_number, 1e10, 1e10 * 1e-5);
  LinearSystemOptions options;
  options.rank_tolerance = 1e-8;
  const LinearSystemResult edited = solve(A, b, options);
  EXPECT_EQ(edited.rank, 1);
  EXPECT_EQ(edited.nullity, 1);
  EXPECT_EQ(edited.rank_tolerance, 1e-8);
  EXPECT_LT(edited.solution.norm(), 1e-3 * exact.solution.norm());  // no 1/sigma = 1e10 blow-up
  EXPECT_TRUE(contains(edited.explanation, "edited to zero"));

  // The deprecated name of the option and of the result's field still work, for one release.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wdeprecated-declarations"
  LinearSystemOptions old_name;
  old_name.threshold = 1e-8;
  const LinearSystemResult old = solve(A, b, old_name);
  EXPECT_EQ(old.rank, 1);
  EXPECT_EQ(old.threshold, 1e-8);
  EXPECT_EQ(old.rank_tolerance, 1e-8);
#pragma GCC diagnostic pop
}

// The minimum-norm solution is A^+ b, computed here by a different decomposition.
TEST(LinearSystem, MatchesThePseudoInverseOnRandomRankDeficientSystems) {
  Generator g(43);
  for (int trial = 0; trial < 20; ++trial) {
    const Index m = 2 + trial % 7, n = 2 + (trial * 3) % 6, r = 1 + trial % std::min(m, n);
    const MatrixXd A = g.gaussian(m, r) * g.gaussian(r, n);
    const MatrixXd B = g.gaussian(m, 2);
    const LinearSystemResult result = solve(A, B);
    EXPECT_EQ(result.rank, r) << m << "x" << n;
    EXPECT_EQ(result.nullity, n - r);
    Eigen::CompleteOrthogonalDecomposition<MatrixXd> cod(A);
    cod.setThreshold(1e-10);
    EXPECT_LT(relative_error(result.solution, cod.pseudoInverse() * B), 1e-10) << m << "x" << n;
    EXPECT_LT((A * result.null_space).norm(), 1e-12 * A.norm());
    EXPECT_LT((result.null_space.transpose() * result.null_space - MatrixXd::Identity(n - r, n - r)).norm(), 1e-13);
    EXPECT_LT((result.range.transpose() * result.range - MatrixXd::Identity(r, r)).norm(), 1e-13);
    EXPECT_EQ(result.at_infinity_dimension, n - r - 1);
  }
}

TEST(LinearSystem, BadInputThrows) {
  const MatrixXd A = MatrixXd::Identity(2, 2);
  EXPECT_THROW(solve(MatrixXd(0, 2), VectorXd(0)), std::invalid_argument);
  EXPECT_THROW(solve(A, VectorXd::Ones(3)), std::invalid_argument);
  EXPECT_THROW(solve(A, MatrixXd(2, 0)), std::invalid_argument);
  MatrixXd bad = A;
  bad(0, 1) = std::nan("");
  EXPECT_THROW(solve(bad, VectorXd::Ones(2)), std::invalid_argument);
  EXPECT_THROW(solve(A, VectorXd::Constant(2, std::numeric_limits<double>::infinity())), std::invalid_argument);
  LinearSystemOptions options;
  options.rank_tolerance = 1.5;
  EXPECT_THROW(solve(A, VectorXd::Ones(2), options), std::invalid_argument);
}

// Regression (found by the stress tests): A of denormal size gave 1 / sigma = Inf and a solution of
// NaN and Inf even when the exact solution is of order one.
TEST(LinearSystemRegression, DenormalAGivesTheSolutionOfTheScaledSystem) {
  Generator g(90);
  const MatrixXd A = g.gaussian(4, 3);
  const VectorXd b = g.gaussian(4, 1);
  const LinearSystemResult unit = solve(A, b);
  for (const double scale : {1e-310, 1e-200, 1e200}) {
    const LinearSystemResult scaled = solve(A * scale, b * scale);
    ASSERT_TRUE(scaled.ok()) << scaled.message;
    ASSERT_TRUE(scaled.solution.allFinite()) << scale;
    // 1e-310 has about 44 significant bits left, so the data itself is rounded at 1e-13.
    EXPECT_LT(relative_error(scaled.solution, unit.solution), scale < 1e-300 ? 1e-11 : 1e-14) << scale;
    EXPECT_EQ(scaled.rank, unit.rank);
    EXPECT_NEAR(scaled.condition_number, unit.condition_number, 1e-11 * unit.condition_number);
    EXPECT_NEAR(scaled.residual_norm / scale, unit.residual_norm, 1e-11 * unit.residual_norm) << scale;
  }
}

// Regression (found by the stress tests): b at 1e-310 lost digits in U^T b, computed among the
// denormals, before the division by sigma, so that x was off by ten units in the last place. The same system lifted into the normal range by a power of two (exactly) has the
// same solution.
TEST(LinearSystemRegression, DenormalRightHandSideKeepsItsDigits) {
  Generator g(91);
  const MatrixXd R = g.orthonormal(3, 3);
  const MatrixXd A = R * 1e-300;
  const VectorXd b = g.gaussian(3, 1) * 3e-310;
  const LinearSystemResult r = solve(A, b);
  ASSERT_TRUE(r.ok());
  const double lift = std::ldexp(1.0, 200);
  const LinearSystemResult lifted = solve(A * lift, b * lift);
  EXPECT_LT(relative_error(r.solution, lifted.solution), 4 * kEps);
}

TEST(LinearSystem, SolutionBeyondTheDoubleRangeIsANumericalFailure) {
  const LinearSystemResult r = solve(MatrixXd::Identity(2, 2) * 1e-300, VectorXd::Constant(2, 1e300));
  EXPECT_FALSE(r.ok());
  EXPECT_EQ(r.status, SolveStatus::NumericalFailure);
  EXPECT_NE(r.message.find("overflows the range of double precision numbers"), std::string::npos) << r.message;
  EXPECT_EQ(r.solution.size(), 0);
  EXPECT_EQ(r.rank, 2);  // the classification is still there
  EXPECT_TRUE(r.consistent);
}

TEST(LinearSystem, TooManyUnknownsThrowsBeforeAllocating) {
  // 10^6 unknowns would need a V of 8 TB.
  const MatrixXd A = MatrixXd::Ones(1, 1000000);
  try {
    solve(A, VectorXd::Ones(1));
    ADD_FAILURE() << "no exception";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("A has 1000000 columns (unknowns); at most 4096"), std::string::npos)
        << e.what();
  }
  LinearSystemOptions options;
  options.max_unknowns = 3;
  EXPECT_THROW(solve(MatrixXd::Ones(1, 4), VectorXd::Ones(1), options), std::invalid_argument);
  options.max_unknowns = 0;
  EXPECT_FALSE(options.is_valid());
}

}  // namespace
}  // namespace spdfit
