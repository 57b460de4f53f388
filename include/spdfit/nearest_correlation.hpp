// The nearest correlation matrix: positive semidefinite with unit diagonal.
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

namespace spdfit {

/// Options of nearest_correlation.
struct NearestCorrelationOptions {
  /// Diagonal weights w (n positive finite numbers): the distance is ||W^1/2 (X - C) W^1/2||_F with
  /// W = diag(w). Empty (the default): all ones, the Frobenius norm.
  Eigen::VectorXd weights;
  /// A floor that keeps the unit diagonal (NAG g02ab's alpha): the result is (1 - alpha) X~ + alpha I
  /// with X~ the nearest correlation matrix to (C - alpha I) / (1 - alpha), so every eigenvalue is
  /// >= alpha. In [0, 1); 0 (the default) gives the plain nearest correlation matrix.
  double alpha = 0.0;
  /// Newton iterations at most (each one symmetric eigendecomposition plus a conjugate-gradient
  /// solve); then the best iterate with converged = false and a warning. >= 1.
  int max_iterations = 200;
  /// Stop when the dual gradient ||diag(X) - 1||_2 (in the weighted problem) is at most
  /// tolerance * sqrt(n). > 0.
  double tolerance = 1e-10;

  /// True when the options are usable for an n x n matrix; otherwise `error` says why.
  bool is_valid(Eigen::Index n, std::string* error = nullptr) const;
};

/// The result of nearest_correlation.
struct NearestCorrelationResult {
  Eigen::MatrixXd X;            ///< symmetric, unit diagonal (exactly 1), positive semidefinite
  double distance = 0.0;        ///< ||W^1/2 (X - sym(C)) W^1/2||_F
  int iterations = 0;           ///< Newton iterations taken
  double gradient_norm = 0.0;   ///< the final ||diag(X) - 1||_2 before the diagonal rescaling
  bool converged = false;       ///< gradient_norm <= tolerance sqrt(n)
  Eigen::Index clipped = 0;     ///< eigenvalues of the final dual matrix set to zero (the rank deficit)
  bool cholesky_ok = false;     ///< whether X has a Cholesky factorization (positive definite)
  std::vector<std::string> warnings;
};

/// The nearest correlation matrix to C: minimizes ||W^1/2 (X - C) W^1/2||_F over symmetric
/// positive semidefinite X with unit diagonal (Higham 2002), by the quadratically convergent
/// Newton method on the dual of Qi & Sun (2006), with Borsdorf & Higham's (2010) improvements:
/// the Newton equation solved by preconditioned conjugate gradients (Jacobi preconditioner) and
/// a line search on the dual function. A final diagonal scaling D^-1/2 X D^-1/2 makes the
/// diagonal 1 to rounding. C's symmetric part is used, with a warning when C is not symmetric to
/// rounding (more often a wrong file than noise).
///
/// Preconditions (else std::invalid_argument): C square, non-empty, finite; options as
/// documented. Cost: O(n^3) per Newton iteration; typically under ten iterations.
NearestCorrelationResult nearest_correlation(const Eigen::Ref<const Eigen::MatrixXd>& C,
                                             const NearestCorrelationOptions& options = {});

}  // namespace spdfit
