#include "spdfit/psd_least_squares.hpp"

#include <Eigen/Cholesky>
#include <cmath>
#include <stdexcept>
#include <string>

#include "estimators/diagnostics.hpp"
#include "spdfit/outcome.hpp"
#include "estimators/noise_weights.hpp"
#include "numerics/linalg.hpp"
#include "estimators/psd_ls_kernel.hpp"

namespace spdfit {

using Eigen::Index;
using Eigen::MatrixXd;

namespace detail {

namespace {

// The weighted problem's estimate and certificate in `k` from the whitened kernel's: X_s back in
// the data's factor units, and the KKT quantities of min sum_i r_i^T Sigma_B^-1 r_i / 2 over
// X >= epsilon I computed from that X (S = sym(R11^T (R11 X - R12) Sigma_B^-1)); the kernel's relative
// KKT residual and duality gap, dimensionless, are the whitened problem's (the same problem in
// other coordinates). False when an eigensolver fails.
bool weighted_certificate(const DynamicReduction& data, const ScaledNoise& noise, const WhitenedB& w,
                          double epsilon_s, PsdLsKernel<Eigen::Dynamic>& k) {
  k.X_s = unwhiten_b(w, k.X_s);
  MatrixXd Y = k.X_s;
  Y.diagonal().array() -= epsilon_s;
  const MatrixXd residual = data.R11 * k.X_s - data.R12;
  const MatrixXd S = symmetric_part(MatrixXd(data.R11.transpose() * residual *
                                             noise.cov_b.llt().solve(MatrixXd::Identity(data.d, data.d))));
  Eigen::VectorXd wy, ws;
  if (!symmetric_eigen(Y, wy) || !symmetric_eigen(S, ws)) return false;
  k.primal_min_eig = wy(0);
  k.dual_min_eig = ws(0);
  k.complementarity = Y.cwiseProduct(S).sum();
  return true;
}

}  // namespace

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
  std::vector<Warning> warnings;
  const std::optional<ScaledNoise> noise = scaled_noise(data);
  if (noise) {
    // Weighted by Sigma_B^-1: the unweighted problem on the whitened data with the floor 0
    // (whiten_b), and the certificate recomputed for the weighted problem from the returned X.
    if (!noise->b_definite) throw_noise_refusal(*noise_refusal(data.options.noise, method), method, data.options.noise);
    const WhitenedB w = whiten_b(data, *noise, epsilon_s, true);
    if (!detail::psd_ls_kernel(w.data, 0.0, data.options.max_iterations, k) ||
        !weighted_certificate(data, *noise, w, epsilon_s, k)) {
      return detail::failure(method, data, "psd-ls: an eigendecomposition did not converge");
    }
    if (auto warning = ignored_noise_warning(data, method)) warnings.push_back(*warning);
  } else if (!detail::psd_ls_kernel(data, epsilon_s, data.options.max_iterations, k)) {
    return detail::failure(method, data, "psd-ls: an eigendecomposition did not converge");
  }
  if (data.rank_a < n) {
    warnings.push_back(Warning(Code::RankDeficient, "A is rank-deficient (rank " + std::to_string(data.rank_a) + " < n = " + std::to_string(n) +
                       "): the constrained minimizer is not unique"));
  }
  if (!k.converged) {
    warnings.push_back(Warning(Code::NotConverged, "psd-ls did not converge in " + std::to_string(k.iterations) +
                       " iterations (relative KKT residual " + detail::format_number(k.kkt_residual) +
                       " > 1e-12): returning the best feasible iterate; raise the iteration limit (" +
                       std::to_string(data.options.max_iterations) + ")"));
  }
  Diagnostics d;
  d.iterations = k.iterations;
  d.gradient_norm = k.kkt_residual;
  d.converged = k.converged;
  PsdCertificate c;
  // S = sym(A^T (A X - B)) has the units of A B; weighted, S = sym(A^T (A X - B) Sigma_B^-1) those of
  // A / B, and <X - epsilon I, S> is dimensionless.
  c.primal_min_eig = std::ldexp(k.primal_min_eig, eb - ea);
  c.dual_min_eig = std::ldexp(k.dual_min_eig, noise ? ea - eb : ea + eb);
  c.complementarity = std::ldexp(k.complementarity, noise ? 0 : 2 * eb);
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
