#include "numerics/least_squares.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace spdfit::detail {

using Eigen::Index;
using Eigen::VectorXi;

namespace {

constexpr double kEps = std::numeric_limits<double>::epsilon();

// Refinement steps at most: each gains about -log10(cond(A D) eps) digits, so two reach full
// accuracy up to cond(A D) ~ 1e8 and four up to ~1e12; beyond that the steps stop contracting
// and the loop ends on its own.
constexpr int kMaxRefinementSteps = 4;

// A step that shrinks the correction by less than this has stopped converging (rounding in the
// solves of the correction equations now dominates): take no more steps.
constexpr double kContraction = 0.5;

// Error-free transformations (Ogita, Rump & Oishi 2005): a + b = s + e and a * b = p + e exactly.
inline void two_sum(double a, double b, double& s, double& e) {
  s = a + b;
  const double z = s - a;
  e = (a - (s - z)) + (b - z);
}
inline void two_product(double a, double b, double& p, double& e) {
  p = a * b;
  e = std::fma(a, b, -p);
}

// One step of Dot2: the running sum s with its compensation t becomes s - a x, exactly carried.
inline void subtract_product(double a, double x, double& s, double& t) {
  double p, ep, q, eq;
  two_product(a, x, p, ep);
  two_sum(s, -p, q, eq);
  s = q;
  t += eq - ep;
}

// b - c - A x for one column, as if in twice the working precision (Dot2): the running sums s
// and their compensations t are kept per row, so that A is read column by column.
void residual_column(const Eigen::Ref<const MatrixXd>& A, const double* x, const double* b, const double* c,
                     double* out) {
  const Index m = A.rows(), n = A.cols();
  VectorXd s(m), t(m);
  for (Index i = 0; i < m; ++i) {
    if (c) {
      two_sum(b[i], -c[i], s(i), t(i));
    } else {
      s(i) = b[i];
      t(i) = 0.0;
    }
  }
  for (Index k = 0; k < n; ++k) {
    const double xk = x[k];
    if (xk == 0.0) continue;
    const double* a = A.col(k).data();
    for (Index i = 0; i < m; ++i) subtract_product(a[i], xk, s(i), t(i));
  }
  for (Index i = 0; i < m; ++i) out[i] = s(i) + t(i);
}

// -A^T r, each entry a compensated dot product.
VectorXd minus_transpose_times(const Eigen::Ref<const MatrixXd>& A, const VectorXd& r) {
  VectorXd g(A.cols());
  for (Index j = 0; j < A.cols(); ++j) {
    const double* a = A.col(j).data();
    double s = 0.0, t = 0.0;
    for (Index i = 0; i < A.rows(); ++i) subtract_product(a[i], r(i), s, t);
    g(j) = s + t;
  }
  return g;
}

// Bjorck's refinement of y and r = b - A y for one right-hand side, with A = U diag(s) V^T of
// full column rank (the thin U). The correction equations [I, A; A^T, 0] [dr; dy] = [f; g] with
// f = b - r - A y and g = -A^T r solve as h = S^-1 V^T g, d = U^T f, dy = V S^-1 (d - h),
// dr = U h + (f - U d). Returns the steps taken.
int refine_column(const Eigen::Ref<const MatrixXd>& A, const FullSvd& dec, const double* b, double* y_out) {
  const Index m = A.rows(), n = A.cols();
  Eigen::Map<VectorXd> y(y_out, n);
  VectorXd r(m), f(m);
  residual_column(A, y.data(), b, nullptr, r.data());
  double previous = std::numeric_limits<double>::infinity();
  int steps = 0;
  for (; steps < kMaxRefinementSteps; ++steps) {
    residual_column(A, y.data(), b, r.data(), f.data());
    const VectorXd g = minus_transpose_times(A, r);
    const VectorXd h = (dec.V.transpose() * g).cwiseQuotient(dec.s);
    const VectorXd d = dec.U.transpose() * f;
    const VectorXd dy = dec.V * (d - h).cwiseQuotient(dec.s);
    const double size = dy.norm();
    // No longer converging (the first step only needs to be finite: previous is +inf).
    if (!(size < kContraction * previous)) break;
    y += dy;
    r += dec.U * h + (f - dec.U * d);
    previous = size;
    if (size <= kEps * y.norm()) {
      ++steps;
      break;
    }
  }
  return steps;
}

}  // namespace

VectorXi column_exponents(const Eigen::Ref<const MatrixXd>& A) {
  VectorXi e(A.cols());
  for (Index j = 0; j < A.cols(); ++j) e(j) = column_exponent(A.col(j));
  return e;
}

void scale_rows(MatrixXd& M, const VectorXi& e, int sign) {
  for (Index i = 0; i < M.rows(); ++i) {
    auto row = M.row(i);
    multiply_by_power_of_two(row, sign * e(i));
  }
}

MatrixXd accurate_residual(const Eigen::Ref<const MatrixXd>& A, const Eigen::Ref<const MatrixXd>& X,
                           const Eigen::Ref<const MatrixXd>& B) {
  // The columns of a Ref are contiguous (inner stride 1).
  MatrixXd R(B.rows(), B.cols());
  for (Index j = 0; j < B.cols(); ++j) residual_column(A, X.col(j).data(), B.col(j).data(), nullptr, R.col(j).data());
  return R;
}

LeastSquaresSolution equilibrated_least_squares(const Eigen::Ref<const MatrixXd>& A,
                                                const Eigen::Ref<const MatrixXd>& B, double cutoff) {
  LeastSquaresSolution out;
  const Index n = A.cols();
  out.exponents = column_exponents(A);
  out.scaled_A = A;
  scale_columns(out.scaled_A, out.exponents, -1);
  out.scaled = svd_full_v(out.scaled_A);
  out.rank = numerical_rank(out.scaled.s, cutoff);
  if (out.rank == n) {
    // Full column rank (so m >= n): the unique solution, in the scaled unknowns y = D^-1 x.
    out.unscaled.s = singular_values(A);
    out.X = out.scaled.V * (out.scaled.s.cwiseInverse().asDiagonal() * (out.scaled.U.transpose() * B));
    for (Index j = 0; j < B.cols(); ++j) {
      out.refinement_steps =
          std::max(out.refinement_steps, refine_column(out.scaled_A, out.scaled, B.col(j).data(), out.X.col(j).data()));
    }
    scale_rows(out.X, out.exponents, -1);
    return out;
  }
  // Rank-deficient: the minimum-norm solution in the data's units (eq. 3.21).
  out.unscaled = svd_full_v(A);
  // The ranks of A and A D agree; only a singular value of A rounded to exactly zero could
  // disagree, and 1 / 0 must not enter the solution.
  const Index r = std::min(out.rank, numerical_rank(out.unscaled.s, 0.0));
  out.X = out.unscaled.V.leftCols(r) *
          (out.unscaled.s.head(r).cwiseInverse().asDiagonal() * (out.unscaled.U.leftCols(r).transpose() * B));
  return out;
}

}  // namespace spdfit::detail
