// Internal: the reduction of a triangular factor to the small matrices the estimators' kernels
// work on (reduce_into, defined in reduction.cpp and instantiated there for every bound of
// SPDFIT_FOR_EACH_MAX_N), and the factor of [A, B / noise_ratio] with the noise estimate made
// from it, which TLS and every method's diagnostics share.
#pragma once

#include <Eigen/Core>
#include <cmath>
#include <cstdint>
#include <optional>

#include "factor/basic_reduction.hpp"
#include "spdfit/fit_options.hpp"
#include "spdfit/lazy_optional.hpp"
#include "spdfit/method.hpp"
#include "spdfit/reduction.hpp"
#include "spdfit/triangular_factor.hpp"

namespace spdfit::detail {

/// Fills `out` (all but `options`, which the caller sets) from the (n + d) x (n + d) triangular
/// factor R of the data (A with n columns, B with d = R.cols() - n) scaled by 2^-exponent_a,
/// 2^-exponent_b, accumulated from m >= n rows: the SVD of R11, the triangular factor of B and
/// its singular values, the ranks. Cost O((n + d)^3). Without `vectors_a`, R11's singular
/// vectors U_a and V_a are left empty (uses_vectors_a says which methods need them).
template <int MaxN>
void reduce_into(const typename BasicReduction<MaxN>::Factor& R, Eigen::Index m, Eigen::Index n, int exponent_a,
                 int exponent_b, BasicReduction<MaxN>& out, bool vectors_a = true);

/// The reduction `method` needs and no more (reduce computes everything, for any method): for
/// one method's fit, without R11's singular vectors when the method does not use them.
Reduction reduce_for(const TriangularFactor& factor, const FitOptions& options, Method method);

/// The (n + d) x (n + d) factor of [A, B / noise_ratio] in a common scaling 2^-e of A and B (what
/// TLS and the noise estimate decompose).
template <int MaxN>
void tls_factor(const BasicReduction<MaxN>& data, typename BasicReduction<MaxN>::Factor& R, int& e);

/// The noise estimate sigma^2 = sum_{i>n} s_i^2 / (d (m - n)), s_i the singular values of
/// [A, B / noise_ratio] in the data's units (of A): unbiased for independent noise of variance
/// sigma^2 in every entry of A (and noise_ratio^2 sigma^2 in B) when A_true X = B_true. Nothing
/// when m <= n. Cost O((n + d)^3).
template <int MaxN>
std::optional<double> noise_variance(const BasicReduction<MaxN>& data);

/// noise_variance from the singular values s (descending, n + d of them) of tls_factor's R, which
/// is scaled by 2^-e, for m > n rows: the one formula for the noise estimate's own SVD and TLS's.
template <typename Vector>
double noise_variance_from(const Vector& s, Eigen::Index m, Eigen::Index n, int e) {
  // Under the TLS model the d smallest singular values of [A, B / r] carry only noise: their
  // squares sum to sigma^2 times d (m - n) in expectation (the unbiased estimate). At
  // m < n + d the factor's bottom rows are zero, and so are the trailing singular values.
  const Eigen::Index d = s.size() - n;
  const double tail = s.tail(d).norm();
  return std::ldexp(tail * tail / (static_cast<double>(d) * static_cast<double>(m - n)), 2 * e);
}

/// The data's noise estimate (noise_variance), computed at the first request of any method's fit,
/// auto's choice or the bootstrap, and kept in the reduction for the others.
inline std::optional<double> data_noise_variance(const DynamicReduction& data) {
  return data.noise_var.get([&data] { return noise_variance(data); });
}

/// Diagnostics::noise_sigma for a fit of `data`: deferred to its first read when `data` belongs to
/// a Reduction (is owned by a shared_ptr), else computed now; nothing when m <= n.
LazyOptional noise_sigma_of(const DynamicReduction& data);

/// Diagnostics::cond_a_scaled (of_b false) or cond_b_scaled for a fit of `data` that reports
/// every diagnostic: reduce_into's number where it computed one, else deferred to its first read
/// (computed now when `data` has no shared owner), once per reduction.
LazyDouble scaled_condition_of(const DynamicReduction& data, bool of_b);

/// How many times noise_variance has run in this process: for the tests that check the noise
/// estimate is computed only when it is read, and once.
std::uint64_t noise_variance_runs();

}  // namespace spdfit::detail
