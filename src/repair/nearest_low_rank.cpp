// The rank and factor repairs (nearest_low_rank.hpp): their starts, the local method run from each,
// and the result with its evidence (every start's distance, the convex lower bound, the
// stationarity residual).
#include "spdfit/nearest_low_rank.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <stdexcept>
#include <string>

#include "numerics/linalg.hpp"
#include "repair/low_rank.hpp"
#include "repair/repair.hpp"
#include "spdfit/format.hpp"

namespace spdfit {

using Eigen::Index;
using Eigen::MatrixXd;
using Eigen::VectorXd;

namespace {

constexpr std::uint64_t kRandomSeed = 20240611;

void check_options(const NearestLowRankOptions& options, Index n, Index k, const char* option) {
  if (k < 1 || k > n) {
    throw InputError("`" + std::string(option) + "` is " + std::to_string(k) + ", but the matrix is " +
                         std::to_string(n) + "x" + std::to_string(n) + ": it must be from 1 to " + std::to_string(n),
                     Code::DataShape, option);
  }
  if (options.weights.size() != 0) {
    if (options.weights.size() != n) {
      throw std::invalid_argument(std::to_string(options.weights.size()) + " weights for a " + std::to_string(n) +
                                  "x" + std::to_string(n) + " matrix: give one per row");
    }
    for (Index i = 0; i < n; ++i) {
      if (!(options.weights(i) > 0.0) || !std::isfinite(options.weights(i))) {
        throw std::invalid_argument("weight " + std::to_string(i + 1) + " is " + format_number(options.weights(i)) +
                                    ": weights must be finite and > 0");
      }
    }
  }
  if (options.max_iterations < 1) throw std::invalid_argument("`max_iterations` must be >= 1");
  if (!(options.tolerance > 0.0) || !std::isfinite(options.tolerance)) {
    throw std::invalid_argument("`tolerance` must be a finite number > 0");
  }
  if (options.random_starts < 0) throw std::invalid_argument("the number of random starts must be >= 0");
}

// Flury's modified principal components: the K leading eigenvectors of the symmetric M scaled by
// the roots of their (non-negative parts of the) eigenvalues, rows then normalized.
MatrixXd modified_pca(MatrixXd M, Index K) {
  const Index n = M.rows();
  VectorXd lambda;
  if (!detail::symmetric_eigen_in_place(M, lambda, true)) {
    throw std::runtime_error("repairing the matrix: the eigensolver did not converge");
  }
  MatrixXd Y(n, K);
  for (Index k = 0; k < K; ++k) Y.col(k) = M.col(n - 1 - k) * std::sqrt(std::max(lambda(n - 1 - k), 0.0));
  return Y;  // normalized by the problem's projection
}

}  // namespace

NearestResult nearest_correlation_rank(const Eigen::Ref<const MatrixXd>& C, Index rank,
                                       const NearestLowRankOptions& options) {
  detail::check_repair_input(C, EigenvalueFloor{});
  const Index n = C.rows();
  check_options(options, n, rank, "rank");
  NearestResult out;
  if (auto w = detail::asymmetry_warning(C)) out.warnings.push_back(*w);
  MatrixXd S = detail::symmetric_part(C);
  {
    MatrixXd copy = S;
    VectorXd lambda;
    if (!detail::symmetric_eigen_in_place(copy, lambda, false)) {
      throw std::runtime_error("repairing the matrix: the eigensolver did not converge");
    }
    out.min_eigenvalue_before = lambda(0);
  }
  // With the diagonal kept, X = D^1/2 R D^1/2: R is the rank-K correlation matrix nearest to
  // D^-1/2 S D^-1/2 in the weights w o d.
  VectorXd w = options.weights.size() ? options.weights : VectorXd::Ones(n);
  VectorXd root_d = VectorXd::Ones(n);
  if (options.keep_diagonal) {
    const VectorXd d = C.diagonal();
    detail::check_variances(d, false, "`keep_diag` with `rank` scales by the standard deviations");
    root_d = d.cwiseSqrt();
    const VectorXd inverse = root_d.cwiseInverse();
    for (Index j = 0; j < n; ++j) S.col(j).array() *= inverse.array() * inverse(j);
    S.diagonal().setOnes();
    w = w.cwiseProduct(d);
  } else if (auto warning = detail::unit_diagonal_warning(S)) {
    out.warnings.push_back(*warning);
  }

  // The convex relaxation: the nearest correlation matrix without the rank (floor 0), whose
  // distance no matrix of rank <= K can beat.
  NearestCorrelationOptions convex;
  convex.weights = w;
  convex.floor = EigenvalueFloor::absolute(0.0);
  const NearestResult relaxed = nearest_correlation(S, convex);

  const detail::LowRankProblem problem(S, w, true);
  std::vector<std::pair<std::string, MatrixXd>> starts;
  starts.emplace_back("modified PCA of C", modified_pca(S, rank));
  starts.emplace_back("modified PCA of the convex solution", modified_pca(relaxed.X, rank));
  std::mt19937_64 generator(kRandomSeed);
  std::normal_distribution<double> normal;
  for (int k = 0; k < options.random_starts; ++k) {
    MatrixXd Y(n, rank);
    for (Index j = 0; j < rank; ++j)
      for (Index i = 0; i < n; ++i) Y(i, j) = normal(generator);
    starts.emplace_back("random " + std::to_string(k + 1), std::move(Y));
  }
  detail::LowRankResult best;
  best.objective = std::numeric_limits<double>::infinity();
  for (auto& [name, Y0] : starts) {
    detail::LowRankResult local =
        detail::spectral_projected_gradient(problem, std::move(Y0), options.max_iterations, options.tolerance);
    NearestStart start;
    start.name = name;
    start.distance = problem.distance(local.Y);
    start.iterations = local.iterations;
    out.starts.push_back(start);
    if (start.distance < best.objective) {
      best = std::move(local);
      best.objective = start.distance;
    }
  }
  // X = D^1/2 Y Y^T D^1/2 = F F^T with F = D^1/2 Y, its diagonal set exactly.
  MatrixXd F = root_d.asDiagonal() * best.Y;
  detail::lower_gram(F, out.X);
  detail::make_symmetric_from_lower(out.X);
  out.X.diagonal() = options.keep_diagonal ? VectorXd(C.diagonal()) : VectorXd::Ones(n);
  out.F = std::move(F);
  const MatrixXd root_w = options.weights.size() ? MatrixXd(options.weights.cwiseSqrt() *
                                                              options.weights.cwiseSqrt().transpose())
                                                 : MatrixXd::Ones(n, n);
  out.distance = root_w.cwiseProduct(out.X - C).norm();
  const double asymmetric = root_w.cwiseProduct(detail::symmetric_part(C) - C).norm();
  out.lower_bound = std::sqrt(relaxed.distance * relaxed.distance + asymmetric * asymmetric);
  out.iterations = best.iterations;
  out.converged = best.converged;
  out.optimality_residual = best.residual;
  out.clipped = n - rank;
  out.cholesky_ok = detail::has_cholesky(out.X);
  out.method = "spectral projected gradient (rank)";
  if (!out.converged) {
    out.warnings.push_back(Warning(Code::NotConverged, "the best start did not converge within " + std::to_string(options.max_iterations) +
                           " iterations (stationarity residual " + format_number(best.residual) +
                           "): the last iterate"));
  }
  return out;
}

NearestResult nearest_correlation_factors(const Eigen::Ref<const MatrixXd>& C, Index factors,
                                          const NearestLowRankOptions& options) {
  detail::check_repair_input(C, EigenvalueFloor{});
  const Index n = C.rows();
  check_options(options, n, factors, "factors");
  if (options.weights.size() != 0) throw std::invalid_argument("`factors` takes no `weights`");
  if (options.keep_diagonal) throw std::invalid_argument("`factors` is a correlation matrix's structure: not with `keep_diag`");
  NearestResult out;
  const detail::LowRankProblem problem(C, VectorXd(), false);
  if (!problem.symmetric()) {
    if (auto w = detail::asymmetry_warning(C)) out.warnings.push_back(*w);
  }
  if (auto w = detail::unit_diagonal_warning(C)) out.warnings.push_back(*w);
  MatrixXd V;
  VectorXd values;
  detail::leading_eigenvectors(C, factors, V, values);
  for (Index k = 0; k < factors; ++k) V.col(k) *= std::sqrt(std::max(values(k), 0.0));
  detail::LowRankResult local =
      detail::spectral_projected_gradient(problem, std::move(V), options.max_iterations, options.tolerance);
  out.distance = problem.distance(local.Y);
  const VectorXd uniqueness = (1.0 - local.Y.rowwise().squaredNorm().array()).matrix();
  if (options.form_x) {
    detail::lower_gram(local.Y, out.X);
    detail::make_symmetric_from_lower(out.X);
    out.X.diagonal().setOnes();
  }
  // X = diag(psi) + F F^T factors when every uniqueness psi_i is clear of rounding.
  out.cholesky_ok = uniqueness.minCoeff() > 4.0 * static_cast<double>(n) * std::numeric_limits<double>::epsilon();
  out.F = std::move(local.Y);
  out.iterations = local.iterations;
  out.converged = local.converged;
  out.optimality_residual = local.residual;
  out.min_eigenvalue_before = std::numeric_limits<double>::quiet_NaN();  // no O(n^3) eigendecomposition here
  out.method = "spectral projected gradient (factors)";
  if (!out.converged) {
    out.warnings.push_back(Warning(Code::NotConverged, "not converged within " + std::to_string(options.max_iterations) +
                           " iterations (stationarity residual " + format_number(local.residual) +
                           "): the last iterate"));
  }
  return out;
}

}  // namespace spdfit
