// The nearest correlation matrix of low rank, and of factor structure: non-convex repairs for
// simulation with K factors and for n too large for dense eigendecompositions.
#pragma once

#include <Eigen/Core>

#include "spdfit/nearest_correlation.hpp"
#include "spdfit/nearest_spd.hpp"

namespace spdfit {

/// Options of nearest_correlation_rank and nearest_correlation_factors.
struct NearestLowRankOptions {
  /// Diagonal weights w (n positive finite numbers; empty: all ones): the distance is
  /// ||W^1/2 (X - C) W^1/2||_F, W = diag(w). The rank repair only.
  Eigen::VectorXd weights;
  /// Keep C's diagonal d instead of a unit one (the rank repair only): X = D^1/2 R D^1/2 with R a
  /// correlation matrix of rank <= K, D = diag(d), every d_i > 0.
  bool keep_diagonal = false;
  /// Iterations of the local method at most, from each start (rank) or in all (factors).
  int max_iterations = 2000;
  /// Stop when the projected (rank: Riemannian) gradient is at most tolerance times its scale,
  /// 4 ||W^1/2 C W^1/2||_F max_i sqrt(w_i)... (see the implementation's stopping test), relative.
  double tolerance = 1e-9;
  /// Random starts besides the modified principal component ones (rank), drawn from a fixed seed.
  int random_starts = 3;
  /// Form X (factors): false leaves X empty and keeps only F (no n x n matrix besides C).
  bool form_x = true;
};

/// The nearest correlation matrix of rank at most K to C (NAG g02ak's problem): minimizes
/// ||W^1/2 (X - C) W^1/2||_F over X = Y Y^T with Y n x K and unit rows (with keep_diagonal, over
/// D^1/2 Y Y^T D^1/2). The problem is not convex: a spectral projected gradient method on the
/// product of unit spheres (Birgin, Martinez & Raydan's non-monotone line search, in the Riemannian
/// form), run from several documented starts: the modified principal components of C (its K
/// leading eigenvectors scaled by their eigenvalues' roots, rows normalized: Flury's "modified
/// PCA"), the same of the convex solution (the nearest correlation matrix without the rank), and
/// `random_starts` random points. The best local solution is returned; every start's distance is
/// in `starts`, the Riemannian gradient relative to its scale in `optimality_residual`, and the
/// distance of the convex solution, a lower bound, in `lower_bound`. F holds Y.
///
/// Preconditions (else std::invalid_argument): C square, finite; 1 <= K <= n; options valid.
/// Cost: O(n^3) for the starts' eigendecompositions and the convex solution, then O(n^2 K) per
/// iteration (a product of C with an n x K matrix).
NearestResult nearest_correlation_rank(const Eigen::Ref<const Eigen::MatrixXd>& C, Eigen::Index rank,
                                       const NearestLowRankOptions& options = {});

/// The nearest correlation matrix with K-factor structure to C (statsmodels' corr_nearest_factor,
/// NAG g02ae's problem): X = diag(1 - ||f_i||^2) + F F^T with F n x K and every ||f_i|| <= 1,
/// minimizing ||X - C||_F, by the spectral projected gradient method (Birgin, Martinez & Raydan
/// 2000) from the K leading eigenvectors of C (a block power iteration: products of C with n x K
/// matrices only). C's diagonal does not enter the fit (X's is 1). With form_x false, X is left
/// empty and no n x n matrix besides C is formed: the distance is summed a column at a time.
/// `optimality_residual` is the projected gradient relative to its scale.
///
/// Preconditions (else std::invalid_argument): C square, finite; 1 <= K <= n. Cost: O(n^2 K) per
/// iteration, a few hundred iterations typically.
NearestResult nearest_correlation_factors(const Eigen::Ref<const Eigen::MatrixXd>& C, Eigen::Index factors,
                                          const NearestLowRankOptions& options = {});

}  // namespace spdfit
