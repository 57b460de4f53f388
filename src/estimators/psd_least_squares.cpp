#include "spdfit/psd_least_squares.hpp"

#include <cmath>
#include <string>

#include "estimators/diagnostics.hpp"
#include "estimators/psd_ls_kernel.hpp"

namespace spdfit {

using Eigen::Index;
using Eigen::MatrixXd;

namespace detail {

FitResult psd_least_squares_scaled(const DynamicReduction& data, double epsilon_s) {
  const Index n = data.n;
  constexpr Method method = Method::PsdLeastSquares;
  const int ea = data.exponent_a, eb = data.exponent_b;
  if (!std::isfinite(epsilon_s)) {
    return detail::failure(method, data,
                           "psd-ls: the eigenvalue floor " + detail::format_number(data.options.min_eig) +
                               " is out of floating-point range in the units of the data");
  }
  detail::PsdLsKernel<Eigen::Dynamic> k;
  if (!detail::psd_ls_kernel(data, epsilon_s, data.options.max_iterations, k)) {
    return detail::failure(method, data, "psd-ls: an eigendecomposition did not converge");
  }
  std::vector<std::string> warnings;
  if (data.rank_a < n) {
    warnings.push_back("A is rank-deficient (rank " + std::to_string(data.rank_a) + " < n = " + std::to_string(n) +
                       "): the constrained minimizer is not unique");
  }
  if (!k.converged) {
    warnings.push_back("psd-ls did not converge in " + std::to_string(k.iterations) +
                       " iterations (relative KKT residual " + detail::format_number(k.kkt_residual) +
                       " > 1e-12): returning the best feasible iterate; raise the iteration limit (" +
                       std::to_string(data.options.max_iterations) + ")");
  }
  Diagnostics d;
  d.iterations = k.iterations;
  d.gradient_norm = k.kkt_residual;
  d.converged = k.converged;
  PsdCertificate c;
  c.primal_min_eig = std::ldexp(k.primal_min_eig, eb - ea);
  c.dual_min_eig = std::ldexp(k.dual_min_eig, ea + eb);
  c.complementarity = std::ldexp(k.complementarity, 2 * eb);
  c.duality_gap = k.duality_gap;
  d.certificate = c;
  return detail::finish(method, data, k.X_s, std::move(d), std::move(warnings));
}

}  // namespace detail

FitResult psd_least_squares(const Reduction& reduction) {
  const detail::DynamicReduction& data = detail::data_of(reduction, Method::PsdLeastSquares);
  // X_s = X 2^(ea - eb): the floor in the factor's units.
  return detail::psd_least_squares_scaled(data, std::ldexp(data.options.min_eig, data.exponent_a - data.exponent_b));
}

FitResult psd_least_squares(const Eigen::Ref<const MatrixXd>& A, const Eigen::Ref<const MatrixXd>& B,
                            const FitOptions& options) {
  return psd_least_squares(reduce(TriangularFactor::from_data(A, B), options));
}

}  // namespace spdfit
