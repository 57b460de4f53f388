// Internal: the factor-structured least-squares fit behind nearest_correlation_rank and
// nearest_correlation_factors, min sum_{i != j} w_i w_j (y_i . y_j - c_ij)^2 over Y (n x K) with
// unit rows (a correlation matrix of rank <= K) or rows in the unit ball (a factor model).
#pragma once

#include <Eigen/Core>

namespace spdfit::detail {

/// The objective's data. C is not copied: it must outlive the problem. Only products of C's
/// symmetric part with n x K matrices are formed (C Y, and C^T Y when C is not exactly symmetric).
class LowRankProblem {
 public:
  /// `w` empty: unit weights. `sphere`: unit rows (else rows in the unit ball).
  LowRankProblem(const Eigen::Ref<const Eigen::MatrixXd>& C, Eigen::VectorXd w, bool sphere);

  /// f(Y) and, when `gradient` is given, its gradient. One product with C.
  double evaluate(const Eigen::MatrixXd& Y, Eigen::MatrixXd* gradient) const;
  /// Y projected onto the constraint: each row scaled to unit norm (sphere; a zero row becomes
  /// e_1) or into the unit ball.
  void project(Eigen::MatrixXd& Y) const;
  /// The stationarity residual: the Riemannian gradient (sphere: g_i - (g_i . y_i) y_i) or the
  /// projected gradient P(Y - g) - Y (ball), relative to the gradient's scale
  /// 4 (||W^1/2 C W^1/2||_F + ||Y^T W Y||_F) max_i sqrt(w_i).
  double residual(const Eigen::MatrixXd& Y, const Eigen::MatrixXd& gradient) const;
  /// ||W^1/2 (X - C) W^1/2||_F for X = diag(1 - ||y_i||^2) + Y Y^T, summed a column at a time
  /// (no n x n matrix): O(n^2 K).
  double distance(const Eigen::MatrixXd& Y) const;
  bool sphere() const { return sphere_; }
  bool symmetric() const { return symmetric_; }
  /// The rounding level of evaluate's value: a few eps ||W^1/2 C W^1/2||_F^2.
  double rounding() const;

 private:
  // C's symmetric part times V.
  void product(const Eigen::MatrixXd& V, Eigen::MatrixXd& out) const;

  const Eigen::Ref<const Eigen::MatrixXd> C_;
  Eigen::VectorXd w_;
  bool sphere_;
  bool symmetric_;
  double c2_ = 0.0;  // sum_ij w_i w_j s_ij^2, S = (C + C^T) / 2
  double scale_ = 1.0;
};

/// What spectral_projected_gradient returns.
struct LowRankResult {
  Eigen::MatrixXd Y;
  double objective = 0.0;
  int iterations = 0;
  double residual = 0.0;  ///< LowRankProblem::residual at Y
  bool converged = false;
};

/// The spectral projected gradient method (Birgin, Martinez & Raydan 2000: Barzilai-Borwein steps,
/// a non-monotone Armijo search over the last 10 values) from Y0; on the sphere, in its Riemannian
/// form (the gradient projected onto the tangent space, the step retracted by normalizing rows).
/// Stops at a residual <= tolerance or after max_iterations steps. Cost per step: about one
/// product of C with an n x K matrix.
LowRankResult spectral_projected_gradient(const LowRankProblem& problem, Eigen::MatrixXd Y0, int max_iterations,
                                          double tolerance);

/// The K leading eigenvectors of C's symmetric part (columns) and their eigenvalues, by block
/// power iteration with Rayleigh-Ritz (products of C with n x (K + p) matrices only), from a
/// seeded random start: accurate enough for a starting point, not a general eigensolver.
void leading_eigenvectors(const Eigen::Ref<const Eigen::MatrixXd>& C, Eigen::Index K, Eigen::MatrixXd& vectors,
                          Eigen::VectorXd& values);

}  // namespace spdfit::detail
