#include "spdfit/reduction.hpp"

#include <stdexcept>
#include <string>

#include "linalg.hpp"

namespace spdfit {

Reduction reduce(const TriangularFactor& factor, const FitOptions& options) {
  std::string error;
  if (!options.is_valid(&error)) throw std::invalid_argument(error);
  const Eigen::Index n = factor.n();
  if (factor.rows() < n) {
    throw std::invalid_argument("the data has " + std::to_string(factor.rows()) + " rows but " +
                                std::to_string(n) + " columns: at least as many rows as columns are needed");
  }
  Reduction r;
  r.m = factor.rows();
  r.n = n;
  r.exponent_a = factor.exponent_a();
  r.exponent_b = factor.exponent_b();
  r.R11 = factor.R11();
  r.R12 = factor.R12();
  r.R22 = factor.R22();
  r.options = options;

  // A = Q1 R11, so A and R11 share their singular values and right singular vectors.
  detail::Svd a = detail::svd(r.R11);
  r.U_a = std::move(a.U);
  r.V_a = std::move(a.V);
  r.s_a = std::move(a.s);

  // B = Q [R12; R22]: its triangular factor R_b has B^T B = R_b^T R_b without forming B^T B.
  Eigen::MatrixXd stacked(2 * n, n);
  stacked << r.R12, r.R22;
  r.R_b = detail::triangular_factor(stacked);
  r.s_b = detail::singular_values(r.R_b);

  const double cutoff = options.rank_cutoff(r.m, n);
  r.rank_a = detail::numerical_rank(r.s_a, cutoff);
  r.rank_b = detail::numerical_rank(r.s_b, cutoff);
  return r;
}

}  // namespace spdfit
