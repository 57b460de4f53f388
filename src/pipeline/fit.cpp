#include "spdfit/fit.hpp"

#include <array>
#include <optional>

#include "estimators/kernels.hpp"
#include "spdfit/auto.hpp"
#include "spdfit/least_squares.hpp"
#include "spdfit/psd_least_squares.hpp"
#include "spdfit/spd_total_least_squares.hpp"
#include "spdfit/spde.hpp"
#include "spdfit/symmetric_procrustes.hpp"
#include "spdfit/total_least_squares.hpp"
#include "uncertainty/bootstrap.hpp"

namespace spdfit {

using Eigen::MatrixXd;

FitResult fit(const Reduction& data, Method method) {
  switch (method) {
    case Method::LeastSquares:
      return least_squares(data);
    case Method::SymmetricProcrustes:
      return symmetric_procrustes(data);
    case Method::TotalLeastSquares:
      return total_least_squares(data);
    case Method::TotalLeastSquaresSymmetric:
      return total_least_squares_symmetric(data);
    case Method::TotalLeastSquaresPsd:
      return total_least_squares_psd(data);
    case Method::Spde:
      return spde(data);
    case Method::SpdTotalLeastSquares:
      return spd_total_least_squares(data);
    case Method::PsdLeastSquares:
      return psd_least_squares(data);
    case Method::Auto:
      return auto_fit(data);
  }
  return spde(data);  // unreachable: every enumerator is handled above
}

FitResult fit(const Eigen::Ref<const MatrixXd>& A, const Eigen::Ref<const MatrixXd>& B, Method method,
              const FitOptions& options) {
  const Reduction data = detail::reduce_for(TriangularFactor::from_data(A, B), options, method);
  FitResult result = fit(data, method);
  if (options.bootstrap > 0 && result.ok()) detail::bootstrap_in_memory(result, A, B, data);
  return result;
}

std::vector<FitResult> fit_all(const Reduction& data) {
  std::vector<FitResult> results;
  if (data.d() != data.n()) {  // a non-square X: the methods that fit one
    for (Method method : kAllMethods) {
      if (fits_non_square(method)) results.push_back(fit(data, method));
    }
    return results;
  }
  results.reserve(kAllMethods.size());
  // The TLS family shares one SVD of [A B]; every other method shares the reduction.
  std::optional<std::array<FitResult, 3>> tls_family;
  for (Method method : kAllMethods) {
    switch (method) {
      case Method::TotalLeastSquares:
      case Method::TotalLeastSquaresSymmetric:
      case Method::TotalLeastSquaresPsd:
        if (!tls_family) tls_family = detail::total_least_squares_family(data);
        results.push_back(std::move((*tls_family)[method == Method::TotalLeastSquares            ? 0
                                                  : method == Method::TotalLeastSquaresSymmetric ? 1
                                                                                                 : 2]));
        break;
      default:
        results.push_back(fit(data, method));
    }
  }
  return results;
}

std::vector<FitResult> fit_all(const Eigen::Ref<const MatrixXd>& A, const Eigen::Ref<const MatrixXd>& B,
                               const FitOptions& options) {
  return fit_all(reduce(TriangularFactor::from_data(A, B), options));
}

}  // namespace spdfit
