// Least squares at the accuracy the data allow (internal): the one home of column equilibration,
// the unit-free rank decision and iterative refinement with an accurate residual, behind every
// least-squares path that has its data at hand (solve, the linkage solves) and, for the rank
// decision, the triangular factor's reduction.
#pragma once

#include <Eigen/Core>
#include <cmath>
#include <utility>

#include "numerics/linalg.hpp"

namespace spdfit::detail {

/// Column exponents e_j with 2^-e_j ||a_j||_2 in [0.5, 1) (0 for a zero column): A diag(2^-e)
/// has columns of about unit norm, and the scaling is exact. Scaling a column of A by 2^k shifts
/// its exponent by k and leaves A diag(2^-e) bit for bit the same (bar underflow). Cost O(m n).
Eigen::VectorXi column_exponents(const Eigen::Ref<const MatrixXd>& A);

/// Column j of M times 2^(sign * e_j), exactly (bar overflow and underflow). Any matrix type:
/// bounded sizes stay on the stack.
template <typename Derived, typename Exponents>
void scale_columns(Eigen::MatrixBase<Derived>& M, const Exponents& e, int sign) {
  for (Index j = 0; j < M.cols(); ++j) {
    auto column = M.col(j);
    multiply_by_power_of_two(column, sign * e(j));
  }
}
/// Row i of M times 2^(sign * e_i), exactly (x = D y: rows of a solution).
void scale_rows(MatrixXd& M, const Eigen::VectorXi& e, int sign);

/// The exponent e with 2^-e ||v||_2 in [0.5, 1) (0 for a zero v): column_exponents' rule.
template <typename Derived>
int column_exponent(const Eigen::MatrixBase<Derived>& v) {
  // stableNorm: no overflow or underflow in the sum of squares, and exactly 2^k times the norm
  // of the column scaled by 2^k.
  const double norm = v.stableNorm();
  int e = 0;
  if (norm > 0.0) std::frexp(norm, &e);  // norm = f 2^e, f in [0.5, 1)
  return e;
}

/// The singular values of A D, D = diag(2^-e) (e from column_exponent), descending: one SVD.
template <typename Matrix, typename Exponents>
typename BasicSvd<Matrix>::Vector equilibrated_singular_values(const Matrix& A, const Exponents& e) {
  Matrix As = A;
  scale_columns(As, e, -1);
  BasicSvd<Matrix> dec;
  svd_into(As, dec, false, false);
  return std::move(dec.s);
}

/// The numerical rank of a square or tall A decided on A D, its columns scaled to about unit norm
/// (van der Sluis: this D brings the condition number within a factor sqrt(n) of its minimum over
/// all column scalings), so that a change of units of one unknown does not change the rank. s
/// holds the singular values of A itself (descending). The scaled singular values are computed
/// only when those of A cannot decide: when rank(s) == n and cond(s) * spread < 1 / cutoff, with
/// spread >= cond(D) from the exponents, A D has full rank too (cond(A D) <= cond(A) cond(D)).
/// With scaled_condition given they are computed and cond(A D) is written there, unless the
/// bound cond(s) * spread is at most report_above (a caller that needs cond(A D) only where it may
/// exceed a threshold): then *scaled_condition is left as it was. Matrix is the plain matrix type
/// (bounded sizes keep everything on the stack). Cost O(m n) or one more SVD.
template <typename Matrix, typename Vector>
Eigen::Index equilibrated_rank(const Matrix& A, const Vector& s, double cutoff, double* scaled_condition = nullptr,
                               double report_above = 0.0) {
  const Index n = A.cols();
  Eigen::Matrix<int, Eigen::Dynamic, 1, Eigen::ColMajor, Matrix::MaxColsAtCompileTime, 1> e(n);
  for (Index j = 0; j < n; ++j) e(j) = column_exponent(A.col(j));
  if (n > 0 && numerical_rank(s, cutoff) == n) {
    const double bound = condition_number(s) * std::ldexp(1.0, e.maxCoeff() - e.minCoeff() + 1);
    if (bound * cutoff < 1.0 && (!scaled_condition || bound <= report_above)) return n;
  }
  const auto scaled = equilibrated_singular_values(A, e);
  if (scaled_condition) *scaled_condition = condition_number(scaled);
  return numerical_rank(scaled, cutoff);
}

/// cond(A D) with A's columns scaled to about unit norm: the number equilibrated_rank writes to
/// its scaled_condition, bit for bit. Cost one SVD (values only).
template <typename Matrix>
double equilibrated_condition_number(const Matrix& A) {
  const Index n = A.cols();
  Eigen::Matrix<int, Eigen::Dynamic, 1, Eigen::ColMajor, Matrix::MaxColsAtCompileTime, 1> e(n);
  for (Index j = 0; j < n; ++j) e(j) = column_exponent(A.col(j));
  return condition_number(equilibrated_singular_values(A, e));
}

/// R = B - A X with every entry computed as if in twice double precision and rounded once
/// (compensated dot products, Ogita, Rump & Oishi 2005, "Accurate sum and dot product",
/// Algorithm Dot2): the residual that iterative refinement needs. Cost O(m n p).
MatrixXd accurate_residual(const Eigen::Ref<const MatrixXd>& A, const Eigen::Ref<const MatrixXd>& X,
                           const Eigen::Ref<const MatrixXd>& B);

/// The minimum-norm least-squares solution of A X ~= B with everything a caller reports about it.
///
/// A (m x n, any shape) is scaled to A D with columns of about unit norm (column_exponents), and
/// the rank is decided on the singular values of A D under the relative cut-off (one rule,
/// spdfit/rank.hpp): the decision does not depend on the units of the unknowns.
///  - Full column rank: Y from the SVD of A D, refined by Bjorck's iterative refinement of the
///    augmented system [I, A D; (A D)^T, 0] [r; y] = [b; 0] with its residuals computed by
///    compensated dot products (A. Bjorck, "Iterative refinement of linear least squares
///    solutions I", BIT 7, 1967), and X = D Y. The solution is then as accurate as the data
///    allow (about cond(A D) times the rounding of the data), not cond(A D)^2 eps; scaling a
///    column of A by a power of two scales the solution's entry by exactly the inverse factor.
///  - Rank-deficient: the minimum-norm solution in the data's units, V_r diag(1/sigma_i) U_r^T B
///    from the SVD of A itself (notes 002, eq. 3.21) with the rank decided above.
struct LeastSquaresSolution {
  Eigen::VectorXi exponents;  ///< the column scaling D = diag(2^-exponents)
  MatrixXd scaled_A;          ///< A D, exactly
  FullSvd scaled;             ///< SVD of A D (full V)
  Eigen::Index rank = 0;      ///< decided on scaled.s
  FullSvd unscaled;           ///< SVD of A: full when rank < n, else only its singular values
  MatrixXd X;                 ///< n x p, in the units of A and B
  int refinement_steps = 0;   ///< refinement steps taken (0 when rank < n)
};

/// Solves A X ~= B as described at LeastSquaresSolution. Preconditions (the callers check them):
/// A non-empty, B with A's rows, all finite, entries well inside the double range (the callers
/// scale by powers of two first). Cost O(m n min(m, n)) for two SVDs plus O(m n p) per
/// refinement step (at most kMaxRefinementSteps).
LeastSquaresSolution equilibrated_least_squares(const Eigen::Ref<const MatrixXd>& A,
                                                const Eigen::Ref<const MatrixXd>& B, double cutoff);

}  // namespace spdfit::detail
