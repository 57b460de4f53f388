// Numerical stress for the estimators: random problems with n = 1..20, cond(A) up to 1e12 (and
// 1e15..1e17 for nearly singular data), A and B scaled independently by 1e-150..1e150, zero and
// duplicate columns, rank-one B, denormal entries and all-zero data. Every estimator returns a
// finite X that satisfies its defining equation, or a NumericalFailure with a message and no X.
// Never NaN or Inf in an answer, never NaN in a diagnostic.
//
// The equations are checked in units where A and B have entries of order one (stress_support.hpp),
// which changes nothing but avoids overflow in the check itself.
#include <gtest/gtest.h>

#include <algorithm>

#include <Eigen/Eigenvalues>
#include <Eigen/QR>
#include <Eigen/SVD>

#include "spdfit/fit.hpp"
#include "spdfit/nearest_spd.hpp"
#include "stress_support.hpp"

namespace spdfit {
namespace {

using test::Generator;
using test::Hostility;
using test::kEps;
using test::StressCase;

// Householder QR and the SVDs are backward stable: the computed X is the exact answer for data
// within c (m + n) eps of a and b, and editing singular values below the rank cut-off max(m, 2n)
// eps moves it by as much again. That bounds the residual of the normal equations by
// c (m + n) eps ||a|| (||r|| + ||a|| ||x|| + ||b||) with no condition number; c is this factor.
constexpr double kBackwardFactor = 20.0;

// spde's X P X = Q holds only to forward accuracy, about cond(A) eps (spde.hpp); this factor
// covers n and the constants of the bound (measured: below 5).
constexpr double kForwardFactor = 100.0;

// The scales A and B are multiplied by, independently.
constexpr double kScales[] = {1e-150, 1e-30, 1.0, 1e30, 1e150};

double pick_scale(Generator& g) { return kScales[static_cast<int>(g.uniform(0, 5)) % 5]; }

// The normal-equation tolerance for a problem in units (see kBackwardFactor).
double backward_tolerance(const test::UnitProblem& u) {
  const double r = (u.a * u.x - u.b).norm();
  return kBackwardFactor * static_cast<double>(u.a.rows() + u.a.cols()) * kEps * u.a.norm() *
             (r + u.a.norm() * u.x.norm() + u.b.norm()) +
         u.a.norm() * u.representation_error();
}

void expect_no_nan_in_diagnostics(const FitResult& r, const std::string& where) {
  const Diagnostics& d = r.diagnostics;
  EXPECT_TRUE(test::not_nan(d.cond_a) && test::not_nan(d.cond_b)) << where;
  EXPECT_TRUE(d.singular_values_a.array().isNaN().count() == 0) << where;
  EXPECT_TRUE(d.singular_values_b.array().isNaN().count() == 0) << where;
  EXPECT_TRUE(test::not_nan(d.residual_norm)) << where;
  for (const auto& x : {d.min_eigenvalue, d.max_eigenvalue, d.area_criterion, d.area_criterion_minimum,
                        d.tls_sigma_n, d.tls_sigma_n1, d.tls_correction_norm, d.tls_v22_min_singular_value}) {
    if (x) {
      EXPECT_TRUE(test::not_nan(*x)) << where;
    }
  }
}

// ls: A^T (A X - B) = 0 (the normal equations; minimum norm when A is rank-deficient).
void check_least_squares(const StressCase& c, const FitResult& r) {
  const test::UnitProblem u = test::in_units(c.A, c.B, r.X);
  const double residual = (u.a.transpose() * (u.a * u.x - u.b)).norm();
  EXPECT_LE(residual, backward_tolerance(u)) << c.name;
}

// procrustes: X = X^T and A^T A X + X A^T A = A^T B + B^T A (thesis eq. 3.15), i.e. the symmetric
// part of A^T (A X - B) is zero.
void check_procrustes(const StressCase& c, const FitResult& r) {
  EXPECT_TRUE(r.X == r.X.transpose()) << c.name;
  const test::UnitProblem u = test::in_units(c.A, c.B, r.X);
  const MatrixXd g = u.a.transpose() * (u.a * u.x - u.b);
  EXPECT_LE((g + g.transpose()).norm(), 2.0 * backward_tolerance(u)) << c.name;
}

// tls: [X; -I] spans the n-dimensional subspace that minimizes ||[A B] W||_F over orthonormal
// W (thesis eq. 4.29-4.33): the minimum is the norm of the n smallest singular values. TLS is
// invariant only under a common scaling of A and B, so both are scaled by the same power of two.
// The computed span is off by about eps ||X|| (V22 is nearly singular when ||X|| is large),
// which the tolerance allows for.
void check_total_least_squares(const StressCase& c, const FitResult& r) {
  const Index n = c.A.cols();
  const int e = std::max(test::unit_exponent(c.A), test::unit_exponent(c.B));
  MatrixXd ab(c.A.rows(), 2 * n);
  ab << test::scaled_by_power_of_two(c.A, -e), test::scaled_by_power_of_two(c.B, -e);
  const VectorXd sigma = Eigen::JacobiSVD<MatrixXd>(ab).singularValues();
  const double minimum = sigma.size() > n ? sigma.tail(sigma.size() - n).squaredNorm() : 0.0;
  MatrixXd Z(2 * n, n);
  Z << r.X, -MatrixXd::Identity(n, n);
  const MatrixXd W = Eigen::HouseholderQR<MatrixXd>(Z).householderQ() * MatrixXd::Identity(2 * n, n);
  const double achieved = (ab * W).squaredNorm();
  const double x_norm = r.X.norm();
  const double tolerance =
      kForwardFactor * static_cast<double>(n) * kEps * sigma(0) * sigma(0) * (1.0 + x_norm * x_norm);
  EXPECT_LE(achieved - minimum, tolerance) << c.name;
}

// spde: X symmetric positive semidefinite with X A^T A X = B^T B (Chen & McInroy, Theorem III.3;
// for B of rank r < n, Corollary III.7, up to the rank cut-off), to cond(A) eps.
void check_spde(const StressCase& c, const FitResult& r) {
  EXPECT_TRUE(r.X == r.X.transpose()) << c.name;
  EXPECT_TRUE(r.diagnostics.positive_semidefinite) << c.name;
  const test::UnitProblem u = test::in_units(c.A, c.B, r.X);
  const MatrixXd ax = u.a * u.x;
  const double residual = (ax.transpose() * ax - u.b.transpose() * u.b).norm();
  const double cond = r.diagnostics.cond_a;
  const double scale = u.a.norm() * u.x.norm() * (u.a.norm() * u.x.norm() + u.b.norm());
  const double representation = 2.0 * u.a.norm() * u.x.norm() * u.representation_error();
  EXPECT_LE(residual, kForwardFactor * static_cast<double>(c.A.cols()) * kEps * cond * scale + representation)
      << c.name;
}

void check_case(const StressCase& c) {
  const Index n = c.A.cols();
  std::vector<FitResult> results;
  ASSERT_NO_THROW(results = fit_all(c.A, c.B)) << c.name;
  const FitResult* tls = nullptr;
  for (const FitResult& r : results) {
    const std::string where = std::string(to_string(r.method)) + ": " + c.name;
    expect_no_nan_in_diagnostics(r, where);
    if (!r.ok()) {
      EXPECT_FALSE(r.message.empty()) << where;
      EXPECT_EQ(r.X.size(), 0) << where;
      continue;
    }
    ASSERT_EQ(r.X.rows(), n) << where;
    ASSERT_EQ(r.X.cols(), n) << where;
    ASSERT_TRUE(test::all_finite(r.X)) << where;
    switch (r.method) {
      case Method::LeastSquares:
        check_least_squares(c, r);
        break;
      case Method::SymmetricProcrustes:
        check_procrustes(c, r);
        break;
      case Method::TotalLeastSquares:
        tls = &r;
        check_total_least_squares(c, r);
        break;
      case Method::TotalLeastSquaresSymmetric:
        ASSERT_NE(tls, nullptr) << where;
        EXPECT_TRUE(r.X == r.X.transpose()) << where;
        EXPECT_TRUE(r.X.isApprox(0.5 * (tls->X + tls->X.transpose()), 4 * kEps) || r.X.norm() == 0.0) << where;
        break;
      case Method::TotalLeastSquaresPsd:
        ASSERT_NE(tls, nullptr) << where;
        EXPECT_TRUE(r.X == r.X.transpose()) << where;
        EXPECT_TRUE(r.diagnostics.positive_semidefinite) << where;
        break;
      case Method::Spde:
        check_spde(c, r);
        break;
      case Method::SpdTotalLeastSquares:
        EXPECT_TRUE(r.X == r.X.transpose()) << where;
        EXPECT_TRUE(r.diagnostics.positive_semidefinite) << where;
        EXPECT_TRUE(r.diagnostics.iterations.has_value()) << where;
        break;
      case Method::PsdLeastSquares:
        EXPECT_TRUE(r.X == r.X.transpose()) << where;
        EXPECT_TRUE(r.diagnostics.positive_semidefinite) << where;
        ASSERT_TRUE(r.diagnostics.certificate.has_value()) << where;
        break;
      case Method::Auto:
        ADD_FAILURE() << "fit_all does not run auto: " << where;
        break;
    }
  }
  // The contract of spde.hpp: A rank-deficient is a failure, never an answer. Otherwise the one
  // failure is an estimate beyond the double range (B huge against A: every method says so).
  const FitResult& spde = *std::find_if(results.begin(), results.end(),
                                         [](const FitResult& r) { return r.method == Method::Spde; });
  if (spde.diagnostics.rank_a < n) {
    EXPECT_FALSE(spde.ok()) << c.name;
  } else if (!spde.ok()) {
    EXPECT_NE(spde.message.find("overflows the range"), std::string::npos) << c.name << ": " << spde.message;
  }
}

class EstimatorStress : public ::testing::TestWithParam<Hostility> {};

TEST_P(EstimatorStress, EveryEstimatorAnswersFinitelyOrFailsClearly) {
  const Hostility hostility = GetParam();
  Generator g(1000 + static_cast<unsigned>(hostility));
  for (Index n = 1; n <= 20; ++n) {
    for (const Index m : {n, 2 * n + 3}) {
      const double cond = std::pow(10.0, g.uniform(0, 12));
      const StressCase c = test::make_stress_case(g, m, n, cond, hostility, pick_scale(g), pick_scale(g));
      SCOPED_TRACE(c.name);
      check_case(c);
    }
  }
}

INSTANTIATE_TEST_SUITE_P(Hostilities, EstimatorStress, ::testing::ValuesIn(test::all_hostilities()),
                         [](const ::testing::TestParamInfo<Hostility>& info) {
                           std::string name = test::to_string(info.param);
                           for (char& ch : name) {
                             if (!std::isalnum(static_cast<unsigned char>(ch))) ch = '_';
                           }
                           return name;
                         });

// The corners: every pair of extreme scales at every decade of condition number up to 1e12.
TEST(EstimatorStressCorners, ExtremeScalesAtEveryConditionNumber) {
  Generator g(2024);
  for (double scale_a : kScales) {
    for (double scale_b : kScales) {
      for (int decade = 0; decade <= 12; decade += 3) {
        const StressCase c =
            test::make_stress_case(g, 9, 4, std::pow(10.0, decade), Hostility::kNone, scale_a, scale_b);
        SCOPED_TRACE(c.name);
        check_case(c);
      }
    }
  }
}

}  // namespace
}  // namespace spdfit
