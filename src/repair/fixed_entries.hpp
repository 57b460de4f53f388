// Internal: the entries a structured repair keeps (nearest_structured), read from a mask or a list
// of pairs and checked, and the checks that a matrix with them and the eigenvalue floor exists.
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

#include "spdfit/nearest_structured.hpp"

namespace spdfit::detail {

/// The kept entries, each once, in the lower triangle (row >= col), the diagonal ones included.
struct FixedPattern {
  Eigen::Index n = 0;
  std::vector<Eigen::Index> row, col;
  Eigen::Index size() const { return static_cast<Eigen::Index>(row.size()); }
  /// Off-diagonal entries kept (pairs i < j) and diagonal entries kept, for the result's count.
  Eigen::Index off_diagonal = 0, diagonal = 0;
};

/// The pattern of `structure.fixed` for an n x n problem with the diagonal `rule` (Unit and Kept
/// keep every diagonal entry whatever the mask says; Free keeps the mask's). Empty `fixed`: the
/// diagonal only (Unit, Kept) or nothing (Free). Throws std::invalid_argument naming the entry:
/// a mask not n x n or not k x 2, entries other than 0 and 1, an asymmetric mask, a mask that
/// keeps nothing, pairs out of range or not integers.
FixedPattern fixed_pattern(const Eigen::MatrixXd& fixed, int index_base, Eigen::Index n, DiagonalRule rule);

/// Throws std::invalid_argument unless H is n x n, finite, >= 0, symmetric to rounding
/// (relative 1e-10) and not zero on every entry the pattern leaves free.
void check_h_weights(const Eigen::MatrixXd& H, const FixedPattern& pattern);

/// Throws std::invalid_argument when the kept entries of B (in the pattern; B symmetric) admit no
/// matrix X with X - diag(f) positive semidefinite: a kept entry larger than the root of its kept
/// diagonal entries' product (less the floors), or a fully kept block (rows and columns whose
/// every entry is kept) whose smallest eigenvalue is below the floor by more than rounding. The
/// message names the entry or the block (1-based) and, when the floor is what fails, `option`.
void check_fixed_feasible(const Eigen::MatrixXd& B, const FixedPattern& pattern, const Eigen::VectorXd& f,
                          const char* option);

/// "1, 2, 5" for 0-based indices, at most `shown` of them then ", ... (k in all)".
std::string index_list(const std::vector<Eigen::Index>& indices, std::size_t shown = 12);

}  // namespace spdfit::detail
