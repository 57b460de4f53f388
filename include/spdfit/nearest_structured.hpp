// Covariance and correlation repair with entries kept exactly (a trusted block) and with
// elementwise weights (how much each entry is trusted), and the raising of low variances.
#pragma once

#include <Eigen/Core>
#include <optional>
#include <string>
#include <vector>

#include "spdfit/nearest_correlation.hpp"
#include "spdfit/nearest_spd.hpp"
#include "spdfit/outcome.hpp"

namespace spdfit {

/// What a structured repair does with the diagonal: leaves it free (the nearest positive
/// semidefinite matrix, as nearest_spd), makes it 1 (the nearest correlation matrix, as
/// nearest_correlation) or keeps C's (as nearest_keep_diagonal).
enum class DiagonalRule { Free, Unit, Kept };

/// The entries a repair keeps and the weights of the others.
struct NearestStructure {
  /// Entries of C kept exactly, to the last bit: an n x n mask (1: kept, 0: free; symmetric, only
  /// 0 and 1), or a k x 2 matrix of k index pairs (i, j), counted from `index_base`, each keeping
  /// (i, j) and (j, i). An n x n matrix is a mask (so for n = 2 a 2 x 2 matrix is one). The
  /// diagonal follows the DiagonalRule; with DiagonalRule::Free the mask's (or the pairs')
  /// diagonal entries are kept too. Empty: none.
  Eigen::MatrixXd fixed;
  int index_base = 1;
  /// Elementwise weights H (n x n, symmetric, finite, >= 0; 0: the entry is free, as for a pair
  /// never observed together): the distance is ||H o (X - C)||_F. Not with
  /// NearestCorrelationOptions::weights (H = w w^T is that case). Empty: none.
  Eigen::MatrixXd h_weights;

  /// True when `fixed` and `h_weights` (those given) are valid for an n x n matrix repaired with
  /// the diagonal rule: the checks that need nothing of the matrix but its size (shape, values,
  /// symmetry, a mask that keeps something, weights not zero on every entry the repair may
  /// change). Otherwise `error` says why, naming the option in backticks.
  bool is_valid(Eigen::Index n, DiagonalRule rule, std::string* error = nullptr) const;
};

/// The nearest matrix to C with the structure's entries of C kept exactly, the diagonal rule and
/// eigenvalues >= the floor, in ||H o (X - C)||_F with elementwise weights, else in
/// ||W^1/2 (X - C) W^1/2||_F (options.weights; all ones by default). The floor is interpreted as
/// by nearest_spd (Free), nearest_correlation (Unit) and nearest_keep_diagonal (Kept).
///
/// Without elementwise weights: Qi and Sun's Newton method on the dual, with the fixed set in
/// place of the diagonal (Qi & Sun, "Correlation stress testing for value-at-risk: an
/// unconstrained convex optimization approach", 2010): theta(y) = ||(G + A^* y)_+||^2 / 2 - b^T y,
/// A the map to the kept entries. With them (H not of the form h h^T, which is the diagonal
/// weights' problem): an augmented Lagrangian method on X >= 0 whose subproblems are solved by a
/// semismooth Newton method with conjugate gradients (as Qi & Sun 2011 for NAG g02aj's problem),
/// stopped on the KKT residuals. Both report a lower bound on the distance from the dual
/// (NearestResult::lower_bound); the kept entries are set exactly at the end, so the smallest
/// eigenvalue is the floor less at most the final constraint residual (gradient_norm).
///
/// Preconditions (else std::invalid_argument naming what is wrong): C square, finite; the mask
/// n x n with only 0 and 1, symmetric, keeping at least one entry; pairs within 1..n; H n x n,
/// finite, >= 0, symmetric to rounding, not zero on every entry the repair may change; the kept
/// entries admit a matrix with the floor: no kept 2 x 2 minor or fully kept block below it (the
/// message names the entries or the block), and no other obstruction the dual iteration proves
/// (the dual's value grows past the largest distance any admissible matrix can have). Cost:
/// O(n^3) per Newton step (an eigendecomposition and conjugate-gradient products with the
/// eigenvectors); the augmented Lagrangian takes a few times as many steps.
NearestResult nearest_structured(const Eigen::Ref<const Eigen::MatrixXd>& C, DiagonalRule diagonal,
                                 const NearestStructure& structure, const NearestCorrelationOptions& options = {});

/// C with every diagonal entry below `min_diag` raised to it: pairwise-deletion covariances with a
/// zero or negative variance. A warning (Code::Warning: no code of its own, none fitting better) naming the raised entries
/// (1-based, with their values) and the option `min_diag` is added to `warnings` when there are
/// any. Throws std::invalid_argument unless min_diag is finite and >= 0. Cost: O(n^2) (the copy).
Eigen::MatrixXd raise_variances(const Eigen::Ref<const Eigen::MatrixXd>& C, double min_diag,
                                std::vector<Warning>& warnings);

}  // namespace spdfit
