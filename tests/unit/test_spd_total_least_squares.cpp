// spd-tls: the TLS criterion f(X) = tr((AX - B)^T (AX - B) (r^2 I + X^2)^-1) minimized over the
// SPD matrices, checked against references computed here from A and B directly: finite
// differences of f, a separate gradient-descent optimizer, closed forms (n = 1, TLS already
// symmetric positive definite, noise-free data) and the criterion's invariances.
#include <gtest/gtest.h>

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <Eigen/LU>
#include <Eigen/SVD>
#include <cmath>
#include <stdexcept>

#include "spdfit/spd_total_least_squares.hpp"
#include "spdfit/spde.hpp"
#include "spdfit/total_least_squares.hpp"
#include "test_support.hpp"

namespace spdfit {
namespace {

using test::Generator;
using test::kEps;
using test::relative_error;

// The criterion from the data, by its definition (not from the factor the library uses).
double criterion(const MatrixXd& A, const MatrixXd& B, const MatrixXd& X, double r = 1.0) {
  const Index n = X.rows();
  const MatrixXd G = A * X - B;
  const MatrixXd W = r * r * MatrixXd::Identity(n, n) + X * X;
  return (G.transpose() * G * W.inverse()).trace();
}

MatrixXd sqrtm(const MatrixXd& X) {
  Eigen::SelfAdjointEigenSolver<MatrixXd> eig(X);
  return eig.eigenvectors() * eig.eigenvalues().cwiseSqrt().asDiagonal() * eig.eigenvectors().transpose();
}

// The derivative of f along X^1/2 S X^1/2 by central differences: <X^1/2 grad f X^1/2, S>.
double riemannian_derivative(const MatrixXd& A, const MatrixXd& B, const MatrixXd& X, const MatrixXd& S,
                             double r = 1.0) {
  // Fourth-order central differences: truncation ~h^4 f^(5), rounding ~eps ||A X|| ||A X - B|| / h
  // (f cancels in A X - B): both below 1e-9 f on the data below.
  const double h = 1e-3;
  const MatrixXd D = sqrtm(X) * S * sqrtm(X);
  auto at = [&](double t) { return criterion(A, B, X + t * D, r); };
  return (at(-2 * h) - 8 * at(-h) + 8 * at(h) - at(2 * h)) / (12 * h);
}

struct Problem {
  MatrixXd A, B, X0;
};

// Errors-in-variables data: A = A0 + noise, B = A0 X0 + noise, X0 SPD.
Problem noisy(Generator& g, Index m, Index n, double noise, double cond = 10.0) {
  Problem p;
  p.X0 = g.spd(n, cond);
  const MatrixXd A0 = 3.0 * g.gaussian(m, n);
  p.A = A0 + noise * g.gaussian(m, n);
  p.B = A0 * p.X0 + noise * g.gaussian(m, n);
  return p;
}

bool is_spd(const MatrixXd& X) {
  return X == X.transpose() && Eigen::LLT<MatrixXd>(X).info() == Eigen::Success;
}

TEST(SpdTotalLeastSquares, RiemannianGradientVanishesAndTheResultIsSpd) {
  Generator g(140);
  for (Index n : {1, 2, 3, 6}) {
    for (double noise : {0.1, 1.0}) {
      const Problem p = noisy(g, 2 * n + 3, n, noise);
      const FitResult r = spd_total_least_squares(p.A, p.B);
      ASSERT_TRUE(r.ok()) << r.message;
      ASSERT_TRUE(is_spd(r.X)) << "n = " << n;
      EXPECT_TRUE(r.diagnostics.positive_definite);
      EXPECT_EQ(r.method, Method::SpdTotalLeastSquares);
      EXPECT_TRUE(r.diagnostics.converged.value_or(false));
      EXPECT_GT(r.diagnostics.iterations.value_or(-1), 0);
      const double f = criterion(p.A, p.B, r.X);
      EXPECT_LE(*r.diagnostics.gradient_norm, 1e-10 * f);
      for (int trial = 0; trial < 4; ++trial) {
        const MatrixXd S = Generator::symmetrize(g.gaussian(n, n)).normalized();
        // Finite differences resolve about 1e-9 f (see riemannian_derivative); the start
        // (SPDE) has derivatives of order f.
        EXPECT_LE(std::abs(riemannian_derivative(p.A, p.B, r.X, S)), 1e-7 * f) << "n = " << n;
      }
    }
  }
}

// A separate optimizer: gradient descent with backtracking on X = L L^T (L lower triangular),
// with finite-difference gradients, run long.
MatrixXd descend(const MatrixXd& A, const MatrixXd& B, const MatrixXd& start, double r, int steps) {
  const Index n = start.rows();
  MatrixXd L = Eigen::LLT<MatrixXd>(start).matrixL();
  auto f_of = [&](const MatrixXd& Lc) { return criterion(A, B, Lc * Lc.transpose(), r); };
  double f = f_of(L), t = 1e-2;
  for (int it = 0; it < steps; ++it) {
    MatrixXd grad = MatrixXd::Zero(n, n);
    for (Index j = 0; j < n; ++j)
      for (Index i = j; i < n; ++i) {
        const double h = 1e-7 * std::max(1.0, std::abs(L(i, j)));
        MatrixXd Lp = L, Lm = L;
        Lp(i, j) += h;
        Lm(i, j) -= h;
        grad(i, j) = (f_of(Lp) - f_of(Lm)) / (2 * h);
      }
    for (t *= 2; t > 1e-20; t *= 0.5) {
      const MatrixXd trial = L - t * grad;
      const double ft = f_of(trial);
      if (ft <= f - 1e-4 * t * grad.squaredNorm()) {
        L = trial;
        f = ft;
        break;
      }
    }
  }
  return L * L.transpose();
}

TEST(SpdTotalLeastSquares, NoWorseThanASeparateOptimizerFromTheSameStart) {
  Generator g(141);
  for (Index n : {2, 3}) {
    for (double r : {1.0, 0.5}) {
      const Problem p = noisy(g, 3 * n + 2, n, 0.5);
      const FitResult start = spde(p.A, p.B);
      ASSERT_TRUE(start.ok());
      const MatrixXd X_ref = descend(p.A, p.B, start.X, r, 4000);
      FitOptions options;
      options.noise_ratio = r;
      const FitResult result = spd_total_least_squares(p.A, p.B, options);
      ASSERT_TRUE(result.ok()) << result.message;
      const double f = criterion(p.A, p.B, result.X, r), f_ref = criterion(p.A, p.B, X_ref, r);
      EXPECT_LE(f, f_ref * (1 + 1e-10)) << "n = " << n << ", r = " << r;
      // The reference reached the same minimizer (to its slower convergence).
      EXPECT_LT(relative_error(X_ref, result.X), 1e-4) << "n = " << n << ", r = " << r;
    }
  }
}

TEST(SpdTotalLeastSquares, ReturnsTheTruthOnNoiseFreeData) {
  Generator g(142);
  for (Index n : {1, 2, 6}) {
    const MatrixXd X0 = g.spd(n, 100.0);
    const MatrixXd A = g.gaussian(3 * n, n);
    const FitResult r = spd_total_least_squares(A, A * X0);
    ASSERT_TRUE(r.ok()) << r.message;
    EXPECT_TRUE(r.diagnostics.converged.value_or(false));
    // cond(A) cond(X0) eps: the truth to rounding.
    EXPECT_LT(relative_error(r.X, X0), 1e4 * kEps) << "n = " << n;
  }
}

TEST(SpdTotalLeastSquares, EqualsTotalLeastSquaresWhenThatIsSymmetricPositiveDefinite) {
  // [A B] = U diag(s) V^T with the n smallest singular values' right vectors spanning
  // [X0; -I]: then X_TLS = -V12 V22^-1 = X0 (SPD), the unconstrained minimizer of f.
  Generator g(143);
  for (Index n : {1, 3, 5}) {
    const Index m = 4 * n;
    const MatrixXd X0 = g.spd(n, 5.0);
    MatrixXd N(2 * n, n);
    N << X0, -MatrixXd::Identity(n, n);
    Eigen::HouseholderQR<MatrixXd> qr(N);
    const MatrixXd V = qr.householderQ() * MatrixXd::Identity(2 * n, 2 * n);  // [V1 V2], V2 spans N
    MatrixXd Vreordered(2 * n, 2 * n);
    Vreordered << V.rightCols(n), V.leftCols(n);
    Eigen::VectorXd s(2 * n);
    for (Index i = 0; i < 2 * n; ++i) s(i) = i < n ? 10.0 - i : 1.0 - 0.1 * (i - n);
    const MatrixXd AB = g.orthonormal(m, 2 * n) * s.asDiagonal() * Vreordered.transpose();
    const MatrixXd A = AB.leftCols(n), B = AB.rightCols(n);
    const FitResult tls = total_least_squares(A, B);
    ASSERT_TRUE(tls.ok());
    ASSERT_LT(relative_error(tls.X, X0), 1e-12);
    const FitResult r = spd_total_least_squares(A, B);
    ASSERT_TRUE(r.ok()) << r.message;
    EXPECT_LT(relative_error(r.X, X0), 1e-10) << "n = " << n;
    EXPECT_LT(relative_error(r.X, tls.X), 1e-10) << "n = " << n;
  }
}

TEST(SpdTotalLeastSquares, IsInvariantToScaling) {
  Generator g(144);
  const Problem p = noisy(g, 12, 4, 0.5);
  const FitResult base = spd_total_least_squares(p.A, p.B);
  ASSERT_TRUE(base.ok());
  // Common scaling: the same X.
  for (double c : {1e150, 1e-150}) {
    const FitResult r = spd_total_least_squares(c * p.A, c * p.B);
    ASSERT_TRUE(r.ok()) << r.message;
    EXPECT_LT(relative_error(r.X, base.X), 1e-12) << c;
    EXPECT_NEAR(*r.diagnostics.gradient_norm / (c * c), *base.diagnostics.gradient_norm,
                1e-10 * criterion(p.A, p.B, base.X));
  }
  // A by alpha, B by beta: X scales by beta / alpha, and the noise ratio by beta / alpha too
  // (f(X; alpha A, beta B, r beta / alpha) = beta^2 f(X alpha / beta; A, B, r)).
  for (auto [alpha, beta] : {std::pair{1e150, 1e-150}, std::pair{1e-150, 1e150}, std::pair{3.0, 1e100}}) {
    FitOptions options;
    options.noise_ratio = beta / alpha;
    const FitResult r = spd_total_least_squares(alpha * p.A, beta * p.B, options);
    ASSERT_TRUE(r.ok()) << r.message;
    EXPECT_LT(relative_error(r.X * (alpha / beta), base.X), 1e-12) << alpha << " " << beta;
  }
}

TEST(SpdTotalLeastSquares, NoiseRatioRescalesB) {
  Generator g(145);
  const Problem p = noisy(g, 15, 3, 0.7);
  for (double r : {3.0, 0.2}) {
    FitOptions options;
    options.noise_ratio = r;
    const FitResult with_r = spd_total_least_squares(p.A, p.B, options);
    const FitResult rescaled = spd_total_least_squares(p.A, p.B / r);
    ASSERT_TRUE(with_r.ok() && rescaled.ok());
    EXPECT_LT(relative_error(with_r.X, r * rescaled.X), 1e-12) << r;
    // And it is the minimizer of f_r, not of f_1.
    EXPECT_LT(criterion(p.A, p.B, with_r.X, r), criterion(p.A, p.B, rescaled.X, r));
  }
}

// n = 1: f(x) = (x^2 Saa - 2 x Sab + Sbb) / (r^2 + x^2), minimized at the positive root of f'.
TEST(SpdTotalLeastSquares, OneByOneClosedForm) {
  Generator g(146);
  for (double r : {1.0, 2.5}) {
    const MatrixXd a = g.gaussian(20, 1);
    const MatrixXd b = 0.8 * a + 0.4 * g.gaussian(20, 1);
    const double Saa = a.squaredNorm(), Sbb = b.squaredNorm(), Sab = a.col(0).dot(b.col(0));
    // d/dx: 2 [Sab x^2 + (r^2 Saa - Sbb) x - r^2 Sab] / (r^2 + x^2)^2 = 0, roots with product
    // -r^2: one positive root for Sab > 0, the minimizer.
    const double p = r * r * Saa - Sbb;
    // (-p + sqrt(p^2 + 4 r^2 Sab^2)) / (2 Sab), without its cancellation for p > 0.
    const double x = p > 0 ? 2 * r * r * Sab / (p + std::sqrt(p * p + 4 * r * r * Sab * Sab))
                           : (-p + std::sqrt(p * p + 4 * r * r * Sab * Sab)) / (2 * Sab);
    FitOptions options;
    options.noise_ratio = r;
    const FitResult result = spd_total_least_squares(a, b, options);
    ASSERT_TRUE(result.ok()) << result.message;
    // The stopping rule leaves |x f'(x)| <= 1e-10 f, an error of 1e-10 f / (x^2 f''), about
    // 1e-12 relative here.
    EXPECT_NEAR(result.X(0, 0), x, 1e-11 * x) << r;
    EXPECT_LE(criterion(a, b, result.X, r), criterion(a, b, MatrixXd::Constant(1, 1, x), r) * (1 + 1e-15));
  }
}

TEST(SpdTotalLeastSquares, InfimumOnTheBoundaryIsTheSemidefiniteLimitWithAWarning) {
  // n = 1 with b negatively correlated with a and |b| < |a|: f decreases to Sbb as x -> 0+.
  Generator g(147);
  const MatrixXd a = g.gaussian(20, 1);
  const MatrixXd b = -0.3 * a + 0.05 * g.gaussian(20, 1);
  ASSERT_LT(a.col(0).dot(b.col(0)), 0.0);
  // Start away from 0 (SPDE, positive by construction) and run to the boundary.
  const FitResult r = spd_total_least_squares(a, b);
  ASSERT_TRUE(r.ok()) << r.message;
  EXPECT_EQ(r.X(0, 0), 0.0);
  EXPECT_TRUE(r.diagnostics.positive_semidefinite);
  EXPECT_FALSE(r.diagnostics.positive_definite);
  ASSERT_FALSE(r.warnings.empty());
  EXPECT_NE(r.warnings.back().text.find("boundary"), std::string::npos);
}

TEST(SpdTotalLeastSquares, BoundaryFaceIsOptimalForN2) {
  // The truth diag(1, -0.5) is indefinite: the infimum over the SPD matrices is on the boundary,
  // a rank-1 X = u y u^T optimal on its face, and f increases into the interior along v (X v = 0).
  Generator g(150);
  const MatrixXd X_true = (MatrixXd(2, 2) << 1.0, 0.0, 0.0, -0.5).finished();
  const MatrixXd A0 = 3.0 * g.gaussian(40, 2);
  const MatrixXd A = A0 + 0.1 * g.gaussian(40, 2), B = A0 * X_true + 0.1 * g.gaussian(40, 2);
  const FitResult r = spd_total_least_squares(A, B);
  ASSERT_TRUE(r.ok()) << r.message;
  EXPECT_TRUE(r.diagnostics.converged.value_or(false));
  EXPECT_TRUE(r.diagnostics.positive_semidefinite);
  EXPECT_FALSE(r.diagnostics.positive_definite);
  ASSERT_FALSE(r.warnings.empty());
  EXPECT_NE(r.warnings.back().text.find("boundary"), std::string::npos);
  Eigen::SelfAdjointEigenSolver<MatrixXd> eig(r.X);
  const Eigen::VectorXd v = eig.eigenvectors().col(0), u = eig.eigenvectors().col(1);
  ASSERT_LT(std::abs(eig.eigenvalues()(0)), 1e-12 * eig.eigenvalues()(1));
  const double f = criterion(A, B, r.X), y = eig.eigenvalues()(1);
  // On the face: d/dt f((y e^t) u u^T) = 0 (fourth-order differences, as riemannian_derivative).
  const double h = 1e-3;
  auto on_face = [&](double t) { return criterion(A, B, y * std::exp(t) * u * u.transpose()); };
  const double slope = (on_face(-2 * h) - 8 * on_face(-h) + 8 * on_face(h) - on_face(2 * h)) / (12 * h);
  EXPECT_LE(std::abs(slope), 1e-8 * f);
  // Into the interior: f grows (the boundary is the infimum, not an artefact).
  for (double t : {1e-6, 1e-3, 1e-1}) EXPECT_GT(criterion(A, B, r.X + t * y * v * v.transpose()), f) << t;
}

TEST(SpdTotalLeastSquares, FailsWhenTheInfimumIsAtInfinity) {
  // n = 1, b ~ -3 a: f(0) = Sbb ~ 9 Saa, f(x) -> Saa as x -> infinity, decreasing on x > 0.
  Generator g(151);
  const MatrixXd a = g.gaussian(20, 1);
  const MatrixXd b = -3.0 * a + 0.05 * g.gaussian(20, 1);
  const FitResult r = spd_total_least_squares(a, b);
  EXPECT_EQ(r.status, Status::NumericalFailure);
  EXPECT_NE(r.message.find("no minimizer"), std::string::npos) << r.message;
}

TEST(SpdTotalLeastSquares, IterationLimitReturnsTheBestIterateWithAWarning) {
  Generator g(148);
  const Problem p = noisy(g, 12, 6, 1.0);
  FitOptions options;
  options.max_iterations = 1;
  const FitResult r = spd_total_least_squares(p.A, p.B, options);
  ASSERT_TRUE(r.ok()) << r.message;
  EXPECT_FALSE(r.diagnostics.converged.value_or(true));
  EXPECT_EQ(r.diagnostics.iterations.value_or(-1), 1);
  EXPECT_TRUE(is_spd(r.X));
  ASSERT_FALSE(r.warnings.empty());
  EXPECT_NE(r.warnings.back().text.find("did not converge"), std::string::npos);
  const FitResult start = spde(p.A, p.B);
  EXPECT_LE(criterion(p.A, p.B, r.X), criterion(p.A, p.B, start.X));
}

TEST(SpdTotalLeastSquares, RankDeficientAStartsFromTlsOrFailsWithAMessage) {
  Generator g(149);
  // A of rank 2 < 3 (its third column a combination of the others): SPDE is undefined.
  Problem p = noisy(g, 12, 3, 0.3);
  p.A.col(2) = p.A.col(0) + p.A.col(1);
  const FitResult r = spd_total_least_squares(p.A, p.B);
  if (r.ok()) {
    EXPECT_TRUE(r.diagnostics.positive_semidefinite);
    if (r.diagnostics.converged.value_or(false)) {
      for (int trial = 0; trial < 3; ++trial) {
        const MatrixXd S = Generator::symmetrize(g.gaussian(3, 3)).normalized();
        EXPECT_LE(std::abs(riemannian_derivative(p.A, p.B, r.X, S)), 1e-7 * criterion(p.A, p.B, r.X));
      }
    }
  } else {
    EXPECT_EQ(r.status, Status::NumericalFailure);
  }
  // A = 0 and B = 0: no positive definite start at all.
  const FitResult none = spd_total_least_squares(MatrixXd::Zero(6, 2), MatrixXd::Zero(6, 2));
  EXPECT_EQ(none.status, Status::NumericalFailure);
  EXPECT_NE(none.message.find("no positive definite starting point"), std::string::npos) << none.message;
}

TEST(SpdTotalLeastSquares, RejectsInvalidOptions) {
  const MatrixXd A = MatrixXd::Identity(3, 2), B = MatrixXd::Identity(3, 2);
  for (double r : {0.0, -1.0, std::nan(""), std::numeric_limits<double>::infinity()}) {
    FitOptions options;
    options.noise_ratio = r;
    EXPECT_FALSE(options.is_valid());
    EXPECT_THROW(spd_total_least_squares(A, B, options), std::invalid_argument);
  }
  FitOptions options;
  options.max_iterations = -1;
  std::string error;
  EXPECT_FALSE(options.is_valid(&error));
  EXPECT_FALSE(error.empty());
  EXPECT_THROW(spd_total_least_squares(A, B, options), std::invalid_argument);
  EXPECT_THROW(spd_total_least_squares(Reduction{}), std::invalid_argument);
}

}  // namespace
}  // namespace spdfit
