#include "numerics/linalg.hpp"

#include <Eigen/Cholesky>
#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include "numerics/block_qr.hpp"
#include "numerics/cholesky_downdate.hpp"

#ifdef SPDFIT_HAVE_LAPACK
#include <cblas.h>
#include <lapacke.h>
#endif

namespace spdfit::detail {

namespace {
// From this many columns on, the QR runs on LAPACK (when built with it); below, on spdfit's block
// QR (block_qr.hpp), which on one thread outran dgeqrf on two at 100 columns (a streamed fit of
// 2e6 x 50 + 50 .npy rows: 1.7 s against 3.1-4.1 s, in-memory at 4e5 rows 1.1 s against
// 1.8-2.4 s, AMD EPYC), and the streaming reader's block QRs (each on a thread of its own) must
// not start OpenBLAS threads.
constexpr Index kLapackMinColumns = 128;
}  // namespace

void svd_large(const Eigen::Ref<const MatrixXd>& A, BasicSvd<MatrixXd>& out, bool compute_u, bool compute_v) {
#ifdef SPDFIT_HAVE_LAPACK
  if (A.rows() >= A.cols() && A.cols() > 0) {
    const lapack_int m = static_cast<lapack_int>(A.rows()), n = static_cast<lapack_int>(A.cols());
    MatrixXd work = A;  // dgesdd overwrites its input
    out.s.resize(n);
    const bool vectors = compute_u || compute_v;
    MatrixXd U(vectors ? m : 1, vectors ? n : 1), VT(vectors ? n : 1, vectors ? n : 1);
    const lapack_int info =
        LAPACKE_dgesdd(LAPACK_COL_MAJOR, vectors ? 'S' : 'N', m, n, work.data(), m, out.s.data(), U.data(),
                       static_cast<lapack_int>(U.rows()), VT.data(), static_cast<lapack_int>(VT.rows()));
    if (info != 0) throw std::runtime_error("the SVD (LAPACK dgesdd) failed: info = " + std::to_string(info));
    if (compute_u) out.U = std::move(U);
    if (compute_v) out.V = VT.transpose();
    return;
  }
#endif
  unsigned options = 0;
  if (compute_u) options |= Eigen::ComputeThinU;
  if (compute_v) options |= Eigen::ComputeThinV;
  Eigen::BDCSVD<MatrixXd> dec(A, options);
  out.s = dec.singularValues();
  if (compute_u) out.U = dec.matrixU();
  if (compute_v) out.V = dec.matrixV();
}

namespace {

#ifdef SPDFIT_HAVE_LAPACK
// The BLAS's general product, C = op(A) op(B), in either precision.
void gemm(bool transpose_a, bool transpose_b, blasint m, blasint n, blasint k, const double* A, blasint lda,
          const double* B, blasint ldb, double* C, blasint ldc) {
  cblas_dgemm(CblasColMajor, transpose_a ? CblasTrans : CblasNoTrans, transpose_b ? CblasTrans : CblasNoTrans, m, n,
              k, 1.0, A, lda, B, ldb, 0.0, C, ldc);
}

void gemm(bool transpose_a, bool transpose_b, blasint m, blasint n, blasint k, const float* A, blasint lda,
          const float* B, blasint ldb, float* C, blasint ldc) {
  cblas_sgemm(CblasColMajor, transpose_a ? CblasTrans : CblasNoTrans, transpose_b ? CblasTrans : CblasNoTrans, m, n,
              k, 1.0f, A, lda, B, ldb, 0.0f, C, ldc);
}
#endif

template <typename Matrix>
void multiply_any(const Eigen::Ref<const Matrix>& A, bool transpose_a, const Eigen::Ref<const Matrix>& B,
                  bool transpose_b, Matrix& C) {
  const Index m = transpose_a ? A.cols() : A.rows(), k = transpose_a ? A.rows() : A.cols();
  const Index n = transpose_b ? B.rows() : B.cols();
  if ((transpose_b ? B.cols() : B.rows()) != k) throw std::invalid_argument("multiply: the shapes do not match");
  C.resize(m, n);
#ifdef SPDFIT_HAVE_LAPACK
  constexpr double kBlasMinProduct = 64.0 * 64.0 * 64.0;
  if (static_cast<double>(m) * static_cast<double>(n) * static_cast<double>(k) >= kBlasMinProduct) {
    gemm(transpose_a, transpose_b, static_cast<blasint>(m), static_cast<blasint>(n), static_cast<blasint>(k), A.data(),
         static_cast<blasint>(A.outerStride()), B.data(), static_cast<blasint>(B.outerStride()), C.data(),
         static_cast<blasint>(C.outerStride()));
    return;
  }
#endif
  if (k == 0) {
    C.setZero();
  } else {
    eigen_product(A, transpose_a, B, transpose_b, C);
  }
}

}  // namespace

void multiply(const Eigen::Ref<const MatrixXd>& A, bool transpose_a, const Eigen::Ref<const MatrixXd>& B,
              bool transpose_b, MatrixXd& C) {
  multiply_any<MatrixXd>(A, transpose_a, B, transpose_b, C);
}

void multiply(const Eigen::Ref<const Eigen::MatrixXf>& A, bool transpose_a, const Eigen::Ref<const Eigen::MatrixXf>& B,
              bool transpose_b, Eigen::MatrixXf& C) {
  multiply_any<Eigen::MatrixXf>(A, transpose_a, B, transpose_b, C);
}

void solve_upper_in_place(const Eigen::Ref<const MatrixXd>& U, MatrixXd& L) {
  if (L.size() == 0) return;  // Eigen's solve takes the address of the first entry
#ifdef SPDFIT_HAVE_LAPACK
  if (U.rows() >= 64) {
    cblas_dtrsm(CblasColMajor, CblasLeft, CblasUpper, CblasNoTrans, CblasNonUnit, static_cast<blasint>(L.rows()),
                static_cast<blasint>(L.cols()), 1.0, U.data(), static_cast<blasint>(U.outerStride()), L.data(),
                static_cast<blasint>(L.outerStride()));
    return;
  }
#endif
  U.triangularView<Eigen::Upper>().solveInPlace(L);
}

void solve_upper_from_right_in_place(const Eigen::Ref<const MatrixXd>& U, MatrixXd& L) {
  if (L.size() == 0) return;
#ifdef SPDFIT_HAVE_LAPACK
  if (U.rows() >= 64) {
    cblas_dtrsm(CblasColMajor, CblasRight, CblasUpper, CblasNoTrans, CblasNonUnit, static_cast<blasint>(L.rows()),
                static_cast<blasint>(L.cols()), 1.0, U.data(), static_cast<blasint>(U.outerStride()), L.data(),
                static_cast<blasint>(L.outerStride()));
    return;
  }
#endif
  U.triangularView<Eigen::Upper>().solveInPlace<Eigen::OnTheRight>(L);
}

bool cholesky_downdate(const Eigen::Ref<const MatrixXd>& R, const Eigen::Ref<const Eigen::VectorXd>& x, MatrixXd& Rc) {
  const Index k = R.rows();
  if (R.cols() != k || x.size() != k) throw std::logic_error("cholesky_downdate: R must be k x k and x of size k");
  for (Index i = 0; i < k; ++i) {
    if (!(std::abs(R(i, i)) > 0.0)) return false;
  }
  Rc = R.triangularView<Eigen::Upper>();
  // R^T a = x; then the rotations that take (a, sqrt(1 - ||a||^2)) to (0, 1), last entry first.
  Eigen::VectorXd s = x;
  R.triangularView<Eigen::Upper>().transpose().solveInPlace(s);
  const double norm2 = s.squaredNorm();
  if (!(norm2 < 1.0)) return false;
  double alpha = std::sqrt(1.0 - norm2);
  Eigen::VectorXd c(k);
  for (Index i = k - 1; i >= 0; --i) {
    const double scale = alpha + std::abs(s(i));
    const double p = alpha / scale, q = s(i) / scale;
    const double norm = std::sqrt(p * p + q * q);
    c(i) = p / norm;
    s(i) = q / norm;
    alpha = scale * norm;
  }
  for (Index j = 0; j < k; ++j) {
    double carried = 0.0;
    for (Index i = j; i >= 0; --i) {
      const double t = c(i) * carried + s(i) * Rc(i, j);
      Rc(i, j) = c(i) * Rc(i, j) - s(i) * carried;
      carried = t;
    }
  }
  return Rc.allFinite();
}

void lower_gram(const Eigen::Ref<const MatrixXd>& L, MatrixXd& X) {
  X.setZero(L.rows(), L.rows());
  if (L.cols() == 0) return;
#ifdef SPDFIT_HAVE_LAPACK
  if (L.rows() >= 64) {
    cblas_dsyrk(CblasColMajor, CblasLower, CblasNoTrans, static_cast<blasint>(L.rows()),
                static_cast<blasint>(L.cols()), 1.0, L.data(), static_cast<blasint>(L.outerStride()), 0.0, X.data(),
                static_cast<blasint>(X.outerStride()));
    return;
  }
#endif
  X.selfadjointView<Eigen::Lower>().rankUpdate(L);
}

bool has_cholesky(const Eigen::Ref<const MatrixXd>& X) {
#ifdef SPDFIT_HAVE_LAPACK
  if (X.rows() >= 64) {
    MatrixXd work = X;
    const lapack_int n = static_cast<lapack_int>(X.rows());
    return LAPACKE_dpotrf(LAPACK_COL_MAJOR, 'L', n, work.data(), n) == 0;
  }
#endif
  return Eigen::LLT<MatrixXd>(X).info() == Eigen::Success;
}

bool symmetric_eigen_large(const Eigen::Ref<const MatrixXd>& M, VectorXd& w, MatrixXd* V) {
#ifdef SPDFIT_HAVE_LAPACK
  if (M.rows() > 0) {
    MatrixXd work = M;  // dsyevd overwrites its input with the eigenvectors
    if (!symmetric_eigen_in_place(work, w, V != nullptr)) return false;
    if (V) *V = std::move(work);
    return true;
  }
#endif
  Eigen::SelfAdjointEigenSolver<MatrixXd> eig(M, V ? Eigen::ComputeEigenvectors : Eigen::EigenvaluesOnly);
  if (eig.info() != Eigen::Success) return false;
  w = eig.eigenvalues();
  if (V) *V = eig.eigenvectors();
  return true;
}

bool symmetric_eigen_in_place(MatrixXd& M, VectorXd& w, bool vectors) {
  const Index n = M.rows();
#ifdef SPDFIT_HAVE_LAPACK
  // From 64 rows on, as every LAPACK path here: below, Eigen's solver, whose bits are the same on
  // every CPU (OpenBLAS's dsyevd kernels differ by CPU, and with them the last bits of a repair).
  if (n >= 64) {
    w.resize(n);
    const lapack_int info = LAPACKE_dsyevd(LAPACK_COL_MAJOR, vectors ? 'V' : 'N', 'L', static_cast<lapack_int>(n),
                                           M.data(), static_cast<lapack_int>(n), w.data());
    return info == 0;
  }
#endif
  Eigen::SelfAdjointEigenSolver<MatrixXd> eig(M, vectors ? Eigen::ComputeEigenvectors : Eigen::EigenvaluesOnly);
  if (eig.info() != Eigen::Success) return false;
  w = eig.eigenvalues();
  if (vectors) M = eig.eigenvectors();
  return true;
}

bool symmetric_eigen_in_place(Eigen::MatrixXf& M, Eigen::VectorXf& w, bool vectors) {
  const Index n = M.rows();
#ifdef SPDFIT_HAVE_LAPACK
  if (n >= 64) {  // as the double-precision solver above
    w.resize(n);
    // The documented workspace sizes, not LAPACKE_ssyevd's query: the query returns the size as a
    // float, which rounds 1 + 6 n + 2 n^2 down from n = 2897 on (above 2^24), and ssyevd then
    // refuses it (Debian 12's OpenBLAS 0.3.21).
    const lapack_int size = static_cast<lapack_int>(n);
    const lapack_int lwork = vectors ? 1 + 6 * size + 2 * size * size : 2 * size + 1;
    const lapack_int liwork = vectors ? 3 + 5 * size : 1;
    std::vector<float> work(static_cast<std::size_t>(lwork));
    std::vector<lapack_int> iwork(static_cast<std::size_t>(liwork));
    const lapack_int info = LAPACKE_ssyevd_work(LAPACK_COL_MAJOR, vectors ? 'V' : 'N', 'L', size, M.data(),
                                                size, w.data(), work.data(), lwork, iwork.data(), liwork);
    return info == 0;
  }
#endif
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXf> eig(M, vectors ? Eigen::ComputeEigenvectors
                                                                 : Eigen::EigenvaluesOnly);
  if (eig.info() != Eigen::Success) return false;
  w = eig.eigenvalues();
  if (vectors) M = eig.eigenvectors();
  return true;
}

void triangular_factor_large(const Eigen::Ref<const MatrixXd>& A, MatrixXd& R) {
  MatrixXd work = A;  // the QR overwrites its input
  R = triangular_factor_in_place(work);
}

Svd svd(const Eigen::Ref<const MatrixXd>& A, bool compute_u, bool compute_v) {
  Svd out;
  svd_into(A, out, compute_u, compute_v);
  return out;
}

FullSvd svd_full_v(const Eigen::Ref<const MatrixXd>& A) {
  FullSvd out;
  if (A.rows() >= A.cols()) {
    Svd dec;
    svd_into(A, dec, true, true);  // V is n x n already
    out.U = std::move(dec.U);
    out.V = std::move(dec.V);
    out.s = std::move(dec.s);
    return out;
  }
  const unsigned options = Eigen::ComputeThinU | Eigen::ComputeFullV;
  if (A.cols() <= svd_detail::kJacobiMaxSize) {
    Eigen::JacobiSVD<MatrixXd> dec(A, options);
    out.U = dec.matrixU();
    out.V = dec.matrixV();
    out.s = dec.singularValues();
  } else {
    Eigen::BDCSVD<MatrixXd> dec(A, options);
    out.U = dec.matrixU();
    out.V = dec.matrixV();
    out.s = dec.singularValues();
  }
  return out;
}

VectorXd singular_values(const Eigen::Ref<const MatrixXd>& A) {
  if (A.size() == 0) return VectorXd(0);
  Svd dec;
  if (A.rows() >= A.cols()) {
    svd_into(A, dec, false, false);
  } else {
    const MatrixXd At = A.transpose();
    svd_into(At, dec, false, false);
  }
  return dec.s;
}

double condition_number(const Eigen::Ref<const VectorXd>& s) {
  if (s.size() == 0) return std::numeric_limits<double>::infinity();
  const double smin = s(s.size() - 1);
  if (!(smin > 0.0)) return std::numeric_limits<double>::infinity();
  return s(0) / smin;
}

MatrixXd triangular_factor(const Eigen::Ref<const MatrixXd>& A) {
  MatrixXd R;
  triangular_factor_into<MatrixXd>(A, R);
  return R;
}

MatrixXd triangular_factor_in_place(Eigen::Ref<MatrixXd> A) {
  const Index cols = A.cols(), k = std::min(A.rows(), cols);
  MatrixXd R = MatrixXd::Zero(cols, cols);
  if (A.rows() == 0) return R;
#ifdef SPDFIT_HAVE_LAPACK
  if (cols >= kLapackMinColumns) {
    Eigen::VectorXd tau(k);
    const lapack_int info =
        LAPACKE_dgeqrf(LAPACK_COL_MAJOR, static_cast<lapack_int>(A.rows()), static_cast<lapack_int>(cols), A.data(),
                       static_cast<lapack_int>(A.outerStride()), tau.data());
    if (info != 0) throw std::runtime_error("the QR (LAPACK dgeqrf) failed: info = " + std::to_string(info));
    R.topRows(k) = A.topRows(k).triangularView<Eigen::Upper>();
    return R;
  }
#endif
  if (A.rows() >= cols) {
    absorb_into_triangle(R, A);  // the QR of [0; A]: spdfit's vectorized block QR
    return R;
  }
  const Eigen::HouseholderQR<Eigen::Ref<MatrixXd>> qr(A);
  R.topRows(k) = qr.matrixQR().topRows(k).triangularView<Eigen::Upper>();
  return R;
}

Index absorb_chunk_rows(Index cols) {
#ifdef SPDFIT_HAVE_LAPACK
  if (cols >= kLapackMinColumns) return std::numeric_limits<Index>::max();
#endif
  return block_qr_chunk_rows(cols);
}

void absorb_rows_into_factor(MatrixXd& R, Eigen::Ref<MatrixXd> rows) {
  const Index cols = R.cols();
#ifdef SPDFIT_HAVE_LAPACK
  if (cols >= kLapackMinColumns) {
    MatrixXd stacked(cols + rows.rows(), cols);
    stacked << R, rows;
    R = triangular_factor_in_place(stacked);
    return;
  }
#endif
  absorb_into_triangle(R, rows);
}

std::optional<int> scale_exponent(const Eigen::Ref<const MatrixXd>& X) {
  if (X.size() == 0) return std::nullopt;
  return scale_exponent(X.cwiseAbs().maxCoeff());
}

std::optional<int> scale_exponent(double biggest) {
  if (!(biggest > 0.0)) return std::nullopt;
  int e = 0;
  std::frexp(biggest, &e);  // biggest = f 2^e with f in [0.5, 1): |x| < 2^e
  return e;
}

}  // namespace spdfit::detail
