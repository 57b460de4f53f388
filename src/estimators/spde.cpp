#include "spdfit/spde.hpp"

#include <cmath>

#include "estimators/diagnostics.hpp"
#include "estimators/kernels.hpp"
#include "numerics/linalg.hpp"

namespace spdfit {

using Eigen::Index;
using Eigen::MatrixXd;

namespace detail {

template <int MaxN>
double spde_kernel(const BasicReduction<MaxN>& data, SquareMatrix<MaxN>& X_s) {
  using Matrix = SquareMatrix<MaxN>;
  const Index n = data.n;
  // X P X = Q with P = R11^T R11 and Q = R_b^T R_b. With Z = R11 X R11^T this reads
  // Z^2 = R11 Q R11^T = M^T M for M = R_b R11^T, so Z is the symmetric polar factor
  // H = V_M S V_M^T of M (the unique SPD square root; Chen & McInroy eq. 15) and
  // X = R11^-1 H R11^-T = L L^T with L = R11^-1 V_M S^(1/2). Working with the triangular
  // factors instead of P and Q keeps the error at about cond(A) eps instead of cond(A)^2 eps.
  Matrix M;
  product_into<Matrix>(data.R_b, false, data.R11, true, M);
  BasicSvd<Matrix> polar;
  svd_into(M, polar, false, true);

  // Corollary III.7: B of rank r < n gives the semidefinite minimizer of rank r. M has the rank
  // of B (R11 is invertible); its trailing singular values are rounding noise: drop them.
  const Index r = data.rank_b;
  X_s.setZero(n, n);
  // B = 0 (r = 0): the minimizer is X = 0. Eigen's triangular solve takes the address of the
  // first entry of its right-hand side, which an n x 0 matrix does not have.
  if (r > 0) {
    Matrix L = polar.V.leftCols(r) * polar.s.head(r).cwiseSqrt().asDiagonal();
    if constexpr (MaxN == Eigen::Dynamic) {
      solve_upper_in_place(data.R11, L);
      lower_gram(L, X_s);
    } else {
      data.R11.template triangularView<Eigen::Upper>().solveInPlace(L);
      X_s.template selfadjointView<Eigen::Lower>().rankUpdate(L);
    }
    make_symmetric_from_lower(X_s);
  }
  return polar.s.head(r).sum();
}

#define SPDFIT_INSTANTIATE(MaxN) \
  template double spde_kernel<MaxN>(const BasicReduction<MaxN>&, SquareMatrix<MaxN>&);
SPDFIT_FOR_EACH_MAX_N(SPDFIT_INSTANTIATE)
#undef SPDFIT_INSTANTIATE

}  // namespace detail

FitResult spde(const Reduction& reduction) {
  const detail::DynamicReduction& data = detail::data_of(reduction, Method::Spde);
  const Index n = data.n;
  if (data.rank_a < n) {
    return detail::failure(Method::Spde, data,
                           "spde: A is rank-deficient (rank " + std::to_string(data.rank_a) +
                               " < n = " + std::to_string(n) +
                               "), so the area criterion has no minimizer: "
                               "collect data that excites every direction of A");
  }
  std::vector<Warning> warnings;
  MatrixXd X_s;
  const double polar_sum = detail::spde_kernel(data, X_s);
  const Index r = data.rank_b;
  if (r < n) {
    warnings.push_back(Warning(Code::RankDeficient, "B is rank-deficient (rank " + std::to_string(r) + " < n = " + std::to_string(n) +
                       "): returning the positive semidefinite minimizer of rank " + std::to_string(r) +
                       " (Chen & McInroy, Corollary III.7)"));
  }

  // Corollary III.4: min f = 2 tr(Sigma_Q~ - A^T B); tr(Sigma_Q~) is the sum of the singular
  // values of M (Q~ and M^T M are similar).
  Diagnostics d;
  const double cross = (data.R11.transpose() * data.R12).trace();
  d.area_criterion_minimum = std::ldexp(2.0 * (polar_sum - cross), data.exponent_a + data.exponent_b);

  FitResult result = detail::finish(Method::Spde, data, X_s, std::move(d), std::move(warnings));
  if (result.ok() && r == n && data.options.diagnostics && !result.diagnostics.positive_definite) {
    result.warnings.push_back(Warning(Code::NotPositiveDefinite, 
        "the estimate is positive definite in exact arithmetic but numerically singular "
        "(smallest eigenvalue " +
        detail::format_number(result.diagnostics.min_eigenvalue.value_or(0.0)) + " against largest " +
        detail::format_number(result.diagnostics.max_eigenvalue.value_or(0.0)) + ")"));
  }
  return result;
}

FitResult spde(const Eigen::Ref<const MatrixXd>& A, const Eigen::Ref<const MatrixXd>& B,
               const FitOptions& options) {
  return spde(reduce(TriangularFactor::from_data(A, B), options));
}

}  // namespace spdfit
