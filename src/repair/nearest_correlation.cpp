#include "spdfit/nearest_correlation.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "estimators/diagnostics.hpp"
#include "numerics/linalg.hpp"
#include "repair/correlation_newton.hpp"
#include "repair/repair.hpp"

namespace spdfit {

using Eigen::Index;
using Eigen::MatrixXd;
using Eigen::VectorXd;

namespace {

// min ||W^1/2 (X - C) W^1/2||_F over symmetric X with diag(X) = d and X >= F, W = diag(w), F the
// floor's diagonal: floor I, or with floor_of_correlation floor D, D = diag(d) (the correlation
// matrix D^-1/2 X D^-1/2 >= floor I: the diagonal-keeping repair's relative floor).
struct FixedDiagonalProblem {
  MatrixXd S;  // the symmetric part of C
  VectorXd d;  // every entry > the floor's
  VectorXd w;  // every entry > 0
  double floor = 0.0;
  bool floor_of_correlation = false;
  const char* option = "`min_eig`";  // the option the floor came from, for messages

  VectorXd floors() const {
    return floor_of_correlation ? VectorXd(floor * d) : VectorXd::Constant(d.size(), floor);
  }
};

// The eigendecomposition S = P diag(lambda) P^T of the input's symmetric part, when computed.
struct Spectrum {
  VectorXd lambda;
  MatrixXd P;
};

// The Newton method's answer to a FixedDiagonalProblem.
struct Solution {
  MatrixXd X;
  int iterations = 0;
  double gradient_norm = 0.0;  // ||diag(X~) - b||_2 in the weighted problem, the input's units
  bool converged = false;
  Index clipped = 0;
};

// Qi & Sun's Newton method on the dual (correlation_newton.hpp), in X~ = W^1/2 (X - F) W^1/2:
// min ||X~ - G||_F over X~ >= 0 with diag(X~) = b, G = W^1/2 (S - F) W^1/2, b = w o (d - diag(F)),
// F = p.floors(). The floor is thus an exact constraint (X >= F), not a clip afterwards. Computed
// in units where max(b) is in [0.5, 1) (an exact power-of-two scaling), so that repairing s C
// gives s X. With unit weights, diag(S) = d and F = floor I, the first dual matrix G + diag(y0)
// is (S - floor I) scaled: `spectrum`, S's eigendecomposition when given, then serves for it (and
// is consumed). p.S is consumed too (it becomes G in place): memory for large n.
Solution solve(FixedDiagonalProblem& p, const NearestCorrelationOptions& options, Spectrum* spectrum = nullptr) {
  const Index n = p.S.rows();
  const VectorXd root = p.w.cwiseSqrt();
  const VectorXd f = p.floors();
  const VectorXd target = p.d - f;
  const int e = detail::scale_exponent(p.w.cwiseProduct(target).maxCoeff()).value_or(0);
  MatrixXd G = std::move(p.S);
  G.diagonal() -= f;
  for (Index j = 0; j < n; ++j) G.col(j).array() *= root.array() * root(j);
  detail::multiply_by_power_of_two(G, -e);
  const VectorXd b = detail::times_power_of_two(p.w.cwiseProduct(target), -e);
  const bool reuse = spectrum && spectrum->P.rows() == n && !p.floor_of_correlation && (b - G.diagonal()).isZero(0.0);
  VectorXd lambda;
  if (reuse) lambda = detail::times_power_of_two((spectrum->lambda.array() - p.floor).matrix(), -e);
  const double tolerance = options.tolerance * std::sqrt(static_cast<double>(n)) * b.maxCoeff();
  detail::CorrelationNewtonResult newton = detail::correlation_newton(
      std::move(G), b, options.max_iterations, tolerance, reuse ? &spectrum->P : nullptr, reuse ? &lambda : nullptr);

  Solution out;
  out.iterations = newton.iterations;
  out.converged = newton.converged;
  out.gradient_norm = std::ldexp(newton.gradient_norm, e);
  out.clipped = newton.clipped;
  // Back to X: the scaling undone, the weights removed, the diagonal scaled to d - floor exactly
  // (a congruence: X stays semidefinite), then the floor; in place.
  MatrixXd X = std::move(newton.X);
  detail::multiply_by_power_of_two(X, e);
  const VectorXd diagonal = X.diagonal().cwiseQuotient(p.w).cwiseMax(std::numeric_limits<double>::min());
  const VectorXd scale = target.cwiseQuotient(diagonal).cwiseSqrt().cwiseQuotient(root);
  for (Index j = 0; j < n; ++j) X.col(j).array() *= scale.array() * scale(j);
  X.diagonal() = p.d;  // X's diagonal plus the floor's, exactly
  detail::make_symmetric_from_lower(X);
  out.X = std::move(X);
  return out;
}

// ||W^1/2 (X - C) W^1/2||_F at any scale (Eigen's stableNorm), a column at a time: no n x n
// temporary.
double weighted_distance(const Eigen::Ref<const MatrixXd>& X, const Eigen::Ref<const MatrixXd>& C, const VectorXd& w) {
  const VectorXd root = w.cwiseSqrt();
  VectorXd columns(X.cols());
  for (Index j = 0; j < X.cols(); ++j) columns(j) = ((X.col(j) - C.col(j)).cwiseProduct(root) * root(j)).stableNorm();
  return columns.stableNorm();
}

// Throws std::invalid_argument when a variance (diagonal entry) is negative, or zero where
// `zero_allowed` is false (`why` then says what needs it positive).
void check_variances(const VectorXd& d, bool zero_allowed, const char* why = "") {
  for (Index i = 0; i < d.size(); ++i) {
    if (d(i) < 0.0) {
      throw std::invalid_argument("diagonal entry " + std::to_string(i + 1) + " is " + detail::format_number(d(i)) +
                                  ": a covariance's variances must be >= 0");
    }
    if (!zero_allowed && d(i) == 0.0) {
      throw std::invalid_argument("diagonal entry " + std::to_string(i + 1) + " is 0, and " + why +
                                  ": drop that variable, or give it a variance");
    }
  }
}

// The weights of the options, or all ones.
VectorXd weights_or_ones(const NearestCorrelationOptions& options, Index n) {
  return options.weights.size() ? options.weights : VectorXd::Ones(n);
}

// The input's symmetric part, its extreme eigenvalues and the warnings about it, shared by the
// repairs.
struct Prepared {
  MatrixXd S;
  VectorXd w;
  double lambda_min = 0.0, lambda_max = 0.0;
  // With a floor of the correlation matrix: the extreme eigenvalues of D^-1/2 S D^-1/2.
  double correlation_min = 0.0, correlation_max = 0.0;
  Spectrum spectrum;  // with eigenvectors when the Newton method's first step can use them
  std::vector<Warning> warnings;
};

// `d` the diagonal the repair keeps (empty: C's own); `of_correlation`: the floor applies to the
// correlation matrix D^-1/2 X D^-1/2 (C's variances all > 0).
Prepared prepare(const Eigen::Ref<const MatrixXd>& C, const NearestCorrelationOptions& options, const VectorXd& d,
                 bool of_correlation = false) {
  detail::check_repair_input(C, options.floor);
  std::string error;
  if (!options.is_valid(C.rows(), &error)) throw std::invalid_argument(error);
  Prepared out;
  out.S = detail::symmetric_part(C);
  out.w = weights_or_ones(options, C.rows());
  const bool vectors =
      !of_correlation && options.weights.size() == 0 && (d.size() == 0 || out.S.diagonal() == d);
  if (!detail::symmetric_eigen(out.S, out.spectrum.lambda, vectors ? &out.spectrum.P : nullptr)) {
    throw std::runtime_error("repairing the matrix: the eigensolver did not converge");
  }
  if (of_correlation) {
    const VectorXd inverse = out.S.diagonal().cwiseSqrt().cwiseInverse();
    MatrixXd R = inverse.asDiagonal() * out.S * inverse.asDiagonal();
    R.diagonal().setOnes();
    VectorXd lambda;
    if (!detail::symmetric_eigen(R, lambda)) {
      throw std::runtime_error("repairing the matrix: the eigensolver did not converge");
    }
    out.correlation_min = lambda(0);
    out.correlation_max = lambda(lambda.size() - 1);
  }
  out.lambda_min = out.spectrum.lambda(0);
  out.lambda_max = out.spectrum.lambda(out.spectrum.lambda.size() - 1);
  if (auto w = detail::asymmetry_warning(C)) out.warnings.push_back(*w);
  return out;
}

// Whether the floor's own change ||X - X0|| (X0 the answer without it, all in the W-norm) can
// exceed the repair r = ||X0 - C||, judged without X0. X and X0 are projections of C onto nested
// convex sets, so ||X - X0||^2 <= D^2 - r^2 (D = ||X - C||), and the floor dominates only if
// r < D / sqrt 2. Z = (1 - a) X0 + a diag(d), a = max_i F_ii / d_i, is admissible, so D <= r + delta
// with delta = a (sum w_i d_i + ||w o d||) >= a ||X0 - diag(d)||_W, and the floor dominates only if
// r < delta / (sqrt 2 - 1). r is at least C's distance to the semidefinite matrices and to those
// with diagonal d: when that bound passes either test the floor cannot dominate.
// `S_diagonal` is the diagonal of C's symmetric part (p.S is consumed by the solve).
bool floor_may_dominate(const Eigen::Ref<const MatrixXd>& C, const FixedDiagonalProblem& p,
                        const VectorXd& S_diagonal, const Prepared& prepared, double distance) {
  VectorXd lambda = prepared.spectrum.lambda;
  if (p.w != VectorXd::Ones(p.w.size())) {
    const VectorXd root = p.w.cwiseSqrt();
    MatrixXd weighted = detail::symmetric_part(C);
    for (Index j = 0; j < weighted.cols(); ++j) weighted.col(j).array() *= root.array() * root(j);
    if (!detail::symmetric_eigen_in_place(weighted, lambda, false)) return true;
  }
  const double to_cone = lambda.cwiseMin(0.0).norm();
  const double to_diagonal = p.w.cwiseProduct(S_diagonal - p.d).norm();
  const double repair_bound = std::max(to_cone, to_diagonal);
  const double a = p.floors().cwiseQuotient(p.d).maxCoeff();
  const double delta = a * (p.w.dot(p.d) + p.w.cwiseProduct(p.d).norm());
  return repair_bound < distance / std::sqrt(2.0) && repair_bound < delta / (std::sqrt(2.0) - 1.0);
}

// Solves the problem (C's symmetric part S already in it) and reports as NearestResult does:
// the shortcut when S is already admissible, the warnings (not converged; a floor that moved X
// more than the repair itself, measured by solving once more without it when floor_may_dominate
// cannot rule it out).
// p.S and prepared.spectrum's eigenvectors are consumed (memory for large n).
NearestResult repair(const Eigen::Ref<const MatrixXd>& C, FixedDiagonalProblem& p, Prepared& prepared,
                     const NearestCorrelationOptions& options) {
  NearestResult out;
  out.min_eigenvalue_before = prepared.lambda_min;
  out.min_eig = p.floor;
  out.warnings = prepared.warnings;
  if (p.floor_of_correlation && !(p.floor < 1.0)) {
    throw std::invalid_argument("the eigenvalue floor of the correlation matrix D^-1/2 X D^-1/2, " +
                                std::string(p.option) + " times its largest eigenvalue " +
                                detail::format_number(prepared.correlation_max) + ", is " +
                                detail::format_number(p.floor) + ", not below its unit diagonal: lower " + p.option);
  }
  const VectorXd f = p.floors();
  for (Index i = 0; i < p.d.size(); ++i) {
    if (!(p.d(i) > f(i))) {
      throw std::invalid_argument("the eigenvalue floor " + detail::format_number(f(i)) + " (" + p.option +
                                  ") is not below diagonal entry " + std::to_string(i + 1) + ", which is " +
                                  detail::format_number(p.d(i)) +
                                  (p.d(i) == 0.0 ? " (a zero variance: drop that variable, or give it a variance)"
                                                 : std::string(": lower ") + p.option +
                                                       ", or the diagonal cannot be kept"));
    }
  }
  const bool admissible = p.floor_of_correlation ? prepared.correlation_min >= p.floor : prepared.lambda_min >= p.floor;
  const VectorXd S_diagonal = p.S.diagonal();
  if (admissible && S_diagonal == p.d) {
    out.X = std::move(p.S);  // already admissible
  } else {
    Solution s;
    try {
      s = solve(p, options, &prepared.spectrum);
    } catch (const std::runtime_error& e) {
      throw std::runtime_error(std::string("repairing the matrix: ") + e.what());
    }
    out.X = std::move(s.X);
    out.iterations = s.iterations;
    out.gradient_norm = s.gradient_norm;
    out.converged = s.converged;
    out.clipped = s.clipped;
    if (!out.converged) {
      out.warnings.push_back(Warning(Code::NotConverged, "not converged within " + std::to_string(options.max_iterations) +
                             " iterations (||diag(X) - d|| = " + detail::format_number(out.gradient_norm) +
                             "): the best iterate, rescaled to the diagonal"));
    }
  }
  out.distance = weighted_distance(out.X, C, p.w);
  out.cholesky_ok = detail::has_cholesky(out.X);
  if (p.floor > 0.0 && out.clipped > 0 && floor_may_dominate(C, p, S_diagonal, prepared, out.distance)) {
    // What the floor alone moved, measured: the problem solved once more without it.
    FixedDiagonalProblem plain{detail::symmetric_part(C), p.d, p.w, 0.0, false, p.option};
    const MatrixXd X0 = solve(plain, options).X;
    if (auto w = detail::floor_warning(p.floor, weighted_distance(out.X, X0, p.w), weighted_distance(X0, C, p.w),
                                       weighted_distance(MatrixXd::Zero(C.rows(), C.cols()), C, p.w),
                                       p.floor_of_correlation ? prepared.correlation_max : prepared.lambda_max,
                                       p.floor_of_correlation)) {
      out.warnings.push_back(*w);
    }
  }
  return out;
}

// The absolute floor of the options: alpha, or the floor resolved against lambda_max.
double floor_of(const NearestCorrelationOptions& options, double lambda_max) {
  return options.alpha > 0.0 ? options.alpha : detail::resolve_floor(options.floor, lambda_max);
}

// The option the floor of `options` came from, for messages.
const char* option_of(const NearestCorrelationOptions& options) {
  return options.alpha > 0.0 ? "`alpha`" : detail::floor_option(options.floor);
}

}  // namespace

bool NearestCorrelationOptions::is_valid(Index n, std::string* error) const {
  auto fail = [error](std::string why) {
    if (error) *error = std::move(why);
    return false;
  };
  if (weights.size() != 0) {
    if (weights.size() != n) {
      return fail(std::to_string(weights.size()) + " weights for a " + std::to_string(n) + "x" + std::to_string(n) +
                  " matrix: give one per row");
    }
    for (Index i = 0; i < n; ++i) {
      if (!(weights(i) > 0.0) || !std::isfinite(weights(i))) {
        return fail("weight " + std::to_string(i + 1) + " is " + detail::format_number(weights(i)) +
                    ": weights must be finite and > 0");
      }
    }
  }
  if (!floor.is_valid(error)) return false;
  if (!(alpha >= 0.0 && alpha < 1.0)) return fail("alpha must be in [0, 1)");
  if (alpha > 0.0 && floor.value > 0.0) return fail("alpha is the unit diagonal's eigenvalue floor: give it or a floor, not both");
  if (max_iterations < 1) return fail("max_iterations must be >= 1");
  if (!(tolerance > 0.0) || !std::isfinite(tolerance)) return fail("tolerance must be a finite number > 0");
  return true;
}

NearestResult nearest_correlation(const Eigen::Ref<const MatrixXd>& C, const NearestCorrelationOptions& options) {
  const Index n = C.rows();
  Prepared prepared = prepare(C, options, VectorXd::Ones(n));
  const double floor = floor_of(options, prepared.lambda_max);
  // A covariance given for a correlation: its variances would be thrown away (and a small-scale
  // one becomes about I), more often a wrong option than intended.
  const double off = (prepared.S.diagonal().array() - 1.0).abs().maxCoeff();
  if (off > 1e-6) {
    prepared.warnings.push_back(Warning(Code::Warning, "the diagonal is not 1 (it ranges from " +
                                detail::format_number(prepared.S.diagonal().minCoeff()) + " to " +
                                detail::format_number(prepared.S.diagonal().maxCoeff()) +
                                "): it was repaired to a correlation matrix (unit diagonal); to keep a covariance's variances "
                                "instead, repair it with its diagonal kept (`keep_diag` or `via_corr`)"));
  }
  FixedDiagonalProblem p{std::move(prepared.S), VectorXd::Ones(n), prepared.w, floor, false, option_of(options)};
  return repair(C, p, prepared, options);
}

NearestResult nearest_keep_diagonal(const Eigen::Ref<const MatrixXd>& C, const NearestCorrelationOptions& options) {
  if (options.alpha > 0.0) {
    throw std::invalid_argument("`alpha` is the floor of a unit diagonal, not for `keep_diag`: give `min_eig` or `min_eig_rel`");
  }
  // A relative floor applies to the correlation matrix D^-1/2 X D^-1/2 (X >= floor D): below every
  // variance whatever their scales, where one relative to C's largest eigenvalue can exceed the
  // smallest variance of a covariance whose variables have different units.
  const bool of_correlation = options.floor.relative && options.floor.value > 0.0;
  check_variances(C.diagonal(), !of_correlation, "a relative floor (`min_eig_rel`) applies to the correlation matrix");
  Prepared prepared = prepare(C, options, VectorXd(), of_correlation);
  const double floor = floor_of(options, of_correlation ? prepared.correlation_max : prepared.lambda_max);
  VectorXd d = C.diagonal();  // the variances exactly as given (S's diagonal can differ for subnormals)
  FixedDiagonalProblem p{std::move(prepared.S), std::move(d), prepared.w, floor, of_correlation, option_of(options)};
  return repair(C, p, prepared, options);
}

NearestResult nearest_via_correlation(const Eigen::Ref<const MatrixXd>& C, const NearestCorrelationOptions& options) {
  detail::check_repair_input(C, options.floor);
  const VectorXd variances = C.diagonal();  // those of C's symmetric part
  check_variances(variances, false, "`via_corr` divides by the standard deviations");
  double min_before = 0.0;
  {
    MatrixXd S = detail::symmetric_part(C);
    VectorXd lambda;
    if (!detail::symmetric_eigen_in_place(S, lambda, false)) {
      throw std::runtime_error("repairing the matrix: the eigensolver did not converge");
    }
    min_before = lambda(0);
  }
  const VectorXd D = variances.cwiseSqrt();
  const VectorXd inverse = D.cwiseInverse();
  MatrixXd R = detail::symmetric_part(C);
  for (Index j = 0; j < R.cols(); ++j) R.col(j).array() *= inverse.array() * inverse(j);
  detail::make_symmetric_from_lower(R);
  R.diagonal().setOnes();
  NearestResult out = nearest_correlation(R, options);
  R = MatrixXd();
  for (Index j = 0; j < out.X.cols(); ++j) out.X.col(j).array() *= D.array() * D(j);
  out.X.diagonal() = variances;
  detail::make_symmetric_from_lower(out.X);
  out.min_eigenvalue_before = min_before;
  out.distance = weighted_distance(out.X, C, weights_or_ones(options, C.rows()));
  out.cholesky_ok = detail::has_cholesky(out.X);
  if (auto w = detail::asymmetry_warning(C)) out.warnings.insert(out.warnings.begin(), *w);
  return out;
}

}  // namespace spdfit
