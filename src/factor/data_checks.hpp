// Internal: the checks of the data a triangular factor is made from, which TriangularFactor and
// the small-problem path share.
#pragma once

#include <Eigen/Core>
#include <optional>
#include <string>

namespace spdfit::detail {

/// Throws std::invalid_argument unless A is k x n, B is k x d, and both are finite (the data
/// checks of TriangularFactor, shared with the small-problem path).
void check_data(const Eigen::Ref<const Eigen::MatrixXd>& A, const Eigen::Ref<const Eigen::MatrixXd>& B,
                Eigen::Index n, Eigen::Index d);
/// check_data's two halves: the shapes, and NaN or Inf in A or B.
void check_shapes(const Eigen::Ref<const Eigen::MatrixXd>& A, const Eigen::Ref<const Eigen::MatrixXd>& B,
                  Eigen::Index n, Eigen::Index d);
void check_finite(const Eigen::Ref<const Eigen::MatrixXd>& A, const Eigen::Ref<const Eigen::MatrixXd>& B);

/// The first NaN or Inf of M, row by row as a user looks for it: its 0-based row and column and
/// "NaN", "Inf" or "-Inf"; nothing when M is finite.
struct NonfiniteEntry {
  Eigen::Index row, column;
  const char* what;
};
std::optional<NonfiniteEntry> first_nonfinite(const Eigen::Ref<const Eigen::MatrixXd>& M);

/// The message for data with fewer rows m than columns n.
std::string too_few_rows(Eigen::Index m, Eigen::Index n);

}  // namespace spdfit::detail
