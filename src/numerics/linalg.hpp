// Internal dense linear-algebra helpers: the SVD (the one choice of algorithm by size, used by the
// estimators and the linear-system solver), the QR, and exact power-of-two scaling. The estimators'
// and the linear-system solver's SVDs and QRs go through here, so that a faster backend is swapped
// in at one place; the small fixed-size eigen-decompositions of diagnostics and repair call Eigen
// directly.
//
// The helpers are templates over the Eigen matrix type, so that the same arithmetic runs on
// dynamic matrices (MatrixXd, any size) and on the bounded-size matrices of the small-problem
// path (small_problem.hpp), whose storage is on the stack: no heap allocation per estimate.
#pragma once

#include <Eigen/Core>
#include <Eigen/Eigenvalues>
#include <Eigen/QR>
#include <Eigen/SVD>
#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>

#include "numerics/householder.hpp"
#include "numerics/one_sided_jacobi.hpp"
#include "spdfit/rank.hpp"

namespace spdfit::detail {

using Eigen::Index;
using Eigen::MatrixXd;
using Eigen::VectorXd;

/// A thin SVD A = U diag(s) V^T, s descending, in matrices of type Matrix.
template <typename Matrix>
struct BasicSvd {
  using Vector = Eigen::Matrix<double, Eigen::Dynamic, 1, Eigen::ColMajor, Matrix::MaxColsAtCompileTime, 1>;
  Matrix U, V;
  Vector s;
};
using Svd = BasicSvd<MatrixXd>;

namespace svd_detail {
// Up to this size the one-sided Jacobi SVD (accurate for the small singular values the
// estimators depend on, see one_sided_jacobi.hpp) is used; above it divide and conquer, which
// is much faster for large n.
constexpr Index kJacobiMaxSize = 64;
}  // namespace svd_detail

/// The SVD of a dynamic A (rows >= cols > 64) by divide and conquer: LAPACK's dgesdd when
/// spdfit is built with LAPACK (SPDFIT_LAPACK), else Eigen's BDCSVD.
void svd_large(const Eigen::Ref<const MatrixXd>& A, BasicSvd<MatrixXd>& out, bool compute_u, bool compute_v);

/// The SVD of a square or tall A into `out`: one-sided Jacobi (accurate small singular vectors,
/// see one_sided_jacobi.hpp) up to 64 columns, divide and conquer above (dynamic matrices
/// only). U is left untouched unless compute_u, V unless compute_v.
template <typename Matrix, typename Derived>
void svd_into(const Eigen::MatrixBase<Derived>& A, BasicSvd<Matrix>& out, bool compute_u = true,
              bool compute_v = true) {
  const Index n = A.cols();
  if constexpr (Matrix::MaxColsAtCompileTime == Eigen::Dynamic) {
    if (n > svd_detail::kJacobiMaxSize || A.rows() < n) {
      svd_large(A, out, compute_u, compute_v);
      return;
    }
  }
  Matrix G = A;
  Matrix V;
  one_sided_jacobi(G, compute_v ? &V : static_cast<Matrix*>(nullptr));
  using Vector = typename BasicSvd<Matrix>::Vector;
  const Vector norms = G.colwise().norm().transpose();
  // Sort descending, ties in column order: the order every caller (ranks, TLS's trailing
  // vectors) relies on. Insertion sort: stable, no allocation, and n is at most 64 here.
  Eigen::Matrix<Index, Eigen::Dynamic, 1, Eigen::ColMajor, Matrix::MaxColsAtCompileTime, 1> order(n);
  for (Index k = 0; k < n; ++k) {
    Index i = k;
    for (; i > 0 && norms(order(i - 1)) < norms(k); --i) order(i) = order(i - 1);
    order(i) = k;
  }
  out.s.resize(n);
  if (compute_u) out.U.resize(A.rows(), n);
  if (compute_v) out.V.resize(n, n);
  for (Index k = 0; k < n; ++k) {
    const Index j = order(k);
    out.s(k) = norms(j);
    if (compute_u) {
      // A zero singular value has no defined left vector; zero is what the callers expect.
      if (norms(j) > 0.0)
        out.U.col(k) = G.col(j) / norms(j);
      else
        out.U.col(k).setZero();
    }
    if (compute_v) out.V.col(k) = V.col(j);
  }
}

/// The SVD of a square or tall matrix (see svd_into).
Svd svd(const Eigen::Ref<const MatrixXd>& A, bool compute_u = true, bool compute_v = true);

/// An SVD with the full V: U m x min(m, n), V n x n (its trailing columns span the null space
/// even when m < n), s descending.
struct FullSvd {
  MatrixXd U, V;
  VectorXd s;
};

/// The SVD of any A (m < n too) with the full V, by the same choice as svd_into: for m >= n it is
/// svd_into's (one-sided Jacobi up to 64 columns, divide and conquer above); for m < n, Eigen's
/// two-sided Jacobi SVD up to 64 columns and divide and conquer (BDCSVD) above.
FullSvd svd_full_v(const Eigen::Ref<const MatrixXd>& A);

/// The singular values of any A (descending, min(m, n) of them), by svd_into's choice on A or,
/// when A is wide, on A^T.
VectorXd singular_values(const Eigen::Ref<const MatrixXd>& A);

// The numerical rank is spdfit::numerical_rank (spdfit/rank.hpp), the one rule for every path.

/// sigma_max / sigma_min; +inf when sigma_min == 0 (including the zero matrix).
double condition_number(const Eigen::Ref<const VectorXd>& s);

/// Householder QR in place for bounded-size matrices (at most a few dozen rows and columns),
/// column by column as Eigen's unblocked HouseholderQR (the same reflectors, LAPACK's dgeqr2;
/// householder_step with serial sums), in plain loops over contiguous columns: at these sizes
/// Eigen's general kernels spend most of their time on call overhead. On return the upper
/// triangle of W holds R.
template <typename Work>
void small_householder_qr(Work& W) {
  static_assert(Work::MaxColsAtCompileTime != Eigen::Dynamic && !(Work::Flags & Eigen::RowMajorBit),
                "for bounded-size column-major matrices");
  const Index m = W.rows(), k = W.cols();
  const Index steps = std::min(m, k);
  for (Index j = 0; j < steps; ++j) {
    double* diagonal = W.col(j).data() + j;  // the column below the diagonal, from the diagonal on
    householder_step<1>(diagonal, m, diagonal + 1, m, m - j - 1, k - j);
  }
}

/// The upper triangular factor of a dynamic A (rows >= 1) into R: LAPACK's blocked dgeqrf
/// when spdfit is built with LAPACK and A has at least 128 columns, else spdfit's vectorized
/// block QR (block_qr.hpp) when A has at least as many rows as columns, else Eigen's
/// HouseholderQR.
void triangular_factor_large(const Eigen::Ref<const MatrixXd>& A, MatrixXd& R);

/// The upper triangular factor R (cols x cols, zero-padded when rows < cols) of the
/// Householder QR of A, written into R. Work is the plain matrix type the QR runs in: bounded
/// sizes use small_householder_qr, dynamic ones triangular_factor_large.
template <typename Work, typename Derived, typename Result>
void triangular_factor_into(const Eigen::MatrixBase<Derived>& A, Result& R) {
  const Index cols = A.cols();
  R.setZero(cols, cols);
  if (A.rows() == 0) return;
  if constexpr (Work::MaxColsAtCompileTime == Eigen::Dynamic) {
    triangular_factor_large(A, R);
  } else {
    Work W = A;
    small_householder_qr(W);
    const Index k = std::min(A.rows(), cols);
    R.topRows(k) = W.topRows(k).template triangularView<Eigen::Upper>();
  }
}

/// The upper triangular factor R (cols x cols, zero-padded when rows < cols) of the
/// Householder QR of A.
MatrixXd triangular_factor(const Eigen::Ref<const MatrixXd>& A);

/// The same, computed in A's own storage (A is overwritten): no copy of a tall block.
MatrixXd triangular_factor_in_place(Eigen::Ref<MatrixXd> A);

/// R (square, upper triangular) <- the upper triangular factor of [R; rows], rows overwritten:
/// spdfit's block QR, which needs no stacked copy, below 128 columns; LAPACK's dgeqrf on the
/// stacked matrix from 128 columns on (when built with LAPACK). Cost O(rows cols^2).
void absorb_rows_into_factor(MatrixXd& R, Eigen::Ref<MatrixXd> rows);

/// How many rows absorb_rows_into_factor (or triangular_factor_in_place, first) may be given at a
/// time for the same bits as all the rows at once, when each call gets a multiple of it: the block
/// QR's chunk below 128 columns; every row (the largest Index) from 128 columns on, where dgeqrf
/// runs on the stacked rows.
Index absorb_chunk_rows(Index cols);

/// C = op(A) op(B), op the transpose where asked, by Eigen's own product (any matrix types).
template <typename MatrixA, typename MatrixB, typename MatrixC>
void eigen_product(const MatrixA& A, bool transpose_a, const MatrixB& B, bool transpose_b, MatrixC& C) {
  if (transpose_a && transpose_b) {
    C.noalias() = A.transpose() * B.transpose();
  } else if (transpose_a) {
    C.noalias() = A.transpose() * B;
  } else if (transpose_b) {
    C.noalias() = A * B.transpose();
  } else {
    C.noalias() = A * B;
  }
}

/// C = op(A) op(B), op the transpose where asked: BLAS dgemm (multithreaded) when spdfit is built
/// with LAPACK and the product is large (from 64^3 multiply-adds on), else Eigen. A and B may be
/// column blocks of a matrix (any outer stride).
void multiply(const Eigen::Ref<const MatrixXd>& A, bool transpose_a, const Eigen::Ref<const MatrixXd>& B,
              bool transpose_b, MatrixXd& C);

/// The same in single precision (BLAS sgemm, else Eigen), about twice as fast: for products whose
/// relative accuracy of about 1e-7 suffices, such as an inexact Newton method's conjugate-gradient
/// products (pattern_newton).
void multiply(const Eigen::Ref<const Eigen::MatrixXf>& A, bool transpose_a, const Eigen::Ref<const Eigen::MatrixXf>& B,
              bool transpose_b, Eigen::MatrixXf& C);

/// C = op(A) op(B) for the estimators' kernels, templates over the matrix type: multiply (the
/// BLAS for large products) for dynamic matrices, Eigen's product for the bounded sizes of the
/// small-problem path.
template <typename Matrix>
void product_into(const Matrix& A, bool transpose_a, const Matrix& B, bool transpose_b, Matrix& C) {
  if constexpr (Matrix::MaxColsAtCompileTime == Eigen::Dynamic) {
    multiply(A, transpose_a, B, transpose_b, C);
  } else {
    eigen_product(A, transpose_a, B, transpose_b, C);
  }
}

/// L := U^-1 L for an upper triangular U (its upper triangle is read): BLAS dtrsm when spdfit is
/// built with LAPACK and U has 64 rows or more, else Eigen.
void solve_upper_in_place(const Eigen::Ref<const MatrixXd>& U, MatrixXd& L);

/// L := L U^-1 for an upper triangular U (its upper triangle is read): BLAS dtrsm from the right
/// when spdfit is built with LAPACK and U has 64 rows or more, else Eigen.
void solve_upper_from_right_in_place(const Eigen::Ref<const MatrixXd>& U, MatrixXd& L);

/// The lower triangle of X = L L^T (the upper one is left as it was): BLAS dsyrk when spdfit is
/// built with LAPACK and X has 64 rows or more, else Eigen.
void lower_gram(const Eigen::Ref<const MatrixXd>& L, MatrixXd& X);

/// Whether the symmetric X (its lower triangle) has a Cholesky factorization X = L L^T, i.e. is
/// numerically positive definite: LAPACK's dpotrf from 64 rows on when built with LAPACK, else
/// Eigen's LLT.
bool has_cholesky(const Eigen::Ref<const MatrixXd>& X);

/// The eigendecomposition of a dynamic symmetric M (its lower triangle) by LAPACK's dsyevd
/// (divide and conquer) when spdfit is built with LAPACK, else Eigen's SelfAdjointEigenSolver:
/// w ascending, V's columns the eigenvectors (when V is given). False when it fails.
bool symmetric_eigen_large(const Eigen::Ref<const MatrixXd>& M, VectorXd& w, MatrixXd* V);

/// symmetric_eigen_large in place (Eigen's solver below 64 rows, as symmetric_eigen), for large n
/// where memory counts: M (its lower triangle) is
/// overwritten by the eigenvectors (with `vectors`; without, its contents are lost), w gets the
/// eigenvalues ascending. With LAPACK, dsyevd's workspace (2 n^2 + 6 n + 1 doubles with vectors,
/// 2 n + 1 without) is the only other allocation. False when it fails.
bool symmetric_eigen_in_place(MatrixXd& M, VectorXd& w, bool vectors);

/// The same in single precision (LAPACK's ssyevd, else Eigen's solver below 64 rows), about half
/// dsyevd's time (bench/results/eigh-precision-epyc-2026-12-02.md): exact for a matrix within
/// about 6e-8 ||M||_2 of M, for the steps of an iteration whose accuracy needs no more (the early
/// Newton steps of correlation_newton).
bool symmetric_eigen_in_place(Eigen::MatrixXf& M, Eigen::VectorXf& w, bool vectors);

/// The eigendecomposition M = V diag(w) V^T of a symmetric M, w ascending (V only when given):
/// symmetric_eigen_large from 64 rows on for dynamic matrices, Eigen's SelfAdjointEigenSolver
/// below and for bounded sizes. False when it fails.
template <typename Matrix, typename Vector>
bool symmetric_eigen(const Matrix& M, Vector& w, Matrix* V = nullptr) {
  if constexpr (Matrix::MaxRowsAtCompileTime == Eigen::Dynamic) {
    if (M.rows() >= 64) return symmetric_eigen_large(M, w, V);
  }
  Eigen::SelfAdjointEigenSolver<Matrix> eig(M, V ? Eigen::ComputeEigenvectors : Eigen::EigenvaluesOnly);
  if (eig.info() != Eigen::Success) return false;
  w = eig.eigenvalues();
  if (V) *V = eig.eigenvectors();
  return true;
}

/// Copies the lower triangle onto the upper one, making the matrix exactly symmetric.
template <typename Derived>
void make_symmetric_from_lower(Eigen::MatrixBase<Derived>& X) {
  X.template triangularView<Eigen::StrictlyUpper>() = X.transpose();
}

/// (X + X^T) / 2 without overflow for entries near the double range.
template <typename Derived>
typename Derived::PlainObject symmetric_part(const Eigen::MatrixBase<Derived>& X) {
  // Halving first keeps entries near the double range finite; addition commutes, so the
  // result is exactly symmetric.
  return 0.5 * X + 0.5 * X.transpose();
}

/// The smallest power-of-two exponent e with |x| < 2^e for every entry (nothing for a zero or
/// empty matrix), so that scaling by 2^-e is exact and leaves every entry below 1 in magnitude.
std::optional<int> scale_exponent(const Eigen::Ref<const MatrixXd>& X);
/// The same for a matrix whose largest magnitude is `biggest` (nothing unless biggest > 0).
std::optional<int> scale_exponent(double biggest);

/// X *= 2^e in place, exactly (bar overflow and underflow of the results), for any e.
template <typename Derived>
void multiply_by_power_of_two(Eigen::MatrixBase<Derived>& X, int e) {
  // 2^e is itself a normal double for |e| <= 1022; beyond that (denormal data, say) scale each
  // entry with ldexp so the factor never overflows or underflows on its own.
  if (e >= -1022 && e <= 1022) {
    X *= std::ldexp(1.0, e);
  } else {
    X = X.unaryExpr([e](double x) { return std::ldexp(x, e); });
  }
}

/// X * 2^e, exactly (see multiply_by_power_of_two).
template <typename Derived>
typename Derived::PlainObject times_power_of_two(const Eigen::MatrixBase<Derived>& X, int e) {
  typename Derived::PlainObject Y = X;
  multiply_by_power_of_two(Y, e);
  return Y;
}

// The helpers above for the matrix types of the estimators' kernels (MatrixXd and the bounded
// sizes of the small-problem path: n <= 2 and n <= 8, and their factors of [A B], 4 and 16) are
// compiled once, in linalg_instances.cpp, and only declared here: each kernel's file would
// otherwise compile its own copy of Eigen's eigensolver and products for every size.
template <int Max>
using BoundedMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::ColMajor, Max, Max>;
template <int Max>
using BoundedVector = Eigen::Matrix<double, Eigen::Dynamic, 1, Eigen::ColMajor, Max, 1>;

#define SPDFIT_LINALG_SVD(INSTANTIATE, Max)                                                                   \
  INSTANTIATE void svd_into<BoundedMatrix<Max>, BoundedMatrix<Max>>(const Eigen::MatrixBase<BoundedMatrix<Max>>&, \
                                                                   BasicSvd<BoundedMatrix<Max>>&, bool, bool);
#define SPDFIT_LINALG_EIGEN(INSTANTIATE, Max)                                                              \
  INSTANTIATE bool symmetric_eigen<BoundedMatrix<Max>, BoundedVector<Max>>(const BoundedMatrix<Max>&,          \
                                                                           BoundedVector<Max>&, BoundedMatrix<Max>*);
#define SPDFIT_LINALG_PRODUCT(INSTANTIATE, Max)                                                                \
  INSTANTIATE void product_into<BoundedMatrix<Max>>(const BoundedMatrix<Max>&, bool, const BoundedMatrix<Max>&, bool, \
                                                    BoundedMatrix<Max>&);
/// Every instantiation compiled in linalg_instances.cpp, as INSTANTIATE(kind, bound).
#ifdef SPDFIT_NO_SMALL_PROBLEM_KERNELS
#define SPDFIT_LINALG_INSTANCES(INSTANTIATE) \
  SPDFIT_LINALG_SVD(INSTANTIATE, Eigen::Dynamic) SPDFIT_LINALG_EIGEN(INSTANTIATE, Eigen::Dynamic)
#else
#define SPDFIT_LINALG_INSTANCES(INSTANTIATE)                                                          \
  SPDFIT_LINALG_SVD(INSTANTIATE, Eigen::Dynamic) SPDFIT_LINALG_SVD(INSTANTIATE, 2)                     \
  SPDFIT_LINALG_SVD(INSTANTIATE, 4) SPDFIT_LINALG_SVD(INSTANTIATE, 8) SPDFIT_LINALG_SVD(INSTANTIATE, 16) \
  SPDFIT_LINALG_EIGEN(INSTANTIATE, Eigen::Dynamic) SPDFIT_LINALG_EIGEN(INSTANTIATE, 2)                 \
  SPDFIT_LINALG_EIGEN(INSTANTIATE, 8) SPDFIT_LINALG_PRODUCT(INSTANTIATE, 2) SPDFIT_LINALG_PRODUCT(INSTANTIATE, 8)
#endif

#define SPDFIT_LINALG_DECLARE extern template
SPDFIT_LINALG_INSTANCES(SPDFIT_LINALG_DECLARE)
#undef SPDFIT_LINALG_DECLARE

}  // namespace spdfit::detail
