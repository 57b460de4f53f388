#include "spdfit/symmetric_procrustes.hpp"

#include <Eigen/Eigenvalues>

#include "estimators/diagnostics.hpp"
#include "estimators/kernels.hpp"
#include "estimators/noise_weights.hpp"
#include "numerics/linalg.hpp"

namespace spdfit {

using Eigen::Index;
using Eigen::MatrixXd;

namespace detail {

template <int MaxN>
void procrustes_kernel(const BasicReduction<MaxN>& data, SquareMatrix<MaxN>& X_s) {
  using Matrix = SquareMatrix<MaxN>;
  const Index n = data.n;
  const Index r = data.rank_a;
  // With R11 = U S V^T, ||R11 X - R12||_F = ||S Xt - C||_F for Xt = V^T X V and C = U^T R12 V.
  // Minimizing over symmetric Xt entry pair by entry pair gives Higham's closed form, the
  // solution of the normal equation (thesis eq. 3.15) without forming A^T A. Singular values
  // under the rank cut-off are edited to zero; entries with both zero are free, and zero is
  // their minimum-norm choice.
  Matrix UR, C;
  product_into<Matrix>(data.U_a, true, data.R12, false, UR);
  product_into<Matrix>(UR, false, data.V_a, false, C);
  typename BasicReduction<MaxN>::Vector s = data.s_a;
  s.tail(n - r).setZero();
  Matrix Xt;
  procrustes_eigenbasis(s, C, Xt);
  Matrix VX, X;
  product_into<Matrix>(data.V_a, false, Xt, false, VX);
  product_into<Matrix>(VX, false, data.V_a, true, X);
  X_s = symmetric_part(X);
}

#define SPDFIT_INSTANTIATE(MaxN) \
  template void procrustes_kernel<MaxN>(const BasicReduction<MaxN>&, SquareMatrix<MaxN>&);
SPDFIT_FOR_EACH_MAX_N(SPDFIT_INSTANTIATE)
#undef SPDFIT_INSTANTIATE

}  // namespace detail

FitResult symmetric_procrustes(const Reduction& reduction) {
  const detail::DynamicReduction& data = detail::data_of(reduction, Method::SymmetricProcrustes);
  const Index n = data.n;
  const Index r = data.rank_a;
  std::vector<Warning> warnings;
  MatrixXd X_s;
  // With a noise model, min sum_i r_i^T Sigma_B^-1 r_i over symmetric X is the unweighted problem
  // on the whitened data (whiten_b): X = C Y C with Y their symmetric Procrustes estimate.
  const std::optional<detail::ScaledNoise> noise = detail::scaled_noise(data);
  std::optional<detail::WhitenedB> whitened;
  if (noise) {
    whitened = detail::whiten_b(data, *noise, 0.0, true);
    MatrixXd Y_s;
    detail::procrustes_kernel(whitened->data, Y_s);
    X_s = detail::unwhiten_b(*whitened, Y_s);
    if (auto warning = detail::ignored_noise_warning(data, Method::SymmetricProcrustes)) warnings.push_back(*warning);
  } else {
    detail::procrustes_kernel(data, X_s);
  }

  if (r < n) {
    warnings.push_back(Warning(Code::RankDeficient, "A is rank-deficient (rank " + std::to_string(r) + " < n = " + std::to_string(n) +
                       "): the symmetric minimizer is not unique; returning the one of minimum norm"));
  }

  // Theorem 3.2 (3): A^T B + B^T A positive definite implies a positive definite estimate (with a
  // noise model, for the whitened data whose estimate Y is congruent to X).
  // Reported with every diagnostic; otherwise computed only for the warning below.
  const detail::DynamicReduction& fitted = whitened ? whitened->data : data;
  const auto cross_term_positive_definite = [&fitted]() {
    MatrixXd cross;
    detail::multiply(fitted.R11, true, fitted.R12, false, cross);
    Eigen::VectorXd w;
    return detail::symmetric_eigen(MatrixXd(cross + cross.transpose()), w) && w(0) > 0.0;
  };
  Diagnostics d;
  if (data.options.diagnostics && data.options.reported_diagnostics) {
    d.cross_term_positive_definite = cross_term_positive_definite();
  }

  FitResult result =
      detail::finish(Method::SymmetricProcrustes, data, X_s, std::move(d), std::move(warnings));
  if (result.ok() && data.options.diagnostics && !result.diagnostics.positive_definite) {
    if (!result.diagnostics.cross_term_positive_definite) {
      result.diagnostics.cross_term_positive_definite = cross_term_positive_definite();
    }
    result.warnings.push_back(Warning(Code::NotPositiveDefinite, 
        "the procrustes estimate is not positive definite (smallest eigenvalue " +
        detail::format_number(result.diagnostics.min_eigenvalue.value_or(0.0)) + "); A^T B + B^T A is " +
        (*result.diagnostics.cross_term_positive_definite ? "positive definite" : "not positive definite")));
  }
  return result;
}

FitResult symmetric_procrustes(const Eigen::Ref<const MatrixXd>& A, const Eigen::Ref<const MatrixXd>& B,
                               const FitOptions& options) {
  return symmetric_procrustes(reduce(TriangularFactor::from_data(A, B), options));
}

}  // namespace spdfit
