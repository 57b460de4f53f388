#include "spdfit/spd_total_least_squares.hpp"

#include <cmath>
#include <string>

#include "estimators/diagnostics.hpp"
#include "estimators/kernels.hpp"
#include "estimators/spd_tls_kernel.hpp"

namespace spdfit {

using Eigen::Index;
using Eigen::MatrixXd;

FitResult spd_total_least_squares(const Reduction& reduction) {
  const detail::DynamicReduction& data = detail::data_of(reduction, Method::SpdTotalLeastSquares);
  const Index n = data.n;
  constexpr Method method = Method::SpdTotalLeastSquares;

  // In the factor's units the criterion is 2^-2ea f, with the noise ratio r_s.
  const std::optional<double> r_s = detail::spd_tls_noise_ratio(data);
  if (!r_s) {
    return detail::failure(method, data,
                           "spd-tls: the noise ratio " + detail::format_number(data.options.noise_ratio) +
                               " times the ratio of the scales of A and B is out of floating-point range: "
                               "rescale A and B to comparable sizes (and the noise ratio with them)");
  }

  detail::SpdTlsKernel<Eigen::Dynamic> k;
  if (!detail::spd_tls_solve(data, *r_s, data.options.max_iterations, k)) {
    return detail::failure(
        method, data,
        "spd-tls: no positive definite starting point: " +
            (data.rank_a < n ? "A is rank-deficient (rank " + std::to_string(data.rank_a) + " < n = " +
                                   std::to_string(n) + "), so SPDE is undefined, "
                             : std::string("SPDE is singular (B has rank ") + std::to_string(data.rank_b) +
                                   " < n = " + std::to_string(n) + "), ") +
            "and the symmetric part of the TLS estimate is not positive definite (or TLS has no solution): "
            "collect data that excite every direction of A and B");
  }
  if (k.unbounded) {
    return detail::failure(
        method, data,
        "spd-tls: the TLS criterion has no minimizer over the positive definite matrices: it keeps "
        "decreasing as an eigenvalue of X grows without bound (the data are too noisy for total least "
        "squares: few rows m for n, or noise comparable to the signal); use spde, or collect more data");
  }
  std::vector<std::string> warnings;
  Diagnostics d;
  d.iterations = k.iterations;
  // ||X^1/2 grad f X^1/2|| has the units of f: 2^2ea times its scaled value.
  d.gradient_norm = std::ldexp(k.gradient_norm, 2 * data.exponent_a);
  d.converged = k.converged;
  if (!k.converged) {
    warnings.push_back("spd-tls did not converge in " + std::to_string(k.iterations) +
                       " iterations (||X^1/2 grad f X^1/2||_F = " + detail::format_number(*d.gradient_norm) +
                       " against the criterion f = " +
                       detail::format_number(std::ldexp(k.criterion, 2 * data.exponent_a)) +
                       "): returning the best iterate; raise the iteration limit (" +
                       std::to_string(data.options.max_iterations) + ")");
  }
  if (k.boundary_zeros > 0) {
    warnings.push_back("the infimum of the TLS criterion over the positive definite matrices is on the boundary: "
                       "the criterion keeps decreasing as " + std::to_string(k.boundary_zeros) +
                       " eigenvalue(s) of X go to zero, so the estimate is the positive semidefinite limit "
                       "(rank " + std::to_string(n - k.boundary_zeros) + "), not positive definite");
  }
  return detail::finish(method, data, k.X_s, std::move(d), std::move(warnings));
}

FitResult spd_total_least_squares(const Eigen::Ref<const MatrixXd>& A, const Eigen::Ref<const MatrixXd>& B,
                                  const FitOptions& options) {
  return spd_total_least_squares(reduce(TriangularFactor::from_data(A, B), options));
}

}  // namespace spdfit
