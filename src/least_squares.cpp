#include "spdfit/least_squares.hpp"

#include "diagnostics.hpp"
#include "linalg.hpp"

namespace spdfit {

using Eigen::MatrixXd;

FitResult least_squares(const Reduction& data) {
  std::vector<std::string> warnings;
  MatrixXd X_s;
  if (data.rank_a == data.n) {
    // Full column rank: back substitution in R11 X = R12 (Householder QR, notes 002 3.7).
    X_s = data.R11.triangularView<Eigen::Upper>().solve(data.R12);
  } else {
    // Rank-deficient A: the minimum-norm solution X = V diag(1/sigma_i) U^T R12 with 1/sigma_i
    // edited to zero for the singular values under the cut-off (notes 002, eq. 3.21, 3.8).
    const Eigen::Index r = data.rank_a;
    X_s = data.V_a.leftCols(r) *
          (data.s_a.head(r).cwiseInverse().asDiagonal() * (data.U_a.leftCols(r).transpose() * data.R12));
    warnings.push_back("A is rank-deficient (rank " + std::to_string(r) + " < n = " + std::to_string(data.n) +
                       "): returning the minimum-norm least-squares solution from the edited SVD");
  }
  return detail::finish(Method::LeastSquares, data, X_s, {}, std::move(warnings));
}

FitResult least_squares(const Eigen::Ref<const MatrixXd>& A, const Eigen::Ref<const MatrixXd>& B,
                        const FitOptions& options) {
  return least_squares(reduce(TriangularFactor::from_data(A, B), options));
}

}  // namespace spdfit
