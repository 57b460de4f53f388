// Internal: what the two Riemannian Newton methods of spd-tls share (spd_tls_kernel.cpp for equal
// noise, spd_ml_kernel.cpp for a noise model): the stopping rule, the trust region's constants,
// the cyclic Jacobi eigensolver that updates the iterates' eigenbases, and the packed coordinates
// of a symmetric step.
#pragma once

#include <Eigen/Core>
#include <Eigen/Jacobi>
#include <cmath>
#include <utility>
#include <limits>

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

}  // namespace spdfit::detail
