// Internal: the one-sided (Hestenes) Jacobi SVD with the relative stopping criterion of
// Demmel and Veselic, "Jacobi's method is more accurate than QR" (SIAM J. Matrix Anal. Appl.,
// 1992), and Drmac and Veselic (LAPACK's dgesvj).
//
// Why not Eigen::JacobiSVD: it is two-sided and stops when the off-diagonal entries fall below
// 2 eps times the *largest* diagonal entry, an absolute criterion that leaves the singular
// vectors of small singular values inaccurate. On the SPDE polar step (M = R_b R11^T, whose
// singular values span cond(A)^2) that cost ~1e-2 relative error at cond(A) = 1e8 where the
// relative criterion below gives ~1e-7 (bench/accuracy.py). Rotating a pair of columns only
// while |g_p^T g_q| > tol ||g_p|| ||g_q|| makes the result as accurate as the columns' own
// scaling allows, and the method works for fixed-size matrices without heap allocation.
#pragma once

#include <Eigen/Core>
#include <cmath>
#include <limits>

namespace spdfit::detail {

/// One-sided Jacobi SVD of a square or tall G (rows >= cols): on return G holds U diag(s)
/// (its columns are the left singular vectors scaled by the singular values, unsorted), V the
/// accumulated rotations (so that G_in V = G_out) when `V` is non-null. Returns the number of
/// sweeps used (at most max_sweeps).
template <typename MatrixG, typename MatrixV>
int one_sided_jacobi(Eigen::MatrixBase<MatrixG>& G, MatrixV* V, int max_sweeps = 60) {
  using Eigen::Index;
  const Index n = G.cols();
  const double tolerance = std::numeric_limits<double>::epsilon() * static_cast<double>(G.rows());
  if (V) V->setIdentity(n, n);
  int sweep = 0;
  for (; sweep < max_sweeps; ++sweep) {
    bool rotated = false;
    for (Index p = 0; p + 1 < n; ++p) {
      for (Index q = p + 1; q < n; ++q) {
        const double a = G.col(p).squaredNorm();
        const double b = G.col(q).squaredNorm();
        const double c = G.col(p).dot(G.col(q));
        if (!(std::abs(c) > tolerance * std::sqrt(a) * std::sqrt(b))) continue;
        rotated = true;
        // The rotation that diagonalizes [a c; c b] (Rutishauser's formulas; |t| <= 1).
        const double zeta = (b - a) / (2.0 * c);
        const double t = (zeta >= 0 ? 1.0 : -1.0) / (std::abs(zeta) + std::sqrt(1.0 + zeta * zeta));
        const double cs = 1.0 / std::sqrt(1.0 + t * t);
        const double sn = cs * t;
        for (Index i = 0; i < G.rows(); ++i) {
          const double gp = G(i, p), gq = G(i, q);
          G(i, p) = cs * gp - sn * gq;
          G(i, q) = sn * gp + cs * gq;
        }
        if (V) {
          for (Index i = 0; i < n; ++i) {
            const double vp = (*V)(i, p), vq = (*V)(i, q);
            (*V)(i, p) = cs * vp - sn * vq;
            (*V)(i, q) = sn * vp + cs * vq;
          }
        }
      }
    }
    if (!rotated) break;
  }
  return sweep;
}

}  // namespace spdfit::detail
