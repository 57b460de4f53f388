#include "spdfit/least_squares.hpp"

#include "estimators/diagnostics.hpp"
#include "estimators/kernels.hpp"
#include "estimators/noise_weights.hpp"
#include "numerics/linalg.hpp"

namespace spdfit {

using Eigen::MatrixXd;

namespace detail {

template <int MaxN>
void least_squares_kernel(const BasicReduction<MaxN>& data, SquareMatrix<MaxN>& X_s) {
  if (data.rank_a == data.n) {
    // Full column rank: back substitution in R11 X = R12 (Householder QR, notes 002 3.7).
    X_s = data.R12;
    data.R11.template triangularView<Eigen::Upper>().solveInPlace(X_s);
    return;
  }
  // Rank-deficient A: the minimum-norm solution X = V diag(1/sigma_i) U^T R12 with 1/sigma_i
  // edited to zero for the singular values under the cut-off (notes 002, eq. 3.21, 3.8).
  const Eigen::Index r = data.rank_a;
  X_s = data.V_a.leftCols(r) *
        (data.s_a.head(r).cwiseInverse().asDiagonal() * (data.U_a.leftCols(r).transpose() * data.R12));
}

#define SPDFIT_INSTANTIATE(MaxN) \
  template void least_squares_kernel<MaxN>(const BasicReduction<MaxN>&, SquareMatrix<MaxN>&);
SPDFIT_FOR_EACH_MAX_N(SPDFIT_INSTANTIATE)
#undef SPDFIT_INSTANTIATE

}  // namespace detail

FitResult least_squares(const Reduction& reduction) {
  const detail::DynamicReduction& data = detail::data_of(reduction, Method::LeastSquares);
  std::vector<Warning> warnings;
  MatrixXd X_s;
  detail::least_squares_kernel(data, X_s);
  if (data.rank_a < data.n) {
    warnings.push_back(Warning(Code::RankDeficient, "A is rank-deficient (rank " + std::to_string(data.rank_a) + " < n = " +
                       std::to_string(data.n) +
                       "): returning the minimum-norm least-squares solution from the edited SVD"));
  }
  // A noise model does not change A^+ B: with Sigma_B alone it is the maximum-likelihood estimate
  // of an unconstrained X whatever Sigma_B; noise in A it ignores, and says so.
  if (auto warning = detail::ignored_noise_warning(data, Method::LeastSquares)) warnings.push_back(*warning);
  return detail::finish(Method::LeastSquares, data, X_s, {}, std::move(warnings));
}

FitResult least_squares(const Eigen::Ref<const MatrixXd>& A, const Eigen::Ref<const MatrixXd>& B,
                        const FitOptions& options) {
  return least_squares(reduce(TriangularFactor::from_data(A, B), options));
}

}  // namespace spdfit
