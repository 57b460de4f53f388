#include "spdfit/fit.hpp"

#include <array>
#include <cmath>
#include <string>
#include <utility>
#include <vector>
#include <optional>
#include <stdexcept>

#include "factor/reduce.hpp"
#include "estimators/kernels.hpp"
#include "estimators/noise_weights.hpp"
#include "pipeline/log_rows.hpp"
#include "pipeline/offsets.hpp"
#include "pipeline/row_scores.hpp"
#include "robust/m_estimator.hpp"
#include "pipeline/sentinels.hpp"
#include "pipeline/units.hpp"
#include "spdfit/format.hpp"
#include "spdfit/outcome.hpp"
#include "spdfit/auto.hpp"
#include "spdfit/least_squares.hpp"
#include "spdfit/psd_least_squares.hpp"
#include "spdfit/spd_total_least_squares.hpp"
#include "spdfit/spde.hpp"
#include "spdfit/symmetric_procrustes.hpp"
#include "spdfit/total_least_squares.hpp"
#include "uncertainty/bootstrap.hpp"

// FitOptions::scale_a and scale_b (pipeline/units.hpp): here, beside fit(A, B, ...), their first user.
namespace spdfit::detail {

namespace {

Eigen::VectorXd unit_factors(const std::vector<double>& given, Eigen::Index columns, const char* option, const char* side) {
  if (given.empty()) return Eigen::VectorXd::Ones(columns);
  if (given.size() != 1 && static_cast<Eigen::Index>(given.size()) != columns) {
    throw OptionError("`" + std::string(option) + "` has " + std::to_string(given.size()) + " values but " + side +
                          " has " + std::to_string(columns) +
                          " columns: give one factor for every column, or one per column",
                      Code::OptionValue, option);
  }
  for (double f : given) {
    if (!(std::isfinite(f) && f > 0.0)) {
      throw OptionError("`" + std::string(option) + "` must be finite numbers > 0 (the factor each column of " + side +
                            " is multiplied by), not " + format_number(f),
                        Code::OptionValue, option);
    }
  }
  return given.size() == 1 ? Eigen::VectorXd::Constant(columns, given.front())
                           : Eigen::VectorXd(Eigen::Map<const Eigen::VectorXd>(given.data(), columns));
}

}  // namespace

std::optional<Units> units_of(const FitOptions& options, Eigen::Index n, Eigen::Index d) {
  if (options.scale_a.empty() && options.scale_b.empty()) return std::nullopt;
  return Units{unit_factors(options.scale_a, n, "scale_a", "A"), unit_factors(options.scale_b, d, "scale_b", "B")};
}

FitOptions options_in_units(const FitOptions& options, const Units& units) {
  FitOptions out = options;
  out.scale_a.clear();
  out.scale_b.clear();
  if (out.noise) out.noise = out.noise->resolved(units.a.size(), units.b.size()).scaled(units.a, units.b);
  return out;
}

void apply_units(const Units& units, Eigen::Ref<Eigen::MatrixXd> A, Eigen::Ref<Eigen::MatrixXd> B) {
  A = A * units.a.asDiagonal();
  B = B * units.b.asDiagonal();
}

TriangularFactor factor_in_units(const TriangularFactor& factor, const Units& units) {
  TriangularFactor out = factor;
  out.scale_columns(units.a, units.b);
  return out;
}

}  // namespace spdfit::detail

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

namespace {

// `body(A, B, options, tare)` on the data as fitted: in the units asked (scale_a, scale_b) and,
// with offsets rest, tared (the rest rows' means subtracted; `tare` then the one subtracted, else
// null), with the options that remain. The one home of that order for the fits of A and B.
template <typename Body>
auto as_fitted(const Eigen::Ref<const MatrixXd>& A, const Eigen::Ref<const MatrixXd>& B, const FitOptions& options,
               Body&& body) {
  const std::optional<detail::Units> units = detail::units_of(options, A.cols(), B.cols());
  if (!units) {
    if (options.offsets != Offsets::Rest) return body(A, B, options, static_cast<const detail::Tare*>(nullptr));
    const detail::TaredData tared = detail::tared_data(A, B, options);
    return body(tared.A, tared.B, detail::options_after_tare(options), &tared.tare);
  }
  MatrixXd A_units = A, B_units = B;
  detail::apply_units(*units, A_units, B_units);
  return as_fitted(A_units, B_units, detail::options_in_units(options, *units), std::forward<Body>(body));
}

}  // namespace

namespace detail {

FitResult fit_numbered(const Eigen::Ref<const MatrixXd>& A_given, const Eigen::Ref<const MatrixXd>& B_given,
                       Method method, const FitOptions& options_given, const RowNumbers& numbers) {
  return as_fitted(A_given, B_given, options_given, [&](const auto& A, const auto& B, const FitOptions& options,
                                                        const Tare* tare) {
    FitResult result;
    if (options.robust != RobustLoss::None) {  // rows reweighted: the M-estimator's own iterations
      detail::RobustFit robust = detail::robust_fit(A, B, method, options);
      result = std::move(robust.result);
      if (robust.factor) result.offsets = detail::offsets_of(result, *robust.factor, options, nullptr);
      if (result.robust) number_rows(*result.robust, numbers);
    } else {
      const TriangularFactor factor = TriangularFactor::from_data(A, B, options.offsets == Offsets::Estimate);
      const Reduction data = detail::reduce_for(factor, options, method);
      result = fit(data, method);
      if (options.bootstrap > 0 && result.ok()) detail::bootstrap_in_memory(result, A, B, data);
      result.offsets = detail::offsets_of(result, factor, options, nullptr);
      for (Warning& w : detail::offset_warnings(A, B, &factor, options)) result.warnings.push_back(std::move(w));
      if (std::optional<Warning> w = detail::dominant_rows_warning(A, B, result, factor, options, numbers)) {
        result.warnings.push_back(std::move(*w));
      }
    }
    if (tare) result.offsets = tare->offsets();
    if (std::optional<Warning> w = detail::sentinel_warning(A, B, numbers, options.robust != RobustLoss::None)) {
      result.warnings.insert(result.warnings.begin(), std::move(*w));
      if (!result.ok()) result.message += detail::sentinel_failure_note();
    }
    return result;
  });
}

std::optional<Warning> dominant_rows_check(const Eigen::Ref<const MatrixXd>& A_given,
                                           const Eigen::Ref<const MatrixXd>& B_given, Method method,
                                           const FitOptions& options, const RowNumbers& numbers) {
  return as_fitted(A_given, B_given, options, [&](const auto& A, const auto& B, const FitOptions& fitted,
                                                  const Tare*) -> std::optional<Warning> {
    FitOptions plain = fitted;
    plain.bootstrap = 0;
    plain.robust = RobustLoss::None;
    plain.robust_tuning.reset();
    const TriangularFactor factor = TriangularFactor::from_data(A, B, plain.offsets == Offsets::Estimate);
    FitResult result;
    try {
      result = fit(detail::reduce_for(factor, plain, method), method);
    } catch (const std::invalid_argument&) {
      return std::nullopt;  // data the method refuses: the commands' own fits say why
    }
    if (!result.ok()) return std::nullopt;
    result.offsets = detail::offsets_of(result, factor, plain, nullptr);
    return detail::dominant_rows_warning(A, B, result, factor, plain, numbers);
  });
}

void refit_robustly(const Eigen::Ref<const MatrixXd>& A, const Eigen::Ref<const MatrixXd>& B, const FitOptions& options,
                    std::vector<FitResult>& results, const RowNumbers& numbers,
                    std::vector<std::vector<Replicate>>* replicates) {
  if (replicates) replicates->assign(results.size(), {});
  if (options.robust == RobustLoss::None) return;
  for (std::size_t k = 0; k < results.size(); ++k) {
    FitResult& r = results[k];
    if (!detail::robust_applies(r.method)) continue;  // spde, without rows, as it is
    detail::RobustFit robust = detail::robust_fit(A, B, r.method, options);
    if (replicates) (*replicates)[k] = std::move(robust.replicates);
    r = std::move(robust.result);
    if (robust.factor) r.offsets = detail::offsets_of(r, *robust.factor, options, nullptr);
    if (r.robust) number_rows(*r.robust, numbers);
  }
}

}  // namespace detail

FitResult fit(const Eigen::Ref<const MatrixXd>& A, const Eigen::Ref<const MatrixXd>& B, Method method,
              const FitOptions& options) {
  return detail::fit_numbered(A, B, method, options, {});
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

std::vector<FitResult> fit_all(const Eigen::Ref<const MatrixXd>& A_given, const Eigen::Ref<const MatrixXd>& B_given,
                               const FitOptions& options_given) {
  return as_fitted(A_given, B_given, options_given, [](const auto& A, const auto& B, const FitOptions& options,
                                                       const detail::Tare* tare) {
    const TriangularFactor factor = TriangularFactor::from_data(A, B, options.offsets == Offsets::Estimate);
    FitOptions plain = options;  // with `robust`, the methods that weigh rows are refitted below
    plain.robust = RobustLoss::None;
    plain.robust_tuning.reset();
    std::vector<FitResult> results = fit_all(reduce(factor, plain));
    for (FitResult& r : results) r.offsets = detail::offsets_of(r, factor, options, nullptr);
    detail::refit_robustly(A, B, options, results, {});
    if (tare) {
      for (FitResult& r : results) r.offsets = tare->offsets();
    }
    return results;
  });
}

}  // namespace spdfit
