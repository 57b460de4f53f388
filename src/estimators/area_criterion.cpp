#include "spdfit/area_criterion.hpp"

#include <cmath>
#include <stdexcept>

#include "estimators/diagnostics.hpp"
#include "numerics/linalg.hpp"

namespace spdfit {

using Eigen::MatrixXd;

std::optional<double> area_criterion(const Reduction& reduction, const Eigen::Ref<const MatrixXd>& X) {
  const detail::DynamicReduction& data = detail::data_of(reduction);
  if (!data.square()) {
    throw std::invalid_argument("area_criterion: A has " + std::to_string(data.n) + " columns but B has " +
                                std::to_string(data.d) + ": the area criterion needs a square X");
  }
  if (X.rows() != data.n || X.cols() != data.n) {
    throw std::invalid_argument("area_criterion: X must be " + std::to_string(data.n) + "x" +
                                std::to_string(data.n));
  }
  if (!X.allFinite()) throw std::invalid_argument("area_criterion: X contains NaN or Inf");
  if (X != X.transpose()) return std::nullopt;
  const MatrixXd X_s = detail::times_power_of_two(X, data.exponent_a - data.exponent_b);
  const auto f = detail::scaled_area_criterion(data, X_s);
  if (!f) return std::nullopt;
  return std::ldexp(*f, data.exponent_a + data.exponent_b);
}

std::optional<double> area_criterion(const Eigen::Ref<const MatrixXd>& A, const Eigen::Ref<const MatrixXd>& B,
                                     const Eigen::Ref<const MatrixXd>& X) {
  return area_criterion(reduce(TriangularFactor::from_data(A, B)), X);
}

}  // namespace spdfit
