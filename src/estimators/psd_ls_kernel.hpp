// Internal: the arithmetic of psd-ls (psd_least_squares.hpp), least squares over the symmetric
// X >= epsilon I, as a kernel over the compile-time bound MaxN like the others in kernels.hpp.
#pragma once

#include "estimators/kernels.hpp"
#include "estimators/psd_ls_newton.hpp"

namespace spdfit::detail {

/// What psd_ls_kernel returns, in the factor's scaled units (see BasicReduction).
template <int MaxN>
struct PsdLsKernel {
  SquareMatrix<MaxN> X_s;        ///< the estimate, >= epsilon_s I
  int iterations = 0;            ///< Newton and projected-gradient iterations (0: Procrustes was feasible)
  PsdLsNewtonInfo newton;        ///< the Newton method's steps and residuals (none when it did not run)
  bool newton_solved = false;    ///< the Newton iterate passed the KKT test (no projected gradient ran)
  double kkt_residual = 0.0;     ///< relative KKT residual of X_s (see psd_least_squares.hpp)
  bool converged = false;        ///< kkt_residual <= the tolerance
  double primal_min_eig = 0.0;   ///< lambda_min(X_s - epsilon_s I)
  double dual_min_eig = 0.0;     ///< lambda_min(S_s), S_s = sym(R11^T (R11 X_s - R12))
  double complementarity = 0.0;  ///< <X_s - epsilon_s I, S_s>
  double duality_gap = 0.0;      ///< |complementarity| / (||R11||_2^2 ||X_s||_F + ||R11^T R12||_F)
};

/// The tolerance on the relative KKT residual: the certificate's, near double's rounding level.
inline constexpr double kPsdLsTolerance = 1e-12;

/// Minimizes ||R11 X_s - R12||_F over symmetric X_s >= epsilon_s I (epsilon_s >= 0): the
/// symmetric Procrustes solution when it is feasible, else, in the eigenbasis of R11^T R11
/// diagonally preconditioned by a congruence (which keeps the cone), the semismooth Newton
/// method of psd_ls_newton.hpp from Procrustes (full-rank A), accepted when its KKT residual is
/// below kPsdLsTolerance. Where it is not (rank-deficient A, a failed line search, rounding),
/// spectral projected gradient (Barzilai-Borwein steps, non-monotone) from the best point so
/// far and, once the rank settles, exact solves on the face the iterate identifies. At most
/// max_iterations iterations of both together; then the feasible point with the smallest KKT
/// residual. Returns false when an eigensolver fails. O(n^3) per iteration.
template <int MaxN>
bool psd_ls_kernel(const BasicReduction<MaxN>& data, double epsilon_s, int max_iterations, PsdLsKernel<MaxN>& out);

/// psd_least_squares with the floor epsilon_s in scaled units (instead of options.min_eig): the
/// result with its diagnostics and certificate. auto's fallback uses it with its own floor.
FitResult psd_least_squares_scaled(const DynamicReduction& data, double epsilon_s);

}  // namespace spdfit::detail
