#include "spdfit/reduction.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>

#include "factor/data_checks.hpp"
#include "factor/reduce.hpp"
#include "numerics/least_squares.hpp"
#include "numerics/linalg.hpp"

namespace spdfit {

namespace detail {

template <int MaxN>
void reduce_into(const typename BasicReduction<MaxN>::Factor& R, Eigen::Index m, Eigen::Index n, int exponent_a,
                 int exponent_b, BasicReduction<MaxN>& out, bool vectors_a) {
  using Matrix = typename BasicReduction<MaxN>::Matrix;
  const Eigen::Index d = R.cols() - n;
  out.m = m;
  out.n = n;
  out.d = d;
  out.exponent_a = exponent_a;
  out.exponent_b = exponent_b;
  out.R11 = R.topLeftCorner(n, n);
  out.R12 = R.topRightCorner(n, d);
  out.R22 = R.bottomRightCorner(d, d);

  // A = Q1 R11, so A and R11 share their singular values and right singular vectors.
  BasicSvd<Matrix> a;
  svd_into(out.R11, a, vectors_a, vectors_a);
  out.U_a = std::move(a.U);
  out.V_a = std::move(a.V);
  out.s_a = std::move(a.s);

  // B = Q [R12; R22]: its triangular factor R_b has B^T B = R_b^T R_b without forming B^T B.
  using Stacked = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::ColMajor,
                                BasicReduction<MaxN>::kMaxFactor, MaxN>;
  triangular_factor_into<Stacked>(R.rightCols(d), out.R_b);
  BasicSvd<Matrix> b;
  svd_into(out.R_b, b, false, false);
  out.s_b = std::move(b.s);

  // The ranks are decided on A and B with their columns scaled to unit norm (the columns of R11
  // and R_b have the norms of A's and B's), so that they do not depend on the units of each
  // column (numerics/least_squares.hpp). The scaled condition numbers are diagnostics: kept
  // where the rank needed the scaled SVD anyway, and cond(A D) computed where the warning about
  // an ill-conditioned A may need it; the others when first read (scaled_condition_of).
  const bool report = out.options.diagnostics;
  const bool all = report && out.options.reported_diagnostics;
  out.cond_a_scaled = out.cond_b_scaled = 0.0;
  out.rank_a = equilibrated_rank(out.R11, out.s_a, out.options.rank_cutoff(m, n),
                                 report ? &out.cond_a_scaled : nullptr, 1.0 / kIllConditionedRcond);
  out.rank_b = equilibrated_rank(out.R_b, out.s_b, out.options.rank_cutoff(m, d),
                                 all ? &out.cond_b_scaled : nullptr, std::numeric_limits<double>::infinity());
}

template <int MaxN>
void tls_factor(const BasicReduction<MaxN>& data, typename BasicReduction<MaxN>::Factor& R, int& e) {
  const Index n = data.n, d = data.d;
  // TLS is only invariant under a common scaling of A and B, so undo the separate scalings
  // of the factor into a common one, 2^-max(ea, eb) (exact: powers of two); then B / r.
  e = std::max(data.exponent_a, data.exponent_b);
  R.setZero(n + d, n + d);
  R.topLeftCorner(n, n) = times_power_of_two(data.R11, data.exponent_a - e);
  R.topRightCorner(n, d) = times_power_of_two(data.R12, data.exponent_b - e);
  R.bottomRightCorner(d, d) = times_power_of_two(data.R22, data.exponent_b - e);
  const double r = data.options.noise_ratio;
  if (r != 1.0) R.rightCols(d) /= r;
}

namespace {
std::atomic<std::uint64_t> noise_variance_count{0};
}  // namespace

std::uint64_t noise_variance_runs() { return noise_variance_count.load(std::memory_order_relaxed); }

LazyOptional noise_sigma_of(const DynamicReduction& data) {
  if (data.m <= data.n) return std::nullopt;
  const auto root = [](std::optional<double> variance) -> std::optional<double> {
    if (!variance) return std::nullopt;
    return std::sqrt(*variance);
  };
  std::shared_ptr<const DynamicReduction> owner = data.weak_from_this().lock();
  if (!owner) return root(data_noise_variance(data));
  return LazyOptional::deferred([owner = std::move(owner), root] { return root(data_noise_variance(*owner)); });
}

LazyDouble scaled_condition_of(const DynamicReduction& data, bool of_b) {
  const double known = of_b ? data.cond_b_scaled : data.cond_a_scaled;
  if (known > 0.0) return known;  // the rank or the warning needed it
  const auto compute = [of_b](const DynamicReduction& d) {
    const DataCache& cache = of_b ? d.cond_b_cache : d.cond_a_cache;
    return *cache.get([&d, of_b] {
      return std::optional<double>(equilibrated_condition_number(of_b ? d.R_b : d.R11));
    });
  };
  std::shared_ptr<const DynamicReduction> owner = data.weak_from_this().lock();
  if (!owner) return compute(data);
  return LazyDouble::deferred([owner = std::move(owner), compute] { return compute(*owner); });
}

template <int MaxN>
std::optional<double> noise_variance(const BasicReduction<MaxN>& data) {
  using Factor = typename BasicReduction<MaxN>::Factor;
  const Index n = data.n, m = data.dof_rows();
  if (m <= n) return std::nullopt;
  int e = 0;
  Factor R;
  tls_factor(data, R, e);
  BasicSvd<Factor> dec;
  svd_into(R, dec, false, false);
  noise_variance_count.fetch_add(1, std::memory_order_relaxed);
  return noise_variance_from(dec.s, m, n, e);
}

#define SPDFIT_INSTANTIATE(MaxN)                                                                  \
  template void reduce_into<MaxN>(const typename BasicReduction<MaxN>::Factor&, Eigen::Index, Eigen::Index, int, \
                                  int,                                                          \
                                  BasicReduction<MaxN>&, bool);                                               \
  template void tls_factor<MaxN>(const BasicReduction<MaxN>&, typename BasicReduction<MaxN>::Factor&, int&); \
  template std::optional<double> noise_variance<MaxN>(const BasicReduction<MaxN>&);
SPDFIT_FOR_EACH_MAX_N(SPDFIT_INSTANTIATE)
#undef SPDFIT_INSTANTIATE

}  // namespace detail

namespace detail {

Reduction reduction_of(std::shared_ptr<const DynamicReduction> data) { return Reduction(std::move(data)); }

// The reduction, with R11's singular vectors or without them (reduce and reduce_for).
Reduction reduce_with(const TriangularFactor& factor, const FitOptions& options, bool vectors_a) {
  std::string error;
  if (!options.is_valid(&error)) throw std::invalid_argument(error);
  if (!options.scale_a.empty() || !options.scale_b.empty()) {
    // The factor's data are in their units already: scaling is the caller's, before or after
    // factoring (fit(A, B, ...), fit_files; TriangularFactor::scale_columns).
    throw std::invalid_argument("`scale_a` and `scale_b` apply to data as given (fit(A, B, ...), fit_files), not to "
                                "a factor or a reduction: scale the factor (TriangularFactor::scale_columns) and "
                                "its noise model instead");
  }
  if (options.robust != RobustLoss::None) {
    throw std::invalid_argument("`robust` reweighs the rows of A and B: fit(A, B, ...) and fit_files in memory apply it, "
                                "not a factor or a reduction");
  }
  if (options.offsets == Offsets::Rest) {
    throw std::invalid_argument("`offsets` rest subtracts the rest rows' means from the data as given (fit(A, B, ...), "
                                "fit_files), not from a factor or a reduction: subtract them before factoring");
  }
  if (options.offsets == Offsets::Estimate && !factor.intercept()) {
    throw std::invalid_argument("`offsets` estimate needs the factor of [1 A B] (TriangularFactor with an intercept, "
                                "which fit(A, B, ...) and fit_files build), not of [A B]");
  }
  const Eigen::Index n = factor.n();
  if (factor.rows() < n) {
    throw std::invalid_argument(detail::too_few_rows(factor.rows(), n));
  }
  if (factor.intercept() && factor.rows() < n + 1) {
    throw InputError("with `offsets` estimate the data need at least n + 1 = " + std::to_string(n + 1) +
                         " rows (one goes to the offsets), not " + std::to_string(factor.rows()),
                     Code::DataShape, "offsets");
  }
  auto r = std::make_shared<detail::DynamicReduction>();
  r->options = options;
  r->centred = factor.intercept();
  // The noise model completed to the data's sizes, or refused (naming the option or rest file).
  if (options.noise) r->options.noise = options.noise->resolved(n, factor.d());
  detail::reduce_into(factor.R(), factor.rows(), n, factor.exponent_a(), factor.exponent_b(), *r, vectors_a);
  return Reduction(std::move(r));
}

Reduction reduce_for(const TriangularFactor& factor, const FitOptions& options, Method method) {
  return reduce_with(factor, options, uses_vectors_a(method));
}

}  // namespace detail

Reduction reduce(const TriangularFactor& factor, const FitOptions& options) {
  return detail::reduce_with(factor, options, true);
}

Eigen::Index Reduction::m() const { return data_ ? data_->m : 0; }
Eigen::Index Reduction::n() const { return data_ ? data_->n : 0; }
Eigen::Index Reduction::d() const { return data_ ? data_->d : 0; }
Eigen::Index Reduction::rank_a() const { return data_ ? data_->rank_a : 0; }
Eigen::Index Reduction::rank_b() const { return data_ ? data_->rank_b : 0; }
const FitOptions& Reduction::options() const {
  static const FitOptions defaults;
  return data_ ? data_->options : defaults;
}

}  // namespace spdfit
