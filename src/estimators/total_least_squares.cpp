#include "spdfit/total_least_squares.hpp"

#include <Eigen/LU>
#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>
#include <string>

#include "estimators/diagnostics.hpp"
#include "estimators/generalized_tls.hpp"
#include "factor/data_checks.hpp"
#include "factor/reduce.hpp"
#include "estimators/kernels.hpp"
#include "numerics/linalg.hpp"
#include "spdfit/nearest_spd.hpp"

namespace spdfit {

using Eigen::Index;
using Eigen::MatrixXd;

namespace detail {

template <int MaxN>
void tls_kernel(const BasicReduction<MaxN>& data, TlsKernel<MaxN>& out) {
  using Factor = typename BasicReduction<MaxN>::Factor;
  using Matrix = SquareMatrix<MaxN>;
  const Index n = data.n, d = data.d;

  int e = 0;
  Factor R;
  tls_factor(data, R, e);

  // [A B] = Q R: the SVD of R gives the singular values and right singular vectors of [A B]
  // (thesis eq. 4.29) at O(n^3) instead of O(m n^2).
  BasicSvd<Factor> dec;
  svd_into(R, dec, false, true);
  const auto& sigma = dec.s;
  out.sigma_n = std::ldexp(sigma(n - 1), e);
  out.sigma_n1 = std::ldexp(sigma(n), e);
  out.correction = std::ldexp(sigma.tail(d).norm(), e);  // thesis eq. 4.33
  // The noise estimate is made of the same singular values: one SVD serves both.
  out.noise_var.reset();
  if (data.dof_rows() > n) out.noise_var = noise_variance_from(sigma, data.dof_rows(), n, e);

  const Matrix V12 = dec.V.topRightCorner(n, d);
  const Matrix V22 = dec.V.bottomRightCorner(d, d);
  BasicSvd<Matrix> v22;
  svd_into(V22, v22, false, false);
  out.v22_min = v22.s(d - 1);

  const double cutoff = data.options.rank_cutoff(data.m, n + d);
  out.exists = out.v22_min > cutoff;
  if (!out.exists) return;
  out.unique = sigma(n - 1) - sigma(n) > cutoff * sigma(0);
  // X = -V12 V22^-1 (thesis eq. 4.37), as the solution of V22^T X^T = -V12^T with pivoting:
  // the TLS solution for [A, B / r], so r X is the data's.
  const Matrix X = -V22.transpose().partialPivLu().solve(V12.transpose()).transpose() * data.options.noise_ratio;
  // Back to the scaled units of the other estimators: X_s = X 2^(ea - eb).
  out.X_s = times_power_of_two(X, data.exponent_a - data.exponent_b);
}

#define SPDFIT_INSTANTIATE(MaxN) \
  template void tls_kernel<MaxN>(const BasicReduction<MaxN>&, TlsKernel<MaxN>&);
SPDFIT_FOR_EACH_MAX_N(SPDFIT_INSTANTIATE)
#undef SPDFIT_INSTANTIATE

}  // namespace detail

namespace {

// X_TLS in the factor's scaled units, or a failure.
struct TlsCore {
  MatrixXd X_s;
  Diagnostics diagnostics;
  std::vector<Warning> warnings;
  std::string error;  // empty on success
};

// Generalized TLS with the noise model (generalized_tls.hpp): the TLS diagnostics are those of the
// whitened data, in units of the noise's standard deviation; least squares when A is exact.
TlsCore generalized_tls_core(const detail::DynamicReduction& data, const detail::ScaledNoise& noise) {
  TlsCore out;
  detail::GeneralizedTls k;
  detail::generalized_tls(data, noise, k);
  if (k.least_squares) {
    out.X_s = std::move(k.X_s);
    if (data.rank_a < data.n) {
      out.warnings.push_back(Warning(Code::RankDeficient, "A is rank-deficient (rank " + std::to_string(data.rank_a) + " < n = " +
                             std::to_string(data.n) +
                             "): returning the minimum-norm least-squares solution from the edited SVD"));
    }
    return out;
  }
  Diagnostics& d = out.diagnostics;
  d.tls_sigma_n = k.sigma_n;
  d.tls_sigma_n1 = k.sigma_n1;
  d.tls_correction_norm = k.correction;
  d.tls_v22_min_singular_value = k.v22_min;
  if (!k.exists) {
    out.error = "tls: no generalized total least-squares solution exists: V22 is singular (smallest singular value " +
                detail::format_number(k.v22_min) +
                "), so the smallest singular subspace of the whitened [A B] contains directions with no B part";
    return out;
  }
  if (!k.unique) {
    out.warnings.push_back(Warning(Code::IllConditioned, "sigma_n = " + detail::format_number(k.sigma_n) + " and sigma_{n+1} = " +
                           detail::format_number(k.sigma_n1) +
                           " of the whitened [A B] are equal to working precision, so the generalized TLS "
                           "solution is not unique"));
  }
  out.X_s = std::move(k.X_s);
  return out;
}

TlsCore tls_core(const detail::DynamicReduction& data) {
  if (const std::optional<detail::ScaledNoise> noise = detail::scaled_noise(data)) {
    return generalized_tls_core(data, *noise);
  }
  TlsCore out;
  detail::TlsKernel<Eigen::Dynamic> k;
  detail::tls_kernel(data, k);
  Diagnostics& d = out.diagnostics;
  // The noise estimate from this SVD rather than a second one of the same factor (finish keeps it).
  if (k.noise_var && data.options.diagnostics && data.options.reported_diagnostics) {
    d.noise_sigma = std::sqrt(*k.noise_var);
  }
  d.tls_sigma_n = k.sigma_n;
  d.tls_sigma_n1 = k.sigma_n1;
  d.tls_correction_norm = k.correction;
  d.tls_v22_min_singular_value = k.v22_min;
  if (!k.exists) {
    out.error = "tls: no total least-squares solution exists: V22 is singular (smallest singular value " +
                detail::format_number(k.v22_min) +
                "), so the smallest singular subspace of [A B] contains directions with no B part";
    return out;
  }
  if (!k.unique) {
    out.warnings.push_back(Warning(Code::IllConditioned, "sigma_n = " + detail::format_number(k.sigma_n) +
                           " and sigma_{n+1} = " + detail::format_number(k.sigma_n1) +
                           " of [A B] are equal to working precision, so the TLS solution is not unique "
                           "(the condition of thesis Theorem 4.7 fails)"));
  }
  out.X_s = std::move(k.X_s);
  return out;
}

// The result of `method` (tls, tls-sym or tls-psd) from the shared X_TLS.
FitResult finish_tls(Method method, const detail::DynamicReduction& data, const TlsCore& core) {
  if (!core.error.empty()) return detail::failure(method, data, core.error, core.warnings);
  MatrixXd X_s;
  switch (method) {
    case Method::TotalLeastSquaresSymmetric:
      X_s = detail::symmetric_part(core.X_s);  // thesis eq. 4.38
      break;
    case Method::TotalLeastSquaresPsd:
      X_s = nearest_spd(core.X_s).X;  // thesis eq. 4.39 (Higham)
      break;
    default:
      X_s = core.X_s;
  }
  return detail::finish(method, data, X_s, core.diagnostics, core.warnings);
}

// The data for `method`, refused when it does not apply (non_square_refusal), or when a non-square
// X meets fewer rows than the n + d columns of [A B] (too_few_rows_refusal). Square data keep the
// rule of every method, m >= n.
const detail::DynamicReduction& tls_data(const Reduction& reduction, Method method) {
  const detail::DynamicReduction& data = detail::data_of(reduction, method);
  if (auto refusal = too_few_rows_refusal(method, data.m, data.n, data.d)) throw std::invalid_argument(*refusal);
  return data;
}

FitResult run(Method method, const Reduction& reduction) {
  const detail::DynamicReduction& data = tls_data(reduction, method);
  return finish_tls(method, data, tls_core(data));
}

}  // namespace

namespace detail {

std::array<FitResult, 3> total_least_squares_family(const Reduction& reduction) {
  const DynamicReduction& data = data_of(reduction, Method::TotalLeastSquaresSymmetric);
  const TlsCore core = tls_core(data);
  return {finish_tls(Method::TotalLeastSquares, data, core),
          finish_tls(Method::TotalLeastSquaresSymmetric, data, core),
          finish_tls(Method::TotalLeastSquaresPsd, data, core)};
}

}  // namespace detail

FitResult total_least_squares(const Reduction& data) { return run(Method::TotalLeastSquares, data); }
FitResult total_least_squares_symmetric(const Reduction& data) {
  return run(Method::TotalLeastSquaresSymmetric, data);
}
FitResult total_least_squares_psd(const Reduction& data) { return run(Method::TotalLeastSquaresPsd, data); }

FitResult total_least_squares(const Eigen::Ref<const MatrixXd>& A, const Eigen::Ref<const MatrixXd>& B,
                              const FitOptions& options) {
  return total_least_squares(reduce(TriangularFactor::from_data(A, B), options));
}
FitResult total_least_squares_symmetric(const Eigen::Ref<const MatrixXd>& A,
                                        const Eigen::Ref<const MatrixXd>& B, const FitOptions& options) {
  return total_least_squares_symmetric(reduce(TriangularFactor::from_data(A, B), options));
}
FitResult total_least_squares_psd(const Eigen::Ref<const MatrixXd>& A, const Eigen::Ref<const MatrixXd>& B,
                                  const FitOptions& options) {
  return total_least_squares_psd(reduce(TriangularFactor::from_data(A, B), options));
}

}  // namespace spdfit
