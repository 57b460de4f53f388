// Internal: Qi and Sun's quadratically convergent Newton method on the dual of the nearest
// semidefinite matrix with a fixed diagonal, the engine of the fixed-diagonal repairs
// (nearest_correlation.cpp).
#pragma once

#include <Eigen/Core>

namespace spdfit::detail {

/// What correlation_newton returns.
struct CorrelationNewtonResult {
  Eigen::MatrixXd X;         ///< (G + diag(y))_+ at the last iterate, exactly symmetric
  int iterations = 0;        ///< Newton steps taken
  double gradient_norm = 0;  ///< ||diag(X) - b||_2 at the last iterate
  bool converged = false;    ///< gradient_norm met the stopping test
  Eigen::Index clipped = 0;  ///< eigenvalues of G + diag(y) at or below 0 (X's zero eigenvalues)
};

/// min ||X - G||_F over symmetric X >= 0 with diag(X) = b (b > 0), by Newton's method on the dual
/// theta(y) = ||(G + diag y)_+||_F^2 / 2 - b^T y (Qi & Sun 2006), with Borsdorf & Higham's (2010)
/// improvements: the Newton equation solved by conjugate gradients preconditioned by the
/// Jacobian's diagonal, and an Armijo line search on theta. Starts at y0 = b - diag(G) (the dual
/// matrix G + diag(y0) has diagonal b); `eigenvectors` and `eigenvalues` (ascending), when given,
/// are that matrix's eigendecomposition, and are consumed.
///
/// Stops when ||diag((G + diag y)_+) - b||_2 <= `tolerance`, or at that gradient's own rounding
/// level when it is larger (2 sqrt(n) eps ||G + diag y||_2: the eigendecomposition it comes from
/// is exact only for a matrix that near), or after `max_iterations` steps (the last iterate,
/// converged = false). Memory, in doubles: G and one n x n eigenvector matrix, which every
/// eigendecomposition overwrites in place (LAPACK's dsyevd adds 2 n^2 while it runs), and during a
/// step the Jacobian's buffers, 3 n r + r (n - r) for r positive eigenvalues: about 4 n^2 at the
/// peak. Throws std::runtime_error when an eigendecomposition fails. Cost per step: one symmetric
/// eigendecomposition (O(n^3)) and, per conjugate-gradient iteration, two products of an n x n by
/// an n x r matrix (4 n^2 r flops). From n = 1000 on, the steps whose gradient stays far above
/// single precision's rounding level of it (the rule in correlation_newton.cpp) run in single
/// precision (ssyevd and sgemm, about half the time; their n^2 floats of eigenvectors and ssyevd's
/// 2 n^2 floats of workspace stay within the peak above); the stopping test, the last steps and X
/// always come from double precision.
CorrelationNewtonResult correlation_newton(Eigen::MatrixXd G, const Eigen::VectorXd& b, int max_iterations,
                                           double tolerance, Eigen::MatrixXd* eigenvectors = nullptr,
                                           Eigen::VectorXd* eigenvalues = nullptr);

}  // namespace spdfit::detail
