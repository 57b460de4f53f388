#include "estimators/small_problem.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "factor/data_checks.hpp"
#include "factor/reduce.hpp"
#include "repair/nearest_spd_kernel.hpp"
#include "estimators/kernels.hpp"
#include "estimators/psd_ls_kernel.hpp"
#include "estimators/spd_tls_kernel.hpp"
#include "numerics/linalg.hpp"

namespace spdfit::detail {

namespace {

using Eigen::Index;
using Eigen::MatrixXd;

// The triangular factor of the scaled [A 2^-ea, B 2^-eb] (m x 2n), factored in pieces of at
// most 4n rows: the first 4n rows, then R stacked on the next 2n rows, and so on.
template <int MaxN>
void small_factor(const Eigen::Ref<const MatrixXd>& A, const Eigen::Ref<const MatrixXd>& B, int ea, int eb,
                  typename BasicReduction<MaxN>::Factor& R) {
  constexpr int kMaxFactor = BasicReduction<MaxN>::kMaxFactor;
  using Stacked =
      Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::ColMajor, 2 * kMaxFactor, kMaxFactor>;
  const Index m = A.rows(), n = A.cols();
  Stacked work;
  Index done = 0;
  while (done < m) {
    const Index top = done == 0 ? 0 : 2 * n;  // rows of R carried over
    const Index take = std::min(m - done, 4 * n - top);
    work.resize(top + take, 2 * n);
    if (top > 0) work.topRows(top) = R;
    auto fresh_a = work.bottomLeftCorner(take, n);
    auto fresh_b = work.bottomRightCorner(take, n);
    fresh_a = A.middleRows(done, take);
    fresh_b = B.middleRows(done, take);
    multiply_by_power_of_two(fresh_a, -ea);
    multiply_by_power_of_two(fresh_b, -eb);
    triangular_factor_into<Stacked>(work, R);
    done += take;
  }
}

// spd-tls's estimate, or false where spd_total_least_squares fails (no start, no minimizer).
template <int MaxN>
bool spd_tls(const BasicReduction<MaxN>& data, int max_iterations, SquareMatrix<MaxN>& X_s) {
  const std::optional<double> r_s = spd_tls_noise_ratio(data);
  if (!r_s) return false;
  SpdTlsKernel<MaxN> k;
  if (!spd_tls_solve(data, *r_s, max_iterations, k) || k.unbounded) return false;
  X_s = k.X_s;
  return true;
}

// Where TLS's result is needed by several methods, it is computed once.
template <int MaxN>
bool estimate_bounded(const Eigen::Ref<const MatrixXd>& A, const Eigen::Ref<const MatrixXd>& B,
                      const std::vector<Method>& methods, std::vector<MatrixXd>& X) {
  using Matrix = SquareMatrix<MaxN>;
  const int ea = scale_exponent(A).value_or(0);
  const int eb = scale_exponent(B).value_or(0);
  BasicReduction<MaxN> data;
  data.options.diagnostics = false;
  {
    typename BasicReduction<MaxN>::Factor R;
    small_factor<MaxN>(A, B, ea, eb, R);
    // R11's singular vectors only when a method uses them (the values do not depend on them).
    const bool vectors_a = std::any_of(methods.begin(), methods.end(), uses_vectors_a);
    reduce_into(R, A.rows(), A.cols(), ea, eb, data, vectors_a);
  }
  const Index n = data.n;
  const FitOptions defaults;
  TlsKernel<MaxN> tls;
  bool tls_done = false;
  Matrix X_s;
  X.resize(methods.size());
  for (std::size_t i = 0; i < methods.size(); ++i) {
    bool ok = true;
    switch (methods[i]) {
      case Method::LeastSquares:
        least_squares_kernel(data, X_s);
        break;
      case Method::SymmetricProcrustes:
        procrustes_kernel(data, X_s);
        break;
      case Method::Spde:
        ok = data.rank_a == n;
        if (ok) spde_kernel(data, X_s);
        break;
      case Method::TotalLeastSquares:
      case Method::TotalLeastSquaresSymmetric:
      case Method::TotalLeastSquaresPsd:
        if (!tls_done) {
          tls_kernel(data, tls);
          tls_done = true;
        }
        ok = tls.exists;
        if (!ok) break;
        if (methods[i] == Method::TotalLeastSquares) {
          X_s = tls.X_s;
        } else if (methods[i] == Method::TotalLeastSquaresSymmetric) {
          X_s = symmetric_part(tls.X_s);
        } else {
          ok = tls.X_s.allFinite() && nearest_spd_kernel<MaxN>(tls.X_s, EigenvalueFloor{}, X_s);
        }
        break;
      case Method::SpdTotalLeastSquares:
        ok = spd_tls(data, defaults.max_iterations, X_s);
        break;
      case Method::PsdLeastSquares: {
        PsdLsKernel<MaxN> k;
        ok = psd_ls_kernel(data, 0.0, defaults.max_iterations, k);
        if (ok) X_s = k.X_s;
        break;
      }
      case Method::Auto: {
        const AutoChoice choice = auto_choice(data, noise_variance(data));
        ok = choice.method == Method::Spde ? (spde_kernel(data, X_s), true)
                                           : spd_tls(data, defaults.max_iterations, X_s);
        ok = ok && clearly_positive_definite(X_s);
        if (!ok) {  // the boundary: psd-ls with auto's floor, as auto_fit
          PsdLsKernel<MaxN> k;
          ok = psd_ls_kernel(data, auto_floor(data), defaults.max_iterations, k);
          if (ok) X_s = k.X_s;
        }
        break;
      }
    }
    if (ok) {
      X[i] = times_power_of_two(X_s, eb - ea);
      ok = X[i].allFinite();  // an estimate beyond the double range is a failure, as in fit()
    }
    if (!ok) X[i].resize(0, 0);
  }
  return true;
}

}  // namespace

bool estimate_small(const Eigen::Ref<const MatrixXd>& A, const Eigen::Ref<const MatrixXd>& B,
                    const std::vector<Method>& methods, std::vector<MatrixXd>& X) {
  const Index n = A.cols();
#ifdef SPDFIT_NO_SMALL_PROBLEM_KERNELS
  (void)n, (void)B, (void)methods, (void)X;
  return false;  // built without them (SPDFIT_SMALL_PROBLEM_KERNELS=OFF): the general path
#else
  if (n > kSmallProblemMaxN) return false;
  if (n < 1) throw std::invalid_argument("the data must have at least one column");
  check_data(A, B, n, n);  // the experiments' X is square
  if (A.rows() < n) throw std::invalid_argument(too_few_rows(A.rows(), n));
  if (n <= 2) return estimate_bounded<2>(A, B, methods, X);
  return estimate_bounded<kSmallProblemMaxN>(A, B, methods, X);
#endif
}

}  // namespace spdfit::detail
