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
#include <algorithm>
#include <cmath>
#include <limits>

namespace spdfit::detail {

/// Columns x, y (length k, distinct) <- (cs x - sn y, sn x + cs y): a loop the compiler
/// vectorizes, which Eigen's JacobiRotation does not for columns of differing alignment.
inline void rotate_columns(double* __restrict x, double* __restrict y, Eigen::Index k, double cs, double sn) {
  for (Eigen::Index i = 0; i < k; ++i) {
    const double xi = x[i], yi = y[i];
    x[i] = cs * xi - sn * yi;
    y[i] = sn * xi + cs * yi;
  }
}

/// One-sided Jacobi SVD of a square or tall G (rows >= cols): on return G holds U diag(s)
/// (its columns are the left singular vectors scaled by the singular values, unsorted), V the
/// accumulated rotations (so that G_in V = G_out) when `V` is non-null. Returns the number of
/// sweeps used (at most max_sweeps).
template <typename MatrixG, typename MatrixV>
int one_sided_jacobi(Eigen::MatrixBase<MatrixG>& G, MatrixV* V, int max_sweeps = 60) {
  using Eigen::Index;
  static_assert(MatrixG::InnerStrideAtCompileTime == 1 && !(MatrixG::Flags & Eigen::RowMajorBit),
                "one_sided_jacobi rotates contiguous columns");
  const Index n = G.cols();
  const double tolerance = std::numeric_limits<double>::epsilon() * static_cast<double>(G.rows());
  if (V) V->setIdentity(n, n);
  // The squared column norms, recomputed at the start of every sweep and updated through it by
  // the exact effect of each rotation (a' = a - t c, b' = b + t c, as LAPACK's dgesvj does),
  // so that a pair costs one dot product instead of three. An update that loses more than half
  // of a norm (cancellation) is replaced by the norm itself.
  Eigen::Matrix<double, Eigen::Dynamic, 1, Eigen::ColMajor, MatrixG::MaxColsAtCompileTime, 1> norms2(n);
  // A sweep visits every pair once in round-robin order (the "circle method" of tournament
  // scheduling): n - 1 rounds (n even; odd n adds a dummy column) of n/2 pairs with no column in
  // common. A pair's rotation angle is a chain of square roots and divisions some 100 cycles
  // long; the pairs of a round are independent, so their angles are computed together, where
  // the processor overlaps the chains (the cyclic order (0,1), (0,2), ... serializes them all).
  // The result is what visiting the round's pairs one by one would give.
  constexpr int kMaxSlots =
      MatrixG::MaxColsAtCompileTime == Eigen::Dynamic ? Eigen::Dynamic : MatrixG::MaxColsAtCompileTime + 1;
  constexpr int kMaxPairs = kMaxSlots == Eigen::Dynamic ? Eigen::Dynamic : kMaxSlots / 2;
  using PairIndices = Eigen::Matrix<Index, Eigen::Dynamic, 1, Eigen::ColMajor, kMaxPairs, 1>;
  using PairValues = Eigen::Matrix<double, Eigen::Dynamic, 1, Eigen::ColMajor, kMaxPairs, 1>;
  const Index slots = n + (n % 2);
  const Index pairs = slots / 2;
  Eigen::Matrix<Index, Eigen::Dynamic, 1, Eigen::ColMajor, kMaxSlots, 1> circle(slots);
  PairIndices P(pairs), Q(pairs);
  PairValues C(pairs), T(pairs), CS(pairs), SN(pairs);
  int sweep = 0;
  for (; sweep < max_sweeps; ++sweep) {
    bool rotated = false;
    for (Index k = 0; k < n; ++k) norms2(k) = G.col(k).squaredNorm();
    for (Index k = 0; k < slots; ++k) circle(k) = k;
    for (Index round = 0; round + 1 < slots; ++round) {
      Index active = 0;  // the round's pairs that need a rotation, first in P, Q
      for (Index k = 0; k < pairs; ++k) {
        const Index p = std::min(circle(k), circle(slots - 1 - k));
        const Index q = std::max(circle(k), circle(slots - 1 - k));
        if (q >= n) continue;  // paired with the dummy column
        const double c = G.col(p).dot(G.col(q));
        if (!(std::abs(c) > tolerance * std::sqrt(norms2(p)) * std::sqrt(norms2(q)))) continue;
        P(active) = p;
        Q(active) = q;
        C(active) = c;
        ++active;
      }
      for (Index k = 0; k < active; ++k) {
        // The rotation that diagonalizes [a c; c b] (Rutishauser's formulas; |t| <= 1).
        const double a = norms2(P(k)), b = norms2(Q(k)), c = C(k);
        const double zeta = (b - a) / (2.0 * c);
        const double t = (zeta >= 0 ? 1.0 : -1.0) / (std::abs(zeta) + std::sqrt(1.0 + zeta * zeta));
        T(k) = t;
        CS(k) = 1.0 / std::sqrt(1.0 + t * t);
        SN(k) = CS(k) * t;
      }
      for (Index k = 0; k < active; ++k) {
        const Index p = P(k), q = Q(k);
        rotate_columns(G.col(p).data(), G.col(q).data(), G.rows(), CS(k), SN(k));
        if (V) rotate_columns(V->col(p).data(), V->col(q).data(), n, CS(k), SN(k));
        const double a = norms2(p), b = norms2(q);
        norms2(p) = a - T(k) * C(k);
        norms2(q) = b + T(k) * C(k);
        if (!(norms2(p) > 0.5 * a)) norms2(p) = G.col(p).squaredNorm();
        if (!(norms2(q) > 0.5 * b)) norms2(q) = G.col(q).squaredNorm();
      }
      rotated = rotated || active > 0;
      // Keep slot 0, turn the others one place.
      const Index last = circle(slots - 1);
      for (Index k = slots - 1; k > 1; --k) circle(k) = circle(k - 1);
      if (slots > 1) circle(1) = last;
    }
    if (!rotated) break;
  }
  return sweep;
}

}  // namespace spdfit::detail
