#include "spdfit/total_least_squares.hpp"

#include <Eigen/LU>
#include <algorithm>
#include <cmath>

#include "diagnostics.hpp"
#include "linalg.hpp"
#include "spdfit/nearest_spd.hpp"

namespace spdfit {

using Eigen::Index;
using Eigen::MatrixXd;

namespace {

// X_TLS in the factor's scaled units, or a failure.
struct TlsCore {
  MatrixXd X_s;
  Diagnostics diagnostics;
  std::vector<std::string> warnings;
  std::string error;  // empty on success
};

TlsCore tls_core(const Reduction& data) {
  const Index n = data.n;
  TlsCore out;

  // TLS is only invariant under a common scaling of A and B, so undo the separate scalings
  // of the factor into a common one, 2^-max(ea, eb) (exact: powers of two).
  const int e = std::max(data.exponent_a, data.exponent_b);
  MatrixXd R = MatrixXd::Zero(2 * n, 2 * n);
  R.topLeftCorner(n, n) = detail::times_power_of_two(data.R11, data.exponent_a - e);
  R.topRightCorner(n, n) = detail::times_power_of_two(data.R12, data.exponent_b - e);
  R.bottomRightCorner(n, n) = detail::times_power_of_two(data.R22, data.exponent_b - e);

  // [A B] = Q R: the SVD of R gives the singular values and right singular vectors of [A B]
  // (thesis eq. 4.29) at O(n^3) instead of O(m n^2).
  const detail::Svd dec = detail::svd(R, false, true);
  const auto& sigma = dec.s;
  Diagnostics& d = out.diagnostics;
  d.tls_sigma_n = std::ldexp(sigma(n - 1), e);
  d.tls_sigma_n1 = std::ldexp(sigma(n), e);
  d.tls_correction_norm = std::ldexp(sigma.tail(n).norm(), e);  // thesis eq. 4.33

  const MatrixXd V12 = dec.V.topRightCorner(n, n);
  const MatrixXd V22 = dec.V.bottomRightCorner(n, n);
  const Eigen::VectorXd v22_sigma = detail::singular_values(V22);
  d.tls_v22_min_singular_value = v22_sigma(n - 1);

  const double cutoff = data.options.rank_cutoff(data.m, 2 * n);
  if (!(v22_sigma(n - 1) > cutoff)) {
    out.error = "tls: no total least-squares solution exists: V22 is singular (smallest singular value " +
                detail::format_number(v22_sigma(n - 1)) +
                "), so the smallest singular subspace of [A B] contains directions with no B part";
    return out;
  }
  if (sigma(n - 1) - sigma(n) <= cutoff * sigma(0)) {
    out.warnings.push_back("sigma_n = " + detail::format_number(*d.tls_sigma_n) +
                           " and sigma_{n+1} = " + detail::format_number(*d.tls_sigma_n1) +
                           " of [A B] are equal to working precision, so the TLS solution is not unique "
                           "(the condition of thesis Theorem 4.7 fails)");
  }
  // X = -V12 V22^-1 (thesis eq. 4.37), as the solution of V22^T X^T = -V12^T with pivoting.
  const MatrixXd X = -V22.transpose().partialPivLu().solve(V12.transpose()).transpose();
  // Back to the scaled units of the other estimators: X_s = X 2^(ea - eb).
  out.X_s = detail::times_power_of_two(X, data.exponent_a - data.exponent_b);
  return out;
}

FitResult run(Method method, const Reduction& data) {
  TlsCore core = tls_core(data);
  if (!core.error.empty()) return detail::failure(method, data, core.error, std::move(core.warnings));
  MatrixXd X_s;
  switch (method) {
    case Method::TotalLeastSquaresSymmetric:
      X_s = detail::symmetric_part(core.X_s);  // thesis eq. 4.38
      break;
    case Method::TotalLeastSquaresPsd:
      X_s = nearest_spd(core.X_s).X;  // thesis eq. 4.39 (Higham)
      break;
    default:
      X_s = std::move(core.X_s);
  }
  return detail::finish(method, data, X_s, std::move(core.diagnostics), std::move(core.warnings));
}

}  // namespace

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
