// Internal: what the two Riemannian Newton methods of spd-tls share (spd_tls_kernel.cpp for equal
// noise, spd_ml_kernel.cpp for a noise model): the stopping rule, the trust region's constants,
// the cyclic Jacobi eigensolver that updates the iterates' eigenbases, and the packed coordinates
// of a symmetric step.
#pragma once

#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <Eigen/Jacobi>
#include <algorithm>
#include <cmath>
#include <utility>
#include <limits>

#include "numerics/linalg.hpp"

namespace spdfit::detail {

namespace trust_region {

inline constexpr double kEps = std::numeric_limits<double>::epsilon();
// The stopping rule: ||X^1/2 grad f X^1/2||_F <= 1e-10 f (scale-invariant).
inline constexpr double kGradientTolerance = 1e-10;
// The computed gradient carries a rounding error of about a few eps times the sizes of the terms
// it cancels (G = R11 X - R12 cancels to the residual): a target below it cannot be met, so the
// rule also accepts a gradient within kRoundingMultiple n eps of those sizes (noise-free data).
inline constexpr double kRoundingMultiple = 4.0;
// Start and iterates must be numerically positive definite: lambda_min > n eps lambda_max.
// Trust region on ||S||_F (S the step in X^1/2 exp(S) X^1/2): the initial and largest radius
// (a radius of 8 lets an eigenvalue change by e^8 in one step), the ratio of actual to
// predicted decrease below which a step is refused, and the radius at which progress stalls.
// Steps with ||S||_F <= kTaylorRadius use exp's Taylor polynomial of degree 2 (error ||S||^3 / 6).
inline constexpr double kTaylorRadius = 0.25;
inline constexpr double kInitialRadius = 1.0, kMaxRadius = 8.0, kAcceptRatio = 1e-4, kMinRadius = 1e-14;
// The infimum is on the boundary when an eigenvalue has fallen below kBoundaryRatio times the
// largest while the criterion still decreases along it (at the stopping rule such an
// eigenvalue is about 1e-10 f / (df/dlambda), far below this; an interior minimizer this
// ill-conditioned is kept unless zeroing the eigenvalue lowers f).
// "The largest" is the larger of lambda_max and the data's scale ||R12|| / ||R11|| (~||B|| / ||A||),
// so that n = 1 and X -> 0 are covered.
inline constexpr double kBoundaryRatio = 1e-6;
// The criterion has no minimizer when an eigenvalue exceeds kUnboundedRatio ||R12|| / sigma_min(R11)
// (~||B|| / sigma_min(A), a bound on any reasonable fit's ||X||) with f still decreasing along it.
inline constexpr double kUnboundedRatio = 1e6;
// The rounding error of the computed criterion, in units of n eps f.
inline constexpr double kCriterionRounding = 64.0;

// Packed index of the symmetric coordinate (i, j), i <= j.
inline Eigen::Index packed(Eigen::Index i, Eigen::Index j) {
  if (i > j) std::swap(i, j);
  return j * (j + 1) / 2 + i;
}

}  // namespace trust_region

// Cyclic Jacobi on the symmetric T, accumulating the rotations into Q: on return T is diagonal
// (the eigenvalues) and the input is Q_out diag Q_out^T in Q_in's coordinates. Few sweeps when T
// is nearly diagonal (the iterates' X in the previous eigenbasis, near convergence), and the
// eigenvalues of a positive definite T to high relative accuracy (Demmel & Veselic 1992) with
// the threshold |t_pq| <= eps sqrt(|t_pp t_qq|). False when it does not converge.
template <typename Matrix>
bool jacobi_eigen(Matrix& T, Matrix& Q) {
  constexpr int kMaxSweeps = 40;
  constexpr double kEps = std::numeric_limits<double>::epsilon();
  const Eigen::Index n = T.rows();
  for (int sweep = 0; sweep < kMaxSweeps; ++sweep) {
    bool rotated = false;
    for (Eigen::Index q = 1; q < n; ++q)
      for (Eigen::Index p = 0; p < q; ++p) {
        const double tpq = std::abs(T(p, q));
        if (tpq <= kEps * std::sqrt(std::abs(T(p, p) * T(q, q))) || tpq <= std::numeric_limits<double>::min()) {
          continue;
        }
        rotated = true;
        Eigen::JacobiRotation<double> J;
        J.makeJacobi(T, p, q);
        T.applyOnTheLeft(p, q, J.adjoint());
        T.applyOnTheRight(p, q, J);
        T(p, q) = T(q, p) = 0.0;
        Q.applyOnTheRight(p, q, J);
      }
    if (!rotated) return true;
  }
  return false;
}


namespace trust_region {

// The step s minimizing Newton's model f + <grad, s> + s^T H s / 2 within the trust region: the
// Newton step of H + mu I, with the Levenberg-Marquardt shift mu the smallest of 0, 1e-8 |H|,
// 1e-7 |H|, ... making it positive definite, cut back to the radius. False for a non-finite H.
// Sets `step` = |s| and `predicted`, the model's decrease. Hmu and llt are the caller's buffers.
template <typename PMatrix, typename PVector>
bool trust_region_step(const PMatrix& H, const PVector& grad, double gnorm, double radius, PMatrix& Hmu,
                       Eigen::LLT<PMatrix>& llt, PVector& s, double& step, double& predicted) {
  const double h_scale = std::max(H.diagonal().cwiseAbs().maxCoeff(), gnorm);
  double mu = 0.0;
  for (;;) {
    Hmu = H;
    Hmu.diagonal().array() += mu;
    llt.compute(Hmu);
    if (llt.info() == Eigen::Success && (llt.matrixLLT().diagonal().array() > 0.0).all()) break;
    mu = mu == 0.0 ? 1e-8 * h_scale : 10.0 * mu;
    if (!(mu < 1e30 * h_scale)) return false;
  }
  s = -llt.solve(grad);
  step = s.norm();
  if (step > radius) {
    s *= radius / step;
    step = radius;
  }
  predicted = -(grad.dot(s) + 0.5 * s.dot(H * s));
  return true;
}

// The step on the cone in the current eigenbasis: T = Lambda^1/2 Z Lambda^1/2 with Z = exp(S) =
// V exp(sigma) V^T for the symmetric S of the packed coordinates s (off-diagonal s_ij / sqrt 2),
// or for small steps its second-order Taylor polynomial I + S + S^2 / 2, positive definite for
// every S (1 + x + x^2/2 > 0) and agreeing with exp to third order, which keeps Newton's quadratic
// convergence. The trial X is Q T Q^T. False when the eigensolver fails.
template <typename Matrix, typename Vector, typename PVector>
bool cone_step(const Vector& sqrt_lambda, const PVector& s, double step, Matrix& T) {
  const Eigen::Index n = sqrt_lambda.size();
  const double root2 = std::sqrt(2.0);
  Matrix S(n, n), Z;
  for (Eigen::Index j = 0; j < n; ++j)
    for (Eigen::Index i = 0; i <= j; ++i) {
      const double v = i == j ? s(packed(i, j)) : s(packed(i, j)) / root2;
      S(i, j) = v;
      S(j, i) = v;
    }
  if (step <= kTaylorRadius) {
    Z.noalias() = 0.5 * S * S;
    Z += S;
    Z.diagonal().array() += 1.0;
  } else {
    T = S;
    Z = Matrix::Identity(n, n);  // V
    if (!jacobi_eigen(T, Z)) return false;
    Z = Z * T.diagonal().array().exp().matrix().asDiagonal() * Z.transpose();
  }
  T = sqrt_lambda.asDiagonal() * Z * sqrt_lambda.asDiagonal();
  T = symmetric_part(T);
  return true;
}

// The trust region's radius after a step of length `step` whose actual decrease was `ratio` times
// the predicted one: a quarter of the step when the model was poor, doubled (up to kMaxRadius)
// when it was good and the step reached the boundary.
inline double updated_radius(double radius, double ratio, double step) {
  if (ratio < 0.25) return 0.25 * step;
  if (ratio > 0.75 && step >= 0.99 * radius) return std::min(2.0 * radius, kMaxRadius);
  return radius;
}

/// A trial point's verdict: true when the iteration moves to it, with `radius` updated. f and
/// f_trial are the criterion at the current and the trial point (f_trial unused when !valid:
/// the trial point is not in the domain), predicted the model's decrease, step the step's length,
/// n the problem's size. Below the resolution of f (the last Newton steps: the decrease is about
/// g^2 / H, the rounding of f about eps f) the ratio of actual to predicted decrease is noise: the
/// step is taken unless f rose beyond its rounding, and the gradient at the new point judges it.
/// Otherwise the ratio decides (updated_radius, kAcceptRatio).
inline bool accept_trial(bool valid, double f, double f_trial, double predicted, double step, Eigen::Index n,
                         double& radius) {
  const double resolution = kCriterionRounding * static_cast<double>(n) * kEps;
  if (predicted < resolution * f) {
    if (valid && f_trial <= f * (1.0 + resolution)) return true;
    radius = 0.25 * step;
    return false;
  }
  const double ratio = valid && predicted > 0.0 ? (f - f_trial) / predicted : -1.0;
  radius = updated_radius(radius, ratio, step);
  return ratio > kAcceptRatio;
}

}  // namespace trust_region

}  // namespace spdfit::detail
