#include "numerics/requested_rank_tolerance.hpp"
#include "spdfit/linear_system.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include <Eigen/SVD>

#include "numerics/least_squares.hpp"
#include "numerics/linalg.hpp"
#include "spdfit/format.hpp"
#include "spdfit/outcome.hpp"
#include "spdfit/rank.hpp"
#include "linear_system/linear_system_explanation.hpp"

namespace spdfit {

using Eigen::Index;
using Eigen::MatrixXd;
using Eigen::VectorXd;

namespace {

bool all_finite(const Eigen::Ref<const MatrixXd>& M) { return M.allFinite(); }

// A singular vector is defined up to its sign, which differs between SVD algorithms: make each
// column's entry of largest magnitude positive (the first such entry on a tie), so that the
// range and null-space bases reported do not depend on which SVD ran.
void orient_columns(MatrixXd& M) {
  for (Index j = 0; j < M.cols(); ++j) {
    Index i = 0;
    M.col(j).cwiseAbs().maxCoeff(&i);
    if (M(i, j) < 0.0) M.col(j) = -M.col(j);
  }
}

}  // namespace

const char* to_string(SystemShape shape) {
  switch (shape) {
    case SystemShape::Underdetermined: return "underdetermined";
    case SystemShape::Determined: return "determined";
    case SystemShape::Overdetermined: return "overdetermined";
  }
  return "?";
}

bool LinearSystemOptions::is_valid(std::string* error) const {
  if (!is_valid_rank_tolerance(detail::requested_rank_tolerance(*this), "threshold", error)) return false;
  if (!(rcond_warning >= 0.0) || !(rcond_warning <= 1.0)) {
    if (error) *error = "rcond_warning must lie in [0, 1]";
    return false;
  }
  if (max_unknowns < 1) {
    if (error) *error = "max_unknowns must be at least 1";
    return false;
  }
  return true;
}

double LinearSystemOptions::cutoff(Index m, Index n) const {
  return rank_cutoff(detail::requested_rank_tolerance(*this), m, n);
}

LinearSystemResult solve(const Eigen::Ref<const MatrixXd>& A_in, const Eigen::Ref<const MatrixXd>& B_in,
                         const LinearSystemOptions& options) {
  std::string error;
  if (!options.is_valid(&error)) throw std::invalid_argument("solve: " + error);
  if (A_in.rows() == 0 || A_in.cols() == 0) throw std::invalid_argument("solve: A is empty");
  if (B_in.cols() == 0) throw std::invalid_argument("solve: b has no columns");
  if (B_in.rows() != A_in.rows()) {
    throw InputError("solve: b has " + std::to_string(B_in.rows()) + " rows but A has " +
                         std::to_string(A_in.rows()) + ": one entry of b per equation is needed",
                     Code::DataShape, "b");
  }
  if (A_in.cols() > options.max_unknowns) {
    throw std::invalid_argument("solve: A has " + std::to_string(A_in.cols()) + " columns (unknowns); at most " +
                                std::to_string(options.max_unknowns) +
                                " are supported (LinearSystemOptions::max_unknowns): the SVD's V and the "
                                "null-space basis take n^2 numbers");
  }
  if (!all_finite(A_in)) throw std::invalid_argument("solve: A has a NaN or infinite entry");
  if (!all_finite(B_in)) throw std::invalid_argument("solve: b has a NaN or infinite entry");

  // Work in units where the largest entries of A and B are in [0.5, 1): scaling by powers of two
  // is exact, and the SVD, 1 / sigma_i and the residuals then neither overflow nor lose digits to
  // denormals, whatever the data's units (as the estimators' TriangularFactor does). Everything
  // below is in these units until the end; the classification does not depend on them.
  const int ea = detail::scale_exponent(A_in).value_or(0);
  const int eb = detail::scale_exponent(B_in).value_or(0);
  const MatrixXd A = detail::times_power_of_two(A_in, -ea);
  const MatrixXd B = detail::times_power_of_two(B_in, -eb);

  LinearSystemResult r;
  r.m = A.rows();
  r.n = A.cols();
  r.p = B.cols();
  r.shape = r.m < r.n ? SystemShape::Underdetermined
                      : (r.m == r.n ? SystemShape::Determined : SystemShape::Overdetermined);
  r.rank_tolerance = options.cutoff(r.m, r.n);
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wdeprecated-declarations"
  r.threshold = r.rank_tolerance;  // the deprecated name's copy
#pragma GCC diagnostic pop

  // The solution and the rank decision, made on A with its columns scaled to unit norm so that
  // it does not depend on the units of the unknowns (numerics/least_squares.hpp).
  const detail::LeastSquaresSolution ls = detail::equilibrated_least_squares(A, B, r.rank_tolerance);
  r.rank = ls.rank;
  r.nullity = r.n - r.rank;
  r.refinement_steps = ls.refinement_steps;
  const VectorXd& s = ls.unscaled.s;
  const double smax = s(0);
  const double smin = s(s.size() - 1);
  const double inf = std::numeric_limits<double>::infinity();
  // A wide matrix (m < n) always has a null space: its condition number is that of its
  // min(m, n) singular values, as MATLAB's cond() reports, and the nullity says the rest.
  r.condition_number = smin > 0.0 ? smax / smin : inf;
  r.reciprocal_condition_number = smax > 0.0 ? smin / smax : 0.0;
  r.effective_condition_number = r.rank > 0 && s(r.rank - 1) > 0.0 ? smax / s(r.rank - 1) : inf;
  r.scaled_singular_values = ls.scaled.s;
  r.scaled_condition_number = detail::condition_number(ls.scaled.s);

  const Index k = r.rank;
  if (k == r.n) {
    // Full column rank: the scaled A's left singular vectors span the same range.
    r.range = ls.scaled.U;
    r.null_space.resize(r.n, 0);
  } else {
    r.range = ls.unscaled.U.leftCols(k);
    r.null_space = ls.unscaled.V.rightCols(r.nullity);
  }
  orient_columns(r.range);
  orient_columns(r.null_space);

  const MatrixXd& x = ls.X;
  const MatrixXd residual = detail::accurate_residual(A, x, B);
  r.residual_norm = std::ldexp(residual.stableNorm(), eb);

  // The projective view, one right-hand side at a time: [A | -b_j] [x; w] = 0.
  r.consistent = true;
  for (Index j = 0; j < r.p; ++j) {
    ColumnClassification c;
    const double bnorm = B.col(j).stableNorm();
    MatrixXd M(r.m, r.n + 1);
    M.leftCols(r.n) = ls.scaled_A;  // decided as rank A is, on the unit-norm columns
    // Scaling the homogeneous coordinate w changes nothing in the solution set, and putting
    // b_j on the scale of A keeps the rank decision from depending on the units of b.
    const double scaled_max = ls.scaled.s(0);
    const double scale = bnorm > 0.0 ? (scaled_max > 0.0 ? scaled_max : 1.0) / bnorm : 0.0;
    M.col(r.n) = -scale * B.col(j);
    c.augmented_rank = numerical_rank(detail::singular_values(M), r.rank_tolerance);
    // Appending a column cannot lower the rank; a count below rank A only happens when a
    // singular value sits right at the cut-off, and then the column is consistent.
    c.consistent = c.augmented_rank <= r.rank;
    c.finite_solution_dimension = c.consistent ? r.nullity : -1;
    c.at_infinity_dimension = r.nullity - 1;
    const double residual_norm = residual.col(j).stableNorm();
    c.residual_norm = std::ldexp(residual_norm, eb);
    // A ratio of quantities in b's units: the same in any units.
    const double denominator = smax * x.col(j).stableNorm() + bnorm;
    c.backward_error = denominator > 0.0 ? residual_norm / denominator : 0.0;
    r.consistent = r.consistent && c.consistent;
    r.columns.push_back(c);
  }
  r.finite_solution_dimension = r.consistent ? r.nullity : -1;
  r.at_infinity_dimension = r.nullity - 1;

  // Back to the data's units: A = 2^ea (units), b = 2^eb (units), x = 2^(eb - ea) (units).
  r.singular_values = detail::times_power_of_two(s, ea);
  r.solution = detail::times_power_of_two(x, eb - ea);
  if (!r.solution.allFinite()) {
    r.status = SolveStatus::NumericalFailure;
    r.message = "solve: the solution overflows the range of double precision numbers (b is about 2^" +
                std::to_string(eb) + " and A about 2^" + std::to_string(ea) + ")";
    r.solution.resize(0, 0);
  }

  // Judged with A's columns scaled to unit norm, as the rank is: columns of different sizes
  // (units) are not ill-conditioning, and the scaled condition number is the one that bounds the
  // solution's error.
  const double scaled_rcond = 1.0 / r.scaled_condition_number;
  if (scaled_rcond < options.rcond_warning) {
    r.warnings.push_back(Warning(Code::IllConditioned, "A is ill-conditioned: reciprocal condition number " + format_number(scaled_rcond, Precision::Medium) +
                         " < " + format_number(options.rcond_warning, Precision::Medium) +
                         " with its columns scaled to unit norm (notes 002, section 3.7.2)"));
  }
  r.explanation = detail::explain(r);
  return r;
}

}  // namespace spdfit
