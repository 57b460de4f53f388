// The structured repairs (nearest_structured.hpp): the problem in the units where it is solved,
// the choice of engine (the dual Newton method with a fixed set, the augmented Lagrangian with
// elementwise weights), and the result in the input's units with the kept entries exact.
#include "spdfit/nearest_structured.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <vector>

#include "numerics/linalg.hpp"
#include "repair/fixed_entries.hpp"
#include "repair/h_weighted.hpp"
#include "repair/pattern_newton.hpp"
#include "repair/repair.hpp"
#include "spdfit/format.hpp"

namespace spdfit {

using Eigen::Index;
using Eigen::MatrixXd;
using Eigen::VectorXd;

namespace {

// H = h h^T to this relative precision is the diagonal weights' problem (w = h o h), solved by
// the faster Newton method on the dual.
constexpr double kRankOneTolerance = 1e-12;

// h with H = h h^T (h_i = sqrt(H_ii) > 0), or nothing.
std::optional<VectorXd> rank_one_root(const MatrixXd& H) {
  const Index n = H.rows();
  if (!(H.diagonal().array() > 0.0).all()) return std::nullopt;
  const VectorXd h = H.diagonal().cwiseSqrt();
  for (Index j = 0; j < n; ++j) {
    for (Index i = 0; i < n; ++i) {
      if (std::abs(H(i, j) - h(i) * h(j)) > kRankOneTolerance * h(i) * h(j)) return std::nullopt;
    }
  }
  return h;
}

// The largest eigenvalue and the smallest of a symmetric matrix (values only).
std::pair<double, double> extreme_eigenvalues(MatrixXd M) {
  VectorXd lambda;
  if (!detail::symmetric_eigen_in_place(M, lambda, false)) {
    throw std::runtime_error("repairing the matrix: the eigensolver did not converge");
  }
  return {lambda(0), lambda(lambda.size() - 1)};
}

// h > 0 with h h^T close to H (>= 0, symmetric): the Perron vector v and eigenvalue l of H by power
// iteration, h = sqrt(l) v, floored at 1e-3 of its largest entry so that every weight is positive.
VectorXd rank_one_fit(const MatrixXd& H) {
  const Index n = H.rows();
  VectorXd v = VectorXd::Ones(n) / std::sqrt(static_cast<double>(n));
  double l = 0.0;
  for (int k = 0; k < 100; ++k) {
    VectorXd next = H * v;
    const double norm = next.norm();
    if (!(norm > 0.0)) break;
    next /= norm;
    const bool done = (next - v).norm() < 1e-10;
    v = std::move(next);
    l = norm;
    if (done) break;
  }
  VectorXd h = v.cwiseAbs() * std::sqrt(std::max(l, 0.0));
  const double top = h.maxCoeff();
  return h.cwiseMax(top > 0.0 ? 1e-3 * top : 1.0);
}

const char* method_name(bool alm) {
  return alm ? "augmented Lagrangian (H weights)" : "Qi-Sun Newton with fixed entries";
}

}  // namespace

bool NearestStructure::is_valid(Index n, DiagonalRule rule, std::string* error) const {
  try {
    const detail::FixedPattern pattern = detail::fixed_pattern(fixed, index_base, n, rule);
    if (h_weights.size() > 0) detail::check_h_weights(h_weights, pattern);
  } catch (const std::invalid_argument& e) {
    if (error) *error = e.what();
    return false;
  }
  return true;
}

Eigen::MatrixXd raise_variances(const Eigen::Ref<const MatrixXd>& C, double min_diag,
                                std::vector<Warning>& warnings) {
  if (!(min_diag >= 0.0) || !std::isfinite(min_diag)) {
    throw std::invalid_argument("`min_diag` must be a finite number >= 0");
  }
  MatrixXd out = C;
  std::string listed;
  int count = 0;
  for (Index i = 0; i < C.rows() && i < C.cols(); ++i) {
    if (C(i, i) < min_diag) {
      if (count < 10) listed += (count == 0 ? "" : ", ") + std::to_string(i + 1) + " (" + format_number(C(i, i)) + ")";
      ++count;
      out(i, i) = min_diag;
    }
  }
  if (count > 10) listed += ", ... (" + std::to_string(count) + " in all)";
  if (count > 0) {
    warnings.push_back(Warning(Code::DiagonalChanged,
                               std::string(count == 1 ? "diagonal entry " : "diagonal entries ") + listed + " " +
                                   (count == 1 ? "was" : "were") + " below `min_diag` and raised to " +
                                   format_number(min_diag) + " before the repair",
                               "min_diag"));
  }
  return out;
}

NearestResult nearest_structured(const Eigen::Ref<const MatrixXd>& C, DiagonalRule rule,
                                 const NearestStructure& structure, const NearestCorrelationOptions& options) {
  detail::check_repair_input(C, options.floor);
  const Index n = C.rows();
  std::string error;
  if (!options.is_valid(n, &error)) throw std::invalid_argument(error);
  const bool weighted = structure.h_weights.size() > 0;
  if (weighted && options.weights.size() > 0) {
    throw std::invalid_argument("give `h_weights` or `weights`, not both (diagonal weights w are H = sqrt(w w^T))");
  }
  if (options.alpha > 0.0 && rule != DiagonalRule::Unit) {
    throw std::invalid_argument("`alpha` is the floor of a unit diagonal: it needs `corr` (otherwise give `min_eig`)");
  }
  const detail::FixedPattern pattern = detail::fixed_pattern(structure.fixed, structure.index_base, n, rule);
  if (weighted) detail::check_h_weights(structure.h_weights, pattern);
  // Accepted when symmetric to rounding; the solvers take it exactly symmetric.
  const MatrixXd h_weights = weighted ? detail::symmetric_part(structure.h_weights) : MatrixXd();

  NearestResult out;
  MatrixXd S = detail::symmetric_part(C);
  if (auto w = detail::asymmetry_warning(C)) out.warnings.push_back(*w);
  if (rule == DiagonalRule::Unit) {
    if (auto w = detail::unit_diagonal_warning(S)) out.warnings.push_back(*w);
  }
  const auto [lambda_min, lambda_max] = extreme_eigenvalues(S);
  out.min_eigenvalue_before = lambda_min;

  // The diagonal targets and the floor's diagonal F (X >= F): as nearest_correlation,
  // nearest_keep_diagonal (a relative floor of the correlation matrix) and nearest_spd.
  VectorXd d = rule == DiagonalRule::Unit ? VectorXd::Ones(n) : VectorXd(C.diagonal());
  const bool of_correlation = rule == DiagonalRule::Kept && options.floor.relative && options.floor.value > 0.0;
  if (rule == DiagonalRule::Kept) {
    detail::check_variances(d, !of_correlation, "a relative floor (`min_eig_rel`) applies to the correlation matrix");
  }
  double floor = 0.0;
  if (options.alpha > 0.0) {
    floor = options.alpha;
  } else if (of_correlation) {
    const VectorXd inverse = d.cwiseSqrt().cwiseInverse();
    MatrixXd R = inverse.asDiagonal() * S * inverse.asDiagonal();
    R.diagonal().setOnes();
    floor = options.floor.value * extreme_eigenvalues(std::move(R)).second;
  } else {
    floor = detail::resolve_floor(options.floor, lambda_max);
  }
  const char* option = options.alpha > 0.0 ? "`alpha`" : detail::floor_option(options.floor);
  const VectorXd f = of_correlation ? VectorXd(floor * d) : VectorXd::Constant(n, floor);
  out.min_eig = floor;

  // The kept entries' targets: C's (symmetric part's) entries, the diagonal d.
  MatrixXd B = MatrixXd::Zero(n, n);
  for (Index p = 0; p < pattern.size(); ++p) {
    const Index i = pattern.row[p], j = pattern.col[p];
    B(i, j) = B(j, i) = i == j ? d(i) : S(i, j);
  }
  for (Index p = 0; p < pattern.size(); ++p) {
    const Index i = pattern.row[p];
    if (i != pattern.col[p]) continue;
    if (!(d(i) > f(i)) && !(d(i) == 0.0 && f(i) == 0.0 && rule == DiagonalRule::Free)) {
      throw std::invalid_argument("the eigenvalue floor " + format_number(f(i)) + " (" + option +
                                  ") is not below diagonal entry " + std::to_string(i + 1) + ", which is " +
                                  format_number(d(i)) +
                                  (d(i) <= 0.0 ? " (a variance that is not positive: drop that variable, give it a "
                                                 "variance, or raise it with `min_diag`)"
                                               : std::string(": lower ") + option + ", or the diagonal cannot be kept"));
    }
  }
  detail::check_fixed_feasible(B, pattern, f, option);

  // Weights: elementwise H, or diagonal w (H = sqrt(w w^T)); H of rank one is the latter.
  VectorXd w = options.weights.size() ? options.weights : VectorXd::Ones(n);
  bool alm = weighted;
  double h_max = 1.0;
  if (weighted) {
    if (auto h = rank_one_root(h_weights)) {
      w = h->cwiseAbs2();
      alm = false;
    } else {
      h_max = h_weights.maxCoeff();
    }
  }
  // With no entry kept off the diagonal and the diagonal fixed, this is the diagonal repair.
  if (!alm && pattern.off_diagonal == 0 && rule != DiagonalRule::Free) {
    NearestCorrelationOptions diagonal = options;
    diagonal.weights = w;
    NearestResult result =
        rule == DiagonalRule::Unit ? nearest_correlation(C, diagonal) : nearest_keep_diagonal(C, diagonal);
    result.method = "Qi-Sun Newton";
    return result;
  }

  // The problem in the units where it is solved: X~ = W^1/2 (X - F) W^1/2 (unit weights with H),
  // scaled by 2^-e so that its largest target or entry is below 1.
  const VectorXd root = w.cwiseSqrt();
  MatrixXd G = S;
  G.diagonal() -= f;
  MatrixXd Bt = B;
  Bt.diagonal() -= f;
  for (Index j = 0; j < n; ++j) {
    G.col(j).array() *= root.array() * root(j);
    Bt.col(j).array() *= root.array() * root(j);
  }
  double biggest = G.cwiseAbs().maxCoeff();
  for (Index p = 0; p < pattern.size(); ++p) biggest = std::max(biggest, std::abs(Bt(pattern.row[p], pattern.col[p])));
  const int e = detail::scale_exponent(biggest).value_or(0);
  detail::multiply_by_power_of_two(G, -e);
  detail::multiply_by_power_of_two(Bt, -e);
  // Every admissible X~ is semidefinite with its diagonal targets when all of them are kept, so
  // ||X~||_F <= trace and ||X~ - G||^2 / 2 <= (trace + ||G||)^2 / 2: a dual value above that
  // proves that there is no admissible X.
  double bound = std::numeric_limits<double>::infinity();
  if (pattern.diagonal == n) bound = 0.5 * std::pow(Bt.diagonal().sum() + G.norm(), 2);
  const double tolerance = options.tolerance * std::sqrt(static_cast<double>(n)) *
                           std::max(Bt.diagonal().cwiseAbs().maxCoeff(), std::ldexp(biggest, -e));

  MatrixXd X;
  double residual = 0.0, dual_value = std::numeric_limits<double>::quiet_NaN();
  std::vector<Index> singular_rows;
  try {
    if (alm) {
      const MatrixXd H = h_weights / h_max;
      // The start: the problem with H replaced by its rank-one fit h h^T (h_i = sqrt(H_ii) would
      // miss weights whose diagonal does not matter, so the Perron vector), solved by the dual
      // Newton method in X~ = D_h X D_h, and its multiplier, mapped back.
      const VectorXd h = rank_one_fit(H);
      MatrixXd Gh = h.asDiagonal() * G * h.asDiagonal(), Bh = h.asDiagonal() * Bt * h.asDiagonal(), Zh;
      detail::PatternNewtonResult start = detail::pattern_newton(
          std::move(Gh), pattern, Bh, options.max_iterations, options.tolerance * std::sqrt(static_cast<double>(n)),
          std::numeric_limits<double>::infinity(), &Zh);
      const VectorXd inverse = h.cwiseInverse();
      const MatrixXd X0 = inverse.asDiagonal() * start.X * inverse.asDiagonal();
      const MatrixXd Z0 = h.asDiagonal() * Zh * h.asDiagonal();
      detail::HWeightedResult s =
          detail::h_weighted_alm(G, H, pattern, Bt, options.max_iterations, options.tolerance, &X0, &Z0);
      out.iterations = start.iterations;
      X = std::move(s.X);
      out.iterations += s.iterations;
      out.converged = s.converged;
      out.clipped = s.clipped;
      out.optimality_residual = s.kkt_residual;
      residual = s.residual;
      dual_value = s.dual_value;
    } else {
      detail::PatternNewtonResult s =
          detail::pattern_newton(std::move(G), pattern, Bt, options.max_iterations, tolerance, bound);
      if (s.infeasible) {
        throw std::invalid_argument(
            "no positive semidefinite matrix with the kept diagonal" +
            std::string(floor > 0.0 ? " and the eigenvalue floor (" + std::string(option) + ")" : "") +
            " has these kept entries (" + std::to_string(pattern.off_diagonal) +
            " off the diagonal): the dual problem is unbounded. Each kept block is positive semidefinite, but "
            "together they admit no completion; keep fewer entries" +
            (floor > 0.0 ? ", or lower the floor" : ""));
      }
      X = std::move(s.X);
      out.iterations = s.iterations;
      out.converged = s.converged;
      out.clipped = s.clipped;
      residual = s.residual;
      dual_value = s.dual_value;
      singular_rows = std::move(s.singular_rows);
    }
  } catch (const std::runtime_error& failure) {
    throw std::runtime_error(std::string("repairing the matrix: ") + failure.what());
  }
  out.gradient_norm = std::ldexp(residual, e);
  if (!out.converged) {
    std::string why;
    if (!singular_rows.empty()) {
      why = ". The multipliers grow without bound: every positive semidefinite matrix with these kept "
            "entries seems to be singular (a kept block that is itself singular does that; the null "
            "direction is largest in rows " +
            detail::index_list(singular_rows) +
            "), and the dual then has no minimizer, where Newton's method converges slowly. Keep a "
            "positive definite block (repair it first with an eigenvalue floor, e.g. `min_eig` 1e-3), "
            "or keep fewer entries";
    }
    out.warnings.push_back(Warning(Code::NotConverged, "not converged within " + std::to_string(options.max_iterations) +
                           " iterations (" + (alm ? "KKT residual " + format_number(out.optimality_residual)
                                                  : "||A(X) - b|| = " + format_number(out.gradient_norm)) +
                           "): the last iterate, with the kept entries set" + why));
  }

  // Back to the input's units: the scaling undone, the weights removed, the floor added, and the
  // kept entries set to C's exactly.
  detail::multiply_by_power_of_two(X, e);
  const VectorXd inverse_root = root.cwiseInverse();
  for (Index j = 0; j < n; ++j) X.col(j).array() *= inverse_root.array() * inverse_root(j);
  X.diagonal() += f;
  for (Index p = 0; p < pattern.size(); ++p) {
    const Index i = pattern.row[p], j = pattern.col[p];
    X(i, j) = X(j, i) = B(i, j);
  }
  if (rule != DiagonalRule::Free) X.diagonal() = d;
  detail::make_symmetric_from_lower(X);

  // The distance, in the weighted norm, and the dual's lower bound on it (C's antisymmetric part
  // is orthogonal to every symmetric change, so it adds in quadrature).
  const MatrixXd Hfull = alm ? h_weights : MatrixXd(root * root.transpose());
  out.distance = Hfull.cwiseProduct(X - C).norm();
  const double asymmetric = Hfull.cwiseProduct(S - C).norm();
  if (!std::isnan(dual_value)) {
    const double scale = std::ldexp(1.0, e) * h_max;
    const double bound_squared = 2.0 * std::max(dual_value, 0.0) * scale * scale;
    out.lower_bound = std::sqrt(bound_squared + asymmetric * asymmetric);
  }
  out.X = std::move(X);
  out.cholesky_ok = detail::has_cholesky(out.X);
  out.method = method_name(alm);
  out.fixed_entries = pattern.off_diagonal + (rule == DiagonalRule::Free ? pattern.diagonal : 0);
  return out;
}

}  // namespace spdfit
