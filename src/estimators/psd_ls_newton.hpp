// Internal: the semismooth Newton method of psd-ls (psd_ls_kernel.cpp), on Robinson's normal map
// of the diagonal quadratic over the positive semidefinite cone.
#pragma once

#include <Eigen/Core>
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "factor/basic_reduction.hpp"
#include "numerics/linalg.hpp"

namespace spdfit::detail {

/// At most this many Newton iterations; their residuals are kept for the tests of the rate.
inline constexpr int kPsdLsMaxNewton = 40;

/// What psd_ls_newton reports besides its iterate.
struct PsdLsNewtonInfo {
  int iterations = 0;                                  ///< Newton steps taken
  int cg_iterations = 0;                               ///< conjugate-gradient iterations, all steps together
  std::array<double, kPsdLsMaxNewton + 1> residual{};  ///< ||F(Z_k)||_F / scale, k = 0..iterations
  bool stalled = false;                                ///< the line search failed (the caller falls back)
};

/// The semismooth Newton method on the normal map of
///
///     min phi(W) = sum_ij c_ij W_ij^2 / 2 - sum_ij G_ij W_ij   over symmetric W >= 0,
///
/// c_ij > 0 entrywise (c symmetric; psd-ls's preconditioned curvature): with P the projection onto
/// the semidefinite cone, F(Z) = c o P(Z) - G + Z - P(Z) (Robinson's normal map) vanishes exactly
/// where W = P(Z) is the minimizer and Z - W = -(c o W - G) the multiplier's negative. F is
/// strongly semismooth, and with Z = Q diag(lambda) Q^T, lambda's positive part the trailing k
/// (set a), the rest (set g), a generalized Jacobian is
///
///     J D = (I - P'(Z)) D + c o P'(Z) D,   P'(Z) D = Q (Omega o (Q^T D Q)) Q^T,
///
/// Omega_ij = 1 on a x a, lambda_i / (lambda_i - lambda_j) on a x g, 0 on g x g (Sun & Sun 2002;
/// the Jacobian of Qi & Sun 2006's nearest correlation method). In Q's coordinates, with
/// E~ = Omega o D~ (the change of W, zero on g x g), the a-rows of J D = R are the symmetric
/// positive definite system
///
///     [Q^T (c o (Q E~ Q^T)) Q]_(a rows) + Theta o E~ = R~_(a rows),
///
/// with Theta_ij = -lambda_j / lambda_i on a x g,
///
/// solved by preconditioned conjugate gradients (Jacobi, from (Q o Q)^T c (Q o Q)) at O(n^2 k)
/// per product, and the g x g block of D~ follows from its rows directly. The step is damped
/// by an Armijo search on ||F||_F. Locally quadratic where the minimizer is strictly
/// complementary (rank(W) + rank(multiplier) = n), as the conjugate-gradient tolerance follows
/// ||F||.
///
/// Starts at Z (updated in place); stops when ||F||_F <= `stop` (returned true), after
/// `max_iterations` steps, or when the line search fails or ||F|| stops decreasing (rounding;
/// returned false, info.stalled for a failed search). W = P(Z) of the last iterate, with its
/// number of positive eigenvalues in `rank`. `scale` normalizes info.residual. False also when
/// an eigensolver fails (info.iterations then < 0).
template <typename Matrix, typename Vector>
class PsdLsNewton {
 public:
  PsdLsNewton(const Matrix& c, const Matrix& G) : c_(c), G_(G), n_(c.rows()) {}

  bool solve(Matrix& Z, double stop, double scale, int max_iterations, Matrix& W, Eigen::Index& rank,
             PsdLsNewtonInfo& info) {
    info = PsdLsNewtonInfo{};
    Point now;
    if (!evaluate(Z, now)) return fail(info);
    info.residual[0] = now.norm_f / scale;
    bool converged = now.norm_f <= stop;
    while (!converged && info.iterations < std::min(max_iterations, kPsdLsMaxNewton)) {
      Matrix D;
      info.cg_iterations += direction(now, scale, D);
      // Armijo on ||F||: the Newton direction is one of descent for ||F||^2 / 2.
      Point next;
      double t = 1.0;
      bool accepted = false;
      for (int k = 0; k < 12; ++k, t *= 0.5) {
        next.Z = now.Z + t * D;
        if (!evaluate(next.Z, next)) return fail(info);
        if (next.norm_f <= (1.0 - 1e-4 * t) * now.norm_f) {
          accepted = true;
          break;
        }
      }
      if (!accepted) {
        info.stalled = true;
        break;
      }
      ++info.iterations;
      info.residual[info.iterations] = next.norm_f / scale;
      const bool slow = next.norm_f > 0.5 * now.norm_f;  // at rounding, or far from quadratic
      now = std::move(next);
      converged = now.norm_f <= stop;
      // Past the region of fast convergence with a residual already near rounding: stop, the caller
      // checks the point (and falls back when it is not good enough).
      if (slow && now.norm_f <= 1e3 * stop) break;
    }
    Z = now.Z;
    W = now.W;
    rank = now.rank;
    return converged;
  }

 private:
  // Z = Q diag(lambda) Q^T, W = P(Z), F = c o W - G + Z - W.
  struct Point {
    Matrix Z, Q, W, F;
    Vector lambda;
    Eigen::Index rank = 0;
    double norm_f = 0.0;
  };

  bool evaluate(const Matrix& Z, Point& p) const {
    if (&p.Z != &Z) p.Z = Z;
    if (!symmetric_eigen(Z, p.lambda, &p.Q)) return false;
    Eigen::Index first = 0;
    while (first < n_ && !(p.lambda(first) > 0.0)) ++first;
    p.rank = n_ - first;
    const auto Qa = p.Q.rightCols(p.rank);
    p.W.setZero(n_, n_);
    if (p.rank > 0) {
      Matrix scaled = Qa * p.lambda.tail(p.rank).asDiagonal();
      product_into(Matrix(scaled), false, Matrix(Qa), true, p.W);
      p.W = symmetric_part(p.W);
    }
    p.F = c_.cwiseProduct(p.W) - G_ + Z - p.W;
    p.norm_f = p.F.norm();
    return true;
  }

  // The a-rows of Q^T (c o (Q X Q^T)) Q for X zero on g x g (stored full, symmetric), as a full
  // symmetric matrix zero on g x g; `full_gg` receives that product's g x g block when given.
  void curvature(const Point& p, const Matrix& X, Matrix& out, Matrix* full_gg = nullptr) const {
    const Eigen::Index k = p.rank, a = n_ - k;
    // Q X Q^T = T + T^T with T = Q_a [X_ag, X_aa / 2] Q^T.
    Matrix half = X.bottomRows(k);
    half.rightCols(k) *= 0.5;
    Matrix rows, T, E;
    product_into(half, false, p.Q, true, rows);  // k x n
    const Matrix Qa = p.Q.rightCols(k);
    product_into(Qa, false, rows, false, T);  // n x n
    E = c_.cwiseProduct(T + T.transpose());
    Matrix left, back;
    product_into(Qa, true, E, false, left);       // k x n
    product_into(left, false, p.Q, false, back);  // k x n: the a-rows
    out.setZero(n_, n_);
    out.bottomRows(k) = back;
    out.topRightCorner(a, k) = back.leftCols(a).transpose();
    if (full_gg) {
      Matrix Qg = p.Q.leftCols(a), EQg, gg;
      product_into(E, false, Qg, false, EQg);
      product_into(Qg, true, EQg, false, gg);
      *full_gg = gg;
    }
  }

  // Theta o X on a x g (and its transpose), 0 elsewhere, added to `out`.
  void add_theta(const Point& p, const Matrix& X, Matrix& out) const {
    const Eigen::Index k = p.rank, a = n_ - k;
    for (Eigen::Index j = 0; j < a; ++j)
      for (Eigen::Index i = 0; i < k; ++i) {
        const double theta = -p.lambda(j) / p.lambda(a + i);
        out(a + i, j) += theta * X(a + i, j);
        out(j, a + i) += theta * X(j, a + i);
      }
  }

  // The Newton direction D at p; returns the conjugate-gradient iterations.
  int direction(const Point& p, double scale, Matrix& D) const {
    const Eigen::Index k = p.rank, a = n_ - k;
    Matrix R;  // Q^T (-F) Q
    {
      Matrix FQ;
      product_into(Matrix(-p.F), false, p.Q, false, FQ);
      product_into(p.Q, true, FQ, false, R);
      R = symmetric_part(R);
    }
    Matrix rhs = R;
    rhs.topLeftCorner(a, a).setZero();
    // Jacobi preconditioner: the diagonal of X -> Q^T (c o (Q X Q^T)) Q on e_i e_j^T is
    // sum_uv c_uv Q_ui^2 Q_vj^2.
    Matrix inverse_diagonal;
    {
      const Matrix S = p.Q.cwiseAbs2();
      Matrix cS, diagonal;
      product_into(c_, false, S, false, cS);
      product_into(S, true, cS, false, diagonal);
      for (Eigen::Index j = 0; j < a; ++j)
        for (Eigen::Index i = 0; i < k; ++i) {
          const double theta = -p.lambda(j) / p.lambda(a + i);
          diagonal(a + i, j) += theta;
          diagonal(j, a + i) += theta;
        }
      inverse_diagonal = diagonal.cwiseMax(std::numeric_limits<double>::min()).cwiseInverse();
      inverse_diagonal.topLeftCorner(a, a).setZero();
    }
    // Conjugate gradients to the relative residual min(1e-2, ||F|| / scale): the forcing term of
    // an inexact Newton method that keeps the quadratic rate.
    const double tolerance = std::min(1e-2, p.norm_f / scale) * rhs.norm();
    Matrix X = Matrix::Zero(n_, n_), r = rhs, z = inverse_diagonal.cwiseProduct(r), d = z, w;
    double rz = r.cwiseProduct(z).sum();
    int iterations = 0;
    const int limit = static_cast<int>(std::min<Eigen::Index>(n_ * (n_ + 1) / 2, 200));
    while (iterations < limit && r.norm() > tolerance) {
      curvature(p, d, w);
      add_theta(p, d, w);
      const double dw = d.cwiseProduct(w).sum();
      if (!(dw > 0.0)) break;
      const double step = rz / dw;
      X += step * d;
      r -= step * w;
      z = inverse_diagonal.cwiseProduct(r);
      const double rz_next = r.cwiseProduct(z).sum();
      d = z + (rz_next / rz) * d;
      rz = rz_next;
      ++iterations;
    }
    // D~: a x a as E~, a x g as E~ / Omega, g x g from its rows: R~_gg - [Q^T (c o E) Q]_gg.
    Matrix image, gg;
    curvature(p, X, image, &gg);
    Matrix Dt = X;
    for (Eigen::Index j = 0; j < a; ++j)
      for (Eigen::Index i = 0; i < k; ++i) {
        const double li = p.lambda(a + i), lj = p.lambda(j);
        Dt(a + i, j) = X(a + i, j) * (li - lj) / li;
        Dt(j, a + i) = Dt(a + i, j);
      }
    Dt.topLeftCorner(a, a) = R.topLeftCorner(a, a) - gg;
    Matrix DQ;
    product_into(p.Q, false, Dt, false, DQ);
    product_into(DQ, false, p.Q, true, D);
    D = symmetric_part(D);
    return iterations;
  }

  static bool fail(PsdLsNewtonInfo& info) {
    info.iterations = -1;
    return false;
  }

  const Matrix& c_;
  const Matrix& G_;
  Eigen::Index n_;
};

}  // namespace spdfit::detail
