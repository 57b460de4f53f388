#include "spdfit/fit.hpp"

#include <array>
#include <optional>

#include "factor/reduce.hpp"
#include "estimators/kernels.hpp"
#include "estimators/noise_weights.hpp"
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

namespace {

// `method` on data whose noise model it cannot use (noise_refusal: spde always, the others when a
// covariance is singular where they need it to be definite): run without the model, saying why.
FitResult fit_without_noise(const Reduction& data, Method method, const std::string& why) {
  FitResult result = fit(detail::without_noise(data), method);
  result.warnings.push_back(Warning(Code::NoiseModelNotice, std::string(to_string(method)) + " ran without the noise model: " + why));
  return result;
}

}  // namespace

std::vector<FitResult> fit_all(const Reduction& data) {
  const std::optional<NoiseModel>& noise = detail::data_of(data).options.noise;
  std::vector<FitResult> results;
  if (data.d() != data.n()) {  // a non-square X: the methods that fit one
    for (Method method : kAllMethods) {
      if (!fits_non_square(method)) continue;
      const std::optional<std::string> refusal = detail::noise_refusal(noise, method);
      results.push_back(refusal ? fit_without_noise(data, method, *refusal) : fit(data, method));
    }
    return results;
  }
  results.reserve(kAllMethods.size());
  // The TLS family shares one SVD of [A B]; every other method shares the reduction.
  std::optional<std::array<FitResult, 3>> tls_family;
  for (Method method : kAllMethods) {
    const std::optional<std::string> refusal = detail::noise_refusal(noise, method);
    switch (method) {
      case Method::TotalLeastSquares:
      case Method::TotalLeastSquaresSymmetric:
      case Method::TotalLeastSquaresPsd:
        if (!tls_family) {
          tls_family = detail::total_least_squares_family(refusal ? detail::without_noise(data) : data);
          if (refusal) {
            for (FitResult& r : *tls_family) {
              r.warnings.push_back(Warning(Code::NoiseModelNotice, std::string(to_string(r.method)) + " ran without the noise model: " + *refusal));
            }
          }
        }
        results.push_back(std::move((*tls_family)[method == Method::TotalLeastSquares            ? 0
                                                  : method == Method::TotalLeastSquaresSymmetric ? 1
                                                                                                 : 2]));
        break;
      default:
        results.push_back(refusal ? fit_without_noise(data, method, *refusal) : fit(data, method));
    }
  }
  return results;
}

std::vector<FitResult> fit_all(const Eigen::Ref<const MatrixXd>& A, const Eigen::Ref<const MatrixXd>& B,
                               const FitOptions& options) {
  return fit_all(reduce(TriangularFactor::from_data(A, B), options));
}

}  // namespace spdfit
