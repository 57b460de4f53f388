#include "spdfit/spd_total_least_squares.hpp"

#include <cmath>
#include <string>

#include "estimators/diagnostics.hpp"
#include "estimators/kernels.hpp"
#include "estimators/psd_ls_kernel.hpp"
#include "estimators/spd_ml_boundary.hpp"
#include "estimators/spd_ml_kernel.hpp"
#include "estimators/spd_tls_kernel.hpp"

namespace spdfit {

using Eigen::Index;
using Eigen::MatrixXd;

namespace {

// The first-order conditions at a converged boundary estimate, relative to the criterion: Newton
// stops at 1e-10, and the certificate, computed from X afresh, adds rounding of about m eps times
// the gradient's terms; 1e-8 leaves room for both (the unit tests' KKT tolerance).
constexpr double kCertificateTolerance = 1e-8;

// Sigma_A = 0: the criterion is sum_i r_i^T Sigma_B^-1 r_i, a convex quadratic, and its infimum over
// the positive definite matrices is weighted psd-ls's minimum over the semidefinite ones (floor 0),
// solved exactly there with its certificate, on the boundary too.
FitResult exact_a(const detail::DynamicReduction& data) {
  FitResult result = detail::psd_least_squares_scaled(data, 0.0);
  result.method = Method::SpdTotalLeastSquares;
  if (result.ok() && !detail::clearly_positive_definite(result.X)) {
    result.warnings.push_back(Warning(Code::Boundary, 
        "the infimum of the likelihood criterion over the positive definite matrices is on the boundary: A is "
        "exact, so it is weighted least squares, whose minimizer over the positive semidefinite matrices is "
        "singular (smallest eigenvalue " + detail::format_number(result.diagnostics.min_eigenvalue.value_or(0.0)) +
        ")"));
  }
  return result;
}

}  // namespace

FitResult spd_total_least_squares(const Reduction& reduction) {
  const detail::DynamicReduction& data = detail::data_of(reduction, Method::SpdTotalLeastSquares);
  const Index n = data.n;
  constexpr Method method = Method::SpdTotalLeastSquares;

  // With a noise model the likelihood criterion, dimensionless (the same in the factor's units);
  // without, the TLS criterion, 2^-2ea f in the factor's units with the noise ratio r_s.
  const std::optional<detail::ScaledNoise> noise = detail::scaled_noise(data);
  if (noise && noise->a_zero) return exact_a(data);
  const std::string criterion_name = noise ? "likelihood criterion" : "TLS criterion";
  const int criterion_exponent = noise ? 0 : 2 * data.exponent_a;
  detail::SpdTlsKernel<Eigen::Dynamic> k;
  bool started = false;
  std::optional<double> r_s;
  if (noise) {
    started = detail::spd_ml_solve(data, *noise, data.options.max_iterations, k);
  } else {
    r_s = detail::spd_tls_noise_ratio(data);
    if (!r_s) {
      return detail::failure(method, data,
                             "spd-tls: the noise ratio " + detail::format_number(data.options.noise_ratio) +
                                 " times the ratio of the scales of A and B is out of floating-point range: "
                                 "rescale A and B to comparable sizes (and the noise ratio with them)");
    }
    started = detail::spd_tls_solve(data, *r_s, data.options.max_iterations, k);
  }
  if (!started) {
    return detail::failure(
        method, data,
        "spd-tls: no positive definite starting point: " +
            (data.rank_a < n ? "A is rank-deficient (rank " + std::to_string(data.rank_a) + " < n = " +
                                   std::to_string(n) + "), so SPDE is undefined, "
             : data.rank_b < n ? std::string("SPDE is singular (B has rank ") + std::to_string(data.rank_b) +
                                     " < n = " + std::to_string(n) + "), "
                               : std::string("SPDE is not positive definite, ")) +
            "and the symmetric part of the TLS estimate is not positive definite (or TLS has no solution): "
            "collect data that excite every direction of A and B");
  }
  if (k.unbounded) {
    return detail::failure(
        method, data,
        "spd-tls: the " + criterion_name +
            " has no minimizer over the positive definite matrices: it keeps "
            "decreasing as an eigenvalue of X grows without bound (the data are too noisy for total least "
            "squares: few rows m for n, or noise comparable to the signal); use spde, or collect more data");
  }
  std::vector<Warning> warnings;
  Diagnostics d;
  d.iterations = k.iterations;
  // ||X^1/2 grad f X^1/2|| has the units of f.
  d.gradient_norm = std::ldexp(k.gradient_norm, criterion_exponent);
  d.converged = k.converged;
  if (!k.converged) {
    warnings.push_back(Warning(Code::NotConverged, "spd-tls did not converge in " + std::to_string(k.iterations) +
                       " iterations (||X^1/2 grad f X^1/2||_F = " + detail::format_number(*d.gradient_norm) +
                       " against the " + criterion_name + " f = " +
                       detail::format_number(std::ldexp(k.criterion, criterion_exponent)) +
                       "): returning the best iterate; raise the iteration limit (" +
                       std::to_string(data.options.max_iterations) + ")"));
  }
  if (k.boundary_zeros > 0) {
    // The constrained problem's first-order conditions at the returned X, from X itself (without
    // a noise model the TLS criterion is the likelihood criterion with Sigma_A = I, Sigma_B = r^2 I).
    d.boundary_certificate = detail::spd_ml_certificate(
        data, noise ? *noise : detail::equal_scaled_noise(n, *r_s * *r_s), k.X_s, n - k.boundary_zeros);
    warnings.push_back(Warning(Code::Boundary, "the infimum of the " + criterion_name + " over the positive definite matrices is on the boundary: "
                       "the criterion keeps decreasing as " + std::to_string(k.boundary_zeros) +
                       " eigenvalue(s) of X go to zero, so the estimate is its minimizer over the positive "
                       "semidefinite matrices (rank " + std::to_string(n - k.boundary_zeros) +
                       "; `certificate` holds the optimality conditions), not positive definite"));
    // The stopping rule judged the iteration's own coordinates and rounding level; the certificate
    // judges X itself. Where they disagree (the iteration stopped far from a point of the
    // conditions, as where the criterion's infimum is near infinity), converged says so.
    const BoundaryCertificate& c = *d.boundary_certificate;
    const bool certified = c.stationarity <= kCertificateTolerance && c.cross_block <= kCertificateTolerance &&
                           c.multiplier_min_eig >= -kCertificateTolerance;
    if (k.converged && !certified) {
      d.converged = false;
      warnings.push_back(Warning(Code::NotConverged,
                                 "spd-tls stopped on the boundary where the first-order conditions do not hold "
                                 "(`certificate`: stationarity " + detail::format_number(c.stationarity) +
                                 ", cross_block " + detail::format_number(c.cross_block) + ", multiplier_min_eig " +
                                 detail::format_number(c.multiplier_min_eig) +
                                 ", relative to the criterion): the estimate is not its constrained minimizer"));
    }
  }
  return detail::finish(method, data, k.X_s, std::move(d), std::move(warnings));
}

FitResult spd_total_least_squares(const Eigen::Ref<const MatrixXd>& A, const Eigen::Ref<const MatrixXd>& B,
                                  const FitOptions& options) {
  return spd_total_least_squares(reduce(TriangularFactor::from_data(A, B), options));
}

}  // namespace spdfit
