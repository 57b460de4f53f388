// Internal: the likelihood criterion of spd-tls with a noise model and its derivatives, as the
// Newton methods of the interior (spd_ml_kernel.cpp) and of the boundary (spd_ml_boundary.cpp)
// and the boundary's certificate evaluate them.
#pragma once

#include <Eigen/Core>

#include "estimators/noise_weights.hpp"
#include "factor/basic_reduction.hpp"

namespace spdfit::detail::spd_ml {

// What stays fixed while Newton runs: the data, the covariances, P = R11^T R11 and R22^T R22.
struct Problem {
  const DynamicReduction& data;
  const ScaledNoise& noise;
  Eigen::MatrixXd P, E22;
};

// A point: X = V diag(lambda) V^T (V = Q, its eigenvectors, in the interior iteration), and what f
// needs: G = R11 X - R12, E = G^T G + R22^T R22, K = W^-1 with W = X Sigma_A X + Sigma_B.
struct Point {
  Eigen::MatrixXd Q, V, X, G, E, K;
  Eigen::VectorXd lambda;
  double f = 0.0;
};

/// f at p.X (n x n, symmetric): fills G, E, K and f = tr(E K); false when W is not numerically
/// positive definite or f is not finite. O(n^3).
bool criterion_at(const Problem& pr, Point& p);

/// The Euclidean gradient of f in X (F = K E K, M = R11^T G, N = Sigma_A X):
///     grad f = M K + K M^T - N F - F N^T,
/// from df = tr(dE K) - tr(F dW), dE = D M + M^T D, dW = D N + N^T D. O(n^3).
struct Gradient {
  Eigen::MatrixXd M, N, F, MK, NF, gradX;
};
void gradient_at(const Problem& pr, const Point& p, Gradient& d);

/// The matrices of the second derivative, d^2 f [D, D] / 2 = tr(D K D C1) + tr(D F D C2) +
/// 2 tr(D L D J) with
///   C1 = P - M K N^T - N K M^T + N F N^T,  C2 = N K N^T - Sigma_A,  L = N K,  J = N F - M K
/// (from d^2E = 2 D P D, d^2W = 2 D Sigma_A D, dK = -K dW K). O(n^3).
struct Curvature {
  Eigen::MatrixXd NK, C1, C2, J;
};
void curvature_at(const Problem& pr, const Point& p, const Gradient& d, Curvature& c);

/// A bound on the magnitude of each entry of grad f's terms (the sizes its computation cancels,
/// G = R11 X - R12 cancelling to the residual on consistent data): the rounding level of the
/// gradient is a few n eps times it, once taken to the iteration's coordinates. O(n^3).
Eigen::MatrixXd gradient_magnitude(const Problem& pr, const Point& p);

/// The Hessian of the Newton model in packed coordinates s of the symmetric step S
/// (|s| = ||S||_F, k x k): the model's quadratic part is sum_t tr(S U_t S V_t) = s^T H s / 2 over
/// the `terms` pairs (U_t, V_t). O(k^4).
void model_hessian(const Eigen::MatrixXd* const* Us, const Eigen::MatrixXd* const* Vs, int terms,
                   Eigen::MatrixXd& H);

}  // namespace spdfit::detail::spd_ml
