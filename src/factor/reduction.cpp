#include "spdfit/reduction.hpp"

#include <stdexcept>
#include <string>
#include <utility>

#include "estimators/kernels.hpp"
#include "numerics/linalg.hpp"

namespace spdfit {

namespace detail {

template <int MaxN>
void reduce_into(const typename BasicReduction<MaxN>::Factor& R, Eigen::Index m, int exponent_a,
                 int exponent_b, BasicReduction<MaxN>& out) {
  using Matrix = typename BasicReduction<MaxN>::Matrix;
  const Eigen::Index n = R.cols() / 2;
  out.m = m;
  out.n = n;
  out.exponent_a = exponent_a;
  out.exponent_b = exponent_b;
  out.R11 = R.topLeftCorner(n, n);
  out.R12 = R.topRightCorner(n, n);
  out.R22 = R.bottomRightCorner(n, n);

  // A = Q1 R11, so A and R11 share their singular values and right singular vectors.
  BasicSvd<Matrix> a;
  svd_into(out.R11, a);
  out.U_a = std::move(a.U);
  out.V_a = std::move(a.V);
  out.s_a = std::move(a.s);

  // B = Q [R12; R22]: its triangular factor R_b has B^T B = R_b^T R_b without forming B^T B.
  using Stacked = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::ColMajor,
                                BasicReduction<MaxN>::kMaxFactor, MaxN>;
  triangular_factor_into<Stacked>(R.rightCols(n), out.R_b);
  BasicSvd<Matrix> b;
  svd_into(out.R_b, b, false, false);
  out.s_b = std::move(b.s);

  const double cutoff = out.options.rank_cutoff(m, n);
  out.rank_a = numerical_rank(out.s_a, cutoff);
  out.rank_b = numerical_rank(out.s_b, cutoff);
}

#define SPDFIT_INSTANTIATE(MaxN)                                                                  \
  template void reduce_into<MaxN>(const typename BasicReduction<MaxN>::Factor&, Eigen::Index, int, int, \
                                  BasicReduction<MaxN>&);
SPDFIT_FOR_EACH_MAX_N(SPDFIT_INSTANTIATE)
#undef SPDFIT_INSTANTIATE

}  // namespace detail

Reduction reduce(const TriangularFactor& factor, const FitOptions& options) {
  std::string error;
  if (!options.is_valid(&error)) throw std::invalid_argument(error);
  const Eigen::Index n = factor.n();
  if (factor.rows() < n) {
    throw std::invalid_argument(detail::too_few_rows(factor.rows(), n));
  }
  auto r = std::make_shared<detail::DynamicReduction>();
  r->options = options;
  detail::reduce_into(factor.R(), factor.rows(), factor.exponent_a(), factor.exponent_b(), *r);
  return Reduction(std::move(r));
}

Eigen::Index Reduction::m() const { return data_ ? data_->m : 0; }
Eigen::Index Reduction::n() const { return data_ ? data_->n : 0; }
Eigen::Index Reduction::rank_a() const { return data_ ? data_->rank_a : 0; }
Eigen::Index Reduction::rank_b() const { return data_ ? data_->rank_b : 0; }
const FitOptions& Reduction::options() const {
  static const FitOptions defaults;
  return data_ ? data_->options : defaults;
}

}  // namespace spdfit
