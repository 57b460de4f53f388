// The estimators with a noise model (FitOptions::noise), against references computed here from A
// and B directly: the likelihood criterion row by row, its Riemannian gradient by finite
// differences, a separate optimizer, equal noise against spd-tls without a model, Sigma_A = 0
// against the KKT conditions of weighted least squares over the semidefinite cone, generalized TLS
// against its closed form (whitening with Cholesky factors, then TLS by a full SVD of the m rows),
// mixed LS-TLS's normal equations, and the invariances under units and coordinates.
#include <gtest/gtest.h>

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <Eigen/LU>
#include <Eigen/SVD>
#include <cmath>
#include <stdexcept>
#include <string>

#include "spdfit/fit.hpp"
#include "spdfit/noise_model.hpp"
#include "spdfit/psd_least_squares.hpp"
#include "spdfit/spd_total_least_squares.hpp"
#include "spdfit/symmetric_procrustes.hpp"
#include "spdfit/total_least_squares.hpp"
#include "likelihood_reference.hpp"
#include "test_support.hpp"

namespace spdfit {
namespace {

using Eigen::Index;
using Eigen::MatrixXd;
using Eigen::VectorXd;
using test::Generator;
using test::relative_error;
using test::likelihood_criterion;

MatrixXd sqrtm(const MatrixXd& X) {
  Eigen::SelfAdjointEigenSolver<MatrixXd> eig(X);
  return eig.eigenvectors() * eig.eigenvalues().cwiseSqrt().asDiagonal() * eig.eigenvectors().transpose();
}

// Errors-in-variables data with per-column noise: A = A0 + E, B = A0 X0 + F, E's columns with
// standard deviations std_a, F's std_b.
struct Problem {
  MatrixXd A, B, X0, Sa, Sb;
  VectorXd std_a, std_b;
};

Problem noisy(Generator& g, Index m, const VectorXd& std_a, const VectorXd& std_b, double cond = 10.0) {
  const Index n = std_a.size();
  Problem p;
  p.X0 = g.spd(n, cond);
  const MatrixXd A0 = 3.0 * g.gaussian(m, n);
  p.A = A0 + g.gaussian(m, n) * std_a.asDiagonal();
  p.B = A0 * p.X0 + g.gaussian(m, n) * std_b.asDiagonal();
  p.std_a = std_a;
  p.std_b = std_b;
  p.Sa = std_a.cwiseAbs2().asDiagonal();
  p.Sb = std_b.cwiseAbs2().asDiagonal();
  return p;
}

FitOptions with_noise(const NoiseModel& model) {
  FitOptions options;
  options.noise = model;
  return options;
}

FitOptions with_std(const Problem& p) { return with_noise(NoiseModel::from_std(p.std_a, p.std_b)); }

VectorXd values(std::initializer_list<double> list) {
  VectorXd v(static_cast<Index>(list.size()));
  Index i = 0;
  for (double x : list) v(i++) = x;
  return v;
}

// The per-channel noise of docs/guide.md's noise-model table (6 columns), and a 3-column version.
const VectorXd kStdA6 = values({0.2, 0.4, 0.8, 0.2, 0.4, 0.8});
const VectorXd kStdB6 = values({3.0, 1.0, 0.3, 3.0, 1.0, 0.3});
const VectorXd kStdA3 = values({0.2, 0.8, 0.4});
const VectorXd kStdB3 = values({3.0, 0.3, 1.0});

bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

// ---- the maximum-likelihood estimate (spd-tls with a noise model) ------------------------------

TEST(MaximumLikelihood, RiemannianGradientVanishesAndTheResultIsSpd) {
  Generator g(400);
  for (const auto& [std_a, std_b] : {std::pair{kStdA3, kStdB3}, std::pair{kStdA6, kStdB6}}) {
    for (Index m : {40, 400}) {
      const Problem p = noisy(g, m, std_a, std_b);
      const FitResult r = spd_total_least_squares(p.A, p.B, with_std(p));
      ASSERT_TRUE(r.ok()) << r.message;
      ASSERT_TRUE(r.diagnostics.positive_definite);
      EXPECT_TRUE(r.diagnostics.converged.value_or(false));
      ASSERT_TRUE(r.diagnostics.noise_model);
      EXPECT_EQ(r.diagnostics.noise_model->source(), NoiseSource::Std);
      const double f = likelihood_criterion(p.A, p.B, r.X, p.Sa, p.Sb);
      EXPECT_LE(*r.diagnostics.gradient_norm, 1e-10 * f);
      // <X^1/2 grad f X^1/2, S> by fourth-order central differences along X^1/2 S X^1/2: they
      // resolve about 1e-9 f here; at the start (SPDE) the derivatives are of order f.
      const MatrixXd root = sqrtm(r.X);
      const Index n = r.X.rows();
      for (int trial = 0; trial < 4; ++trial) {
        const MatrixXd S = Generator::symmetrize(g.gaussian(n, n)).normalized();
        const MatrixXd D = root * S * root;
        const double h = 1e-3;
        auto at = [&](double t) { return likelihood_criterion(p.A, p.B, r.X + t * D, p.Sa, p.Sb); };
        const double slope = (at(-2 * h) - 8 * at(-h) + 8 * at(h) - at(2 * h)) / (12 * h);
        EXPECT_LE(std::abs(slope), 1e-7 * f) << "n = " << n << ", m = " << m;
      }
      // No perturbation lowers it.
      for (int trial = 0; trial < 6; ++trial) {
        const MatrixXd S = Generator::symmetrize(g.gaussian(n, n)).normalized();
        for (double t : {1e-4, 1e-2, 1e-1}) {
          const MatrixXd X = r.X + t * r.X.norm() * S;
          if (Eigen::LLT<MatrixXd>(X).info() != Eigen::Success) continue;
          EXPECT_GE(likelihood_criterion(p.A, p.B, X, p.Sa, p.Sb), f * (1 - 1e-12));
        }
      }
    }
  }
}

// A separate optimizer: gradient descent with backtracking on X = L L^T with finite-difference
// gradients of the row-by-row criterion, run long from the same start (SPDE).
MatrixXd descend(const Problem& p, const MatrixXd& start, int steps) {
  const Index n = start.rows();
  MatrixXd L = Eigen::LLT<MatrixXd>(start).matrixL();
  auto f_of = [&](const MatrixXd& Lc) { return likelihood_criterion(p.A, p.B, Lc * Lc.transpose(), p.Sa, p.Sb); };
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

TEST(MaximumLikelihood, NoWorseThanASeparateOptimizer) {
  Generator g(401);
  for (Index n : {2, 3}) {
    const Problem p = noisy(g, 30, kStdA3.head(n), kStdB3.head(n));
    const FitResult start = fit(p.A, p.B, Method::Spde);
    ASSERT_TRUE(start.ok());
    const MatrixXd X_ref = descend(p, start.X, 3000);
    const FitResult r = spd_total_least_squares(p.A, p.B, with_std(p));
    ASSERT_TRUE(r.ok()) << r.message;
    const double f = likelihood_criterion(p.A, p.B, r.X, p.Sa, p.Sb);
    const double f_ref = likelihood_criterion(p.A, p.B, X_ref, p.Sa, p.Sb);
    EXPECT_LE(f, f_ref * (1 + 1e-10)) << "n = " << n;
    EXPECT_LT(relative_error(X_ref, r.X), 1e-4) << "n = " << n;
  }
}

// Sigma_A = s^2 I and Sigma_B = s^2 r^2 I: the criterion is the TLS criterion over s^2, so the
// estimate is spd-tls's with noise_ratio r, computed by the other Newton method (spd_tls_kernel).
// Both stop at ||X^1/2 grad f X^1/2|| <= 1e-10 f, which leaves X within about 1e-10 cond of the
// minimizer: 1e-8 relative is the tests' tolerance for spd-tls.
TEST(MaximumLikelihood, EqualNoiseIsSpdTlsWithTheNoiseRatio) {
  Generator g(402);
  for (double r : {1.0, 2.5}) {
    for (Index n : {1, 3, 6}) {
      const double s = 0.7;
      const Problem p = noisy(g, 60, VectorXd::Constant(n, s), VectorXd::Constant(n, s * r));
      FitOptions ratio;
      ratio.noise_ratio = r;
      const FitResult plain = spd_total_least_squares(p.A, p.B, ratio);
      const FitResult ml = spd_total_least_squares(p.A, p.B, with_noise(NoiseModel::from_std(s, s * r)));
      ASSERT_TRUE(plain.ok() && ml.ok()) << plain.message << ml.message;
      EXPECT_LT(relative_error(ml.X, plain.X), 1e-8) << "n = " << n << ", r = " << r;
    }
  }
}

// KKT conditions of min sum_i r_i^T Sigma_B^-1 r_i / 2 over X >= 0, computed here: X >= 0,
// S = sym(A^T (A X - B) Sigma_B^-1) >= 0, <X, S> = 0 (each relative to the sizes of its terms).
void expect_weighted_kkt(const MatrixXd& A, const MatrixXd& B, const MatrixXd& Sb, const MatrixXd& X, double floor,
                         double tolerance, const std::string& what) {
  const MatrixXd Sb_inv = Sb.inverse();
  const MatrixXd G = A.transpose() * (A * X - B) * Sb_inv;
  const MatrixXd S = 0.5 * (G + G.transpose());
  const double scale = (A.transpose() * A * X * Sb_inv).norm() + (A.transpose() * B * Sb_inv).norm();
  MatrixXd Y = X;
  Y.diagonal().array() -= floor;
  const VectorXd wy = Eigen::SelfAdjointEigenSolver<MatrixXd>(Y).eigenvalues();
  const VectorXd ws = Eigen::SelfAdjointEigenSolver<MatrixXd>(S).eigenvalues();
  EXPECT_GE(wy(0), -tolerance * X.norm()) << what;
  EXPECT_GE(ws(0), -tolerance * scale) << what;
  EXPECT_LE(std::abs(Y.cwiseProduct(S).sum()), tolerance * scale * X.norm()) << what;
}

// Sigma_A = 0: the criterion is sum_i r_i^T Sigma_B^-1 r_i, weighted least squares over the SPD
// matrices: spd-tls ends at its minimizer (on the boundary when the truth is indefinite) and
// agrees with weighted psd-ls. Both interior and boundary cases.
TEST(MaximumLikelihood, ExactAIsWeightedLeastSquaresOverTheSemidefiniteCone) {
  Generator g(403);
  for (bool indefinite : {false, true}) {
    Problem p = noisy(g, 50, VectorXd::Zero(3), kStdB3);
    if (indefinite) {
      // A truth with a negative eigenvalue: the constrained minimizer is singular.
      const MatrixXd A0 = p.A;
      MatrixXd X0 = p.X0;
      X0 -= 1.5 * Eigen::SelfAdjointEigenSolver<MatrixXd>(X0).eigenvalues()(0) * MatrixXd::Identity(3, 3);
      X0(0, 0) -= 4.0;
      p.B = A0 * X0 + g.gaussian(50, 3) * kStdB3.asDiagonal();
    }
    const FitOptions options = with_noise(NoiseModel::from_std(VectorXd::Zero(3), kStdB3));
    const FitResult ml = spd_total_least_squares(p.A, p.B, options);
    const FitResult psd = psd_least_squares(p.A, p.B, options);
    ASSERT_TRUE(ml.ok() && psd.ok()) << ml.message << psd.message;
    EXPECT_TRUE(psd.diagnostics.converged.value_or(false));
    EXPECT_TRUE(ml.diagnostics.converged.value_or(false));
    // Newton's boundary detection leaves rounding-level eigenvalues: 1e-9 of the data's scale.
    expect_weighted_kkt(p.A, p.B, p.Sb, ml.X, 0.0, 1e-9, indefinite ? "spd-tls, boundary" : "spd-tls");
    expect_weighted_kkt(p.A, p.B, p.Sb, psd.X, 0.0, 1e-9, indefinite ? "psd-ls, boundary" : "psd-ls");
    EXPECT_LT(relative_error(ml.X, psd.X), 1e-7) << indefinite;
    if (indefinite) {
      EXPECT_LT(*ml.diagnostics.min_eigenvalue, 1e-9 * *ml.diagnostics.max_eigenvalue);
      ASSERT_FALSE(ml.warnings.empty());
      EXPECT_TRUE(contains(ml.warnings.back().text, "boundary"));
      // The certificate reports the weighted problem's conditions.
      ASSERT_TRUE(psd.diagnostics.certificate);
      EXPECT_GE(psd.diagnostics.certificate->dual_min_eig, -1e-9 * p.A.norm() / p.B.norm());
    }
  }
}

// Units: A in other units (a), B in other units (b), the noise converted alike; and a change of
// the coordinates' units A -> A D, B -> B D^-1 (D diagonal). To 1e-9 relative.
TEST(NoiseModelFits, FollowTheUnitsOfTheData) {
  Generator g(404);
  const Problem p = noisy(g, 200, kStdA6, kStdB6);
  const double a = 1e-3, b = 7.0;
  const VectorXd d = values({1.0, 1e-3, 10.0, 2.0, 0.5, 1e2});
  const MatrixXd D = d.asDiagonal(), D_inv = d.cwiseInverse().asDiagonal();
  for (Method method : {Method::SpdTotalLeastSquares, Method::PsdLeastSquares, Method::SymmetricProcrustes,
                        Method::TotalLeastSquares, Method::TotalLeastSquaresSymmetric, Method::Auto}) {
    const FitResult base = fit(p.A, p.B, method, with_std(p));
    const FitResult scaled = fit(a * p.A, b * p.B, method, with_noise(NoiseModel::from_std(a * p.std_a, b * p.std_b)));
    const FitResult moved =
        fit(p.A * D, p.B * D_inv, method,
            with_noise(NoiseModel::from_cov(D * p.Sa * D, D_inv * p.Sb * D_inv)));
    ASSERT_TRUE(base.ok() && scaled.ok() && moved.ok()) << to_string(method);
    EXPECT_LT(relative_error(scaled.X, (b / a) * base.X), 1e-9) << to_string(method);
    EXPECT_LT(relative_error(moved.X, D_inv * base.X * D_inv), 1e-9) << to_string(method);
    if (method == Method::Auto) {
      EXPECT_EQ(scaled.method, base.method);
      EXPECT_EQ(moved.method, base.method);
    }
  }
}

// ---- generalized total least squares -----------------------------------------------------------

// The closed form: with Cholesky factors Sigma = L L^T, TLS of [A L_A^-T, B L_B^-T] by a full SVD
// of the m x 2n matrix, X~ = -V12 V22^-1, and X = L_A^-T X~ L_B^T.
MatrixXd gtls_reference(const MatrixXd& A, const MatrixXd& B, const MatrixXd& Sa, const MatrixXd& Sb) {
  const Index n = A.cols(), d = B.cols();
  const MatrixXd La = Eigen::LLT<MatrixXd>(Sa).matrixL(), Lb = Eigen::LLT<MatrixXd>(Sb).matrixL();
  const MatrixXd Aw = A * La.transpose().inverse(), Bw = B * Lb.transpose().inverse();
  MatrixXd C(A.rows(), n + d);
  C << Aw, Bw;
  const Eigen::JacobiSVD<MatrixXd> svd(C, Eigen::ComputeFullV);
  const MatrixXd V12 = svd.matrixV().topRightCorner(n, d), V22 = svd.matrixV().bottomRightCorner(d, d);
  const MatrixXd Xw = -V12 * V22.inverse();
  return La.transpose().inverse() * Xw * Lb.transpose();
}

TEST(GeneralizedTls, IsWhiteningThenTls) {
  Generator g(405);
  const Problem p = noisy(g, 80, kStdA3, kStdB3);
  // Full covariances too: correlated noise.
  const MatrixXd Sa = p.Sa + 0.01 * MatrixXd::Ones(3, 3), Sb = p.Sb + 0.05 * MatrixXd::Ones(3, 3);
  for (const auto& [sa, sb] : {std::pair{p.Sa, p.Sb}, std::pair{Sa, Sb}}) {
    const MatrixXd X_ref = gtls_reference(p.A, p.B, sa, sb);
    const FitOptions options = with_noise(NoiseModel::from_cov(sa, sb));
    const FitResult tls = total_least_squares(p.A, p.B, options);
    ASSERT_TRUE(tls.ok()) << tls.message;
    EXPECT_LT(relative_error(tls.X, X_ref), 1e-10);
    const FitResult sym = total_least_squares_symmetric(p.A, p.B, options);
    EXPECT_LT(relative_error(sym.X, 0.5 * (X_ref + X_ref.transpose())), 1e-10);
    // The whitened correction norm: about sqrt(d (m - n)) = 15 when the model is right.
    ASSERT_TRUE(tls.diagnostics.tls_correction_norm);
    EXPECT_GT(*tls.diagnostics.tls_correction_norm, 10.0);
    EXPECT_LT(*tls.diagnostics.tls_correction_norm, 20.0);
  }
  // A non-square X (d != n): the same closed form.
  const MatrixXd B2 = p.B.leftCols(2);
  const MatrixXd Sb2 = p.Sb.topLeftCorner(2, 2);
  const FitResult wide = total_least_squares(p.A, B2, with_noise(NoiseModel::from_cov(p.Sa, Sb2)));
  ASSERT_TRUE(wide.ok()) << wide.message;
  EXPECT_LT(relative_error(wide.X, gtls_reference(p.A, B2, p.Sa, Sb2)), 1e-10);
}

// Mixed LS-TLS (exact columns of A): the exact column's normal equation a_1^T (A X - B) = 0 holds
// (the corrections lie orthogonal to it), and the estimate is the limit of generalized TLS as
// that column's noise goes to 0 (at std 1e-6 of the others' 0.2-0.8, within 1e-6).
TEST(GeneralizedTls, ExactColumnsAreMixedLeastSquaresAndTls) {
  Generator g(406);
  const VectorXd std_a = values({0.0, 0.8, 0.4});
  const Problem p = noisy(g, 80, std_a, kStdB3);
  const FitResult r = total_least_squares(p.A, p.B, with_std(p));
  ASSERT_TRUE(r.ok()) << r.message;
  const MatrixXd residual = p.A * r.X - p.B;
  EXPECT_LT((p.A.col(0).transpose() * residual).norm(), 1e-11 * p.A.col(0).norm() * residual.norm());
  VectorXd nearly = std_a;
  nearly(0) = 1e-6;
  const MatrixXd X_limit = gtls_reference(p.A, p.B, MatrixXd(nearly.cwiseAbs2().asDiagonal()), p.Sb);
  EXPECT_LT(relative_error(r.X, X_limit), 1e-6);
  // A exact altogether: least squares.
  const FitResult ls = total_least_squares(p.A, p.B, with_noise(NoiseModel::from_std(VectorXd::Zero(3), p.std_b)));
  ASSERT_TRUE(ls.ok());
  EXPECT_LT(relative_error(ls.X, fit(p.A, p.B, Method::LeastSquares).X), 1e-13);
  EXPECT_FALSE(ls.diagnostics.tls_sigma_n);
}

// ---- the methods that model noise in B only ------------------------------------------------------

TEST(WeightedLeastSquares, ProcrustesAndPsdLsAreWeightedByTheNoiseInB) {
  Generator g(407);
  const Problem p = noisy(g, 60, VectorXd::Zero(3), kStdB3);
  const FitOptions options = with_std(p);
  // Procrustes: the weighted normal equation sym(A^T (A X - B) Sigma_B^-1) = 0.
  const FitResult proc = symmetric_procrustes(p.A, p.B, options);
  ASSERT_TRUE(proc.ok());
  const MatrixXd G = p.A.transpose() * (p.A * proc.X - p.B) * p.Sb.inverse();
  EXPECT_LT((G + G.transpose()).norm(),
            1e-11 * (p.A.transpose() * p.B * p.Sb.inverse()).norm());
  EXPECT_TRUE(proc.warnings.empty());  // A exact: nothing ignored
  // psd-ls with a floor: X >= floor I with the weighted KKT conditions.
  FitOptions floored = options;
  floored.min_eig = 0.5;
  const FitResult psd = psd_least_squares(p.A, p.B, floored);
  ASSERT_TRUE(psd.ok());
  expect_weighted_kkt(p.A, p.B, p.Sb, psd.X, 0.5, 1e-9, "psd-ls with a floor");
  // Noise in A is ignored, with a warning naming the option.
  const FitResult noisy_a = psd_least_squares(p.A, p.B, with_noise(NoiseModel::from_std(kStdA3, kStdB3)));
  ASSERT_TRUE(noisy_a.ok());
  ASSERT_FALSE(noisy_a.warnings.empty());
  EXPECT_TRUE(contains(noisy_a.warnings.back().text, "`noise_std_a`")) << noisy_a.warnings.back().text;
  // ls is A^+ B whatever the weight (bit for bit), with the same warning when A has noise.
  const FitResult ls = fit(p.A, p.B, Method::LeastSquares, with_noise(NoiseModel::from_std(kStdA3, kStdB3)));
  EXPECT_EQ(ls.X, fit(p.A, p.B, Method::LeastSquares).X);
  ASSERT_FALSE(ls.warnings.empty());
  EXPECT_TRUE(contains(ls.warnings.back().text, "ls models noise in B only"));
}

// ---- what each method needs ------------------------------------------------------------------

TEST(NoiseModelFits, MethodsRefuseAModelTheyCannotUseNamingTheOptions) {
  Generator g(408);
  const Problem p = noisy(g, 30, kStdA3, kStdB3);
  auto message = [&](Method method, const NoiseModel& model) -> std::string {
    try {
      (void)fit(p.A, p.B, method, with_noise(model));
    } catch (const std::invalid_argument& e) {
      return e.what();
    }
    return "";
  };
  const std::string spde = message(Method::Spde, NoiseModel::from_std(kStdA3, kStdB3));
  EXPECT_TRUE(contains(spde, "auto") && contains(spde, "spd-tls")) << spde;
  const VectorXd exact_b = values({1.0, 0.0, 1.0});
  EXPECT_TRUE(contains(message(Method::PsdLeastSquares, NoiseModel::from_std(kStdA3, exact_b)), "`noise_std_b`"));
  EXPECT_TRUE(contains(message(Method::SymmetricProcrustes, NoiseModel::from_std(kStdA3, exact_b)), "singular"));
  EXPECT_TRUE(contains(message(Method::TotalLeastSquares, NoiseModel::from_std(kStdA3, exact_b)), "`noise_std_b`"));
  const std::string both = message(Method::SpdTotalLeastSquares, NoiseModel::from_std(values({0.0, 1.0, 1.0}), exact_b));
  EXPECT_TRUE(contains(both, "`noise_std_a`") && contains(both, "`noise_std_b`")) << both;
  EXPECT_TRUE(contains(message(Method::Auto, NoiseModel::from_std(values({0.0, 1.0, 1.0}), exact_b)), "singular"));
  // What they can use is taken: spd-tls with exact B columns (Sigma_A > 0), tls with A exact.
  EXPECT_EQ(message(Method::SpdTotalLeastSquares, NoiseModel::from_std(kStdA3, exact_b)), "");
  EXPECT_EQ(message(Method::TotalLeastSquares, NoiseModel::from_std(VectorXd::Zero(3), exact_b)), "");
  EXPECT_EQ(message(Method::LeastSquares, NoiseModel::from_std(VectorXd::Zero(3), VectorXd::Zero(3))), "");
  // A model of another size: named when the data are reduced.
  EXPECT_TRUE(contains(message(Method::SpdTotalLeastSquares, NoiseModel::from_std(kStdA6, kStdB6)),
                       "`noise_std_a` has 6 values but A has 3 columns"));
  // noise_ratio with a model.
  FitOptions both_given = with_noise(NoiseModel::from_std(1.0, 1.0));
  both_given.noise_ratio = 3.0;
  EXPECT_THROW((void)fit(p.A, p.B, Method::SpdTotalLeastSquares, both_given), std::invalid_argument);
}

TEST(NoiseModelFits, FitAllRunsWhatCannotUseTheModelWithoutItAndSaysSo) {
  Generator g(409);
  const Problem p = noisy(g, 100, kStdA3, kStdB3);
  const std::vector<FitResult> all = fit_all(p.A, p.B, with_std(p));
  ASSERT_EQ(all.size(), kAllMethods.size());
  for (const FitResult& r : all) {
    ASSERT_TRUE(r.ok()) << to_string(r.method) << ": " << r.message;
    if (r.method == Method::Spde) {
      EXPECT_FALSE(r.diagnostics.noise_model);
      ASSERT_FALSE(r.warnings.empty());
      EXPECT_TRUE(contains(r.warnings.back().text, "spde ran without the noise model")) << r.warnings.back().text;
      EXPECT_EQ(r.X, fit(p.A, p.B, Method::Spde).X);
    } else {
      EXPECT_TRUE(r.diagnostics.noise_model) << to_string(r.method);
      EXPECT_LT(relative_error(r.X, fit(p.A, p.B, r.method, with_std(p)).X), 1e-13) << to_string(r.method);
    }
  }
}

}  // namespace
}  // namespace spdfit
