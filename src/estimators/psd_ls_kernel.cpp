#include "estimators/psd_ls_kernel.hpp"

#include <Eigen/Eigenvalues>
#include <Eigen/QR>
#include <algorithm>
#include <cmath>
#include <limits>

#include "numerics/linalg.hpp"

namespace spdfit::detail {

using Eigen::Index;

namespace {

constexpr double kEps = std::numeric_limits<double>::epsilon();

// The Newton method's target for ||F||_F / ||G||_F in the preconditioned units: a few hundred
// times the rounding of F's evaluation (an eigendecomposition, backward error about n eps), well
// below what the KKT tolerance asks for; the KKT test in the original units decides.
constexpr double kNewtonStop = 1e-14;

// The problem in the eigenbasis of H = R11^T R11 = V diag(h) V^T (V from the SVD of R11, h = s^2
// with the singular values under the rank cut-off edited to zero). With Y = X - epsilon I and
// Yt = V^T Y V (the orthogonal change keeps the cone):
//
//   ||R11 X - R12||^2 / 2 = sum_ij c_ij Yt_ij^2 / 2 - sum_ij G_ij Yt_ij + const,
//   c_ij = (h_i + h_j) / 2,   G = sym(diag(s) Ct),   Ct = U^T (R12 - epsilon R11) V,
//
// a diagonal quadratic over the positive semidefinite cone, with gradient S = c o Yt - G (the
// multiplier of the KKT conditions, V^T sym(R11^T (R11 X - R12)) V).
template <int MaxN>
struct Problem {
  using Matrix = SquareMatrix<MaxN>;
  using Vector = typename BasicReduction<MaxN>::Vector;
  Index n = 0;
  Vector s;           // singular values of R11 (those under the rank cut-off edited to 0)
  Vector h;           // s^2: curvature of the diagonal, descending
  Matrix c, G;        // see above
  double h_max = 0.0;
  double scale = 0.0;  // ||R11^T R12||_F, the data part of the KKT residual's denominator
  double epsilon = 0.0;
};

// The positive semidefinite part of the symmetric M (eigenvalues clipped at 0), its number of
// positive eigenvalues, their eigenvectors (columns of `range`) and all of M's eigenvalues,
// ascending (`eigenvalues`). False when the eigensolver fails.
template <int MaxN>
bool project(const SquareMatrix<MaxN>& M, SquareMatrix<MaxN>& out, SquareMatrix<MaxN>* range = nullptr,
             Index* rank = nullptr, typename BasicReduction<MaxN>::Vector* eigenvalues = nullptr) {
  using Matrix = SquareMatrix<MaxN>;
  typename BasicReduction<MaxN>::Vector local;
  auto& w = eigenvalues ? *eigenvalues : local;
  Matrix V;
  if (!symmetric_eigen(M, w, &V)) return false;
  const Index n = M.rows();
  Index first = 0;  // eigenvalues ascending: the positive ones are the trailing n - first
  while (first < n && !(w(first) > 0.0)) ++first;
  const Index k = n - first;
  const Matrix W = V.rightCols(k);
  out.setZero(n, n);
  if (k > 0) {
    out.template triangularView<Eigen::Lower>() = W * w.tail(k).asDiagonal() * W.transpose();
    make_symmetric_from_lower(out);
  }
  if (range) *range = W;
  if (rank) *rank = k;
  return true;
}

// The relative KKT residual of the feasible Yt: ||Yt - P(Yt - S / h_max)||_F h_max over
// h_max ||Yt + epsilon I||_F + ||R11^T R12||_F, zero exactly at the minimizer (the natural
// residual of the variational inequality). Negative on eigensolver failure.
template <int MaxN>
double kkt_residual(const Problem<MaxN>& p, const SquareMatrix<MaxN>& Yt) {
  using Matrix = SquareMatrix<MaxN>;
  if (!(p.h_max > 0.0)) return 0.0;  // A = 0: every feasible X is a minimizer
  const Matrix S = p.c.cwiseProduct(Yt) - p.G;
  Matrix P;
  if (!project<MaxN>(Yt - S / p.h_max, P)) return -1.0;
  Matrix X = Yt;
  X.diagonal().array() += p.epsilon;
  return (Yt - P).norm() * p.h_max / (p.h_max * X.norm() + p.scale);
}

// The minimizer over the face {U Z U^T : Z symmetric} of the cone, U an orthonormal basis of the
// range of the iterate: (H_U Z + Z H_U) / 2 = U^T G U with H_U = U^T diag(h) U, solved in the
// eigenbasis of H_U, from the SVD of diag(s) U (directions without curvature get 0, the
// minimum-norm choice). Returns the candidate Yt = U Z+ U^T with Z's rounding-level negative
// eigenvalues clipped, or false when Z is clearly indefinite (the face is too large) or an
// eigensolver fails.
template <int MaxN>
bool face_solve(const Problem<MaxN>& p, const SquareMatrix<MaxN>& U, SquareMatrix<MaxN>& Yt) {
  using Matrix = SquareMatrix<MaxN>;
  const Index k = U.cols(), n = p.n;
  if (k == 0) {
    Yt.setZero(n, n);
    return true;
  }
  // H_U = (diag(s) U)^T (diag(s) U): its eigenpairs from the SVD of diag(s) U, not from the
  // product (which would square its condition number).
  BasicSvd<Matrix> su;
  svd_into(Matrix(p.s.asDiagonal() * U), su, false, true);
  const Matrix& Q = su.V;
  const typename BasicReduction<MaxN>::Vector lambda = su.s.cwiseAbs2();
  typename BasicReduction<MaxN>::Vector z;
  Matrix Zt = Q.transpose() * (U.transpose() * p.G * U) * Q;
  const double floor = static_cast<double>(n) * kEps * p.h_max;
  for (Index j = 0; j < k; ++j)
    for (Index i = 0; i < k; ++i) {
      const double d = 0.5 * (lambda(i) + lambda(j));
      Zt(i, j) = d > floor ? Zt(i, j) / d : 0.0;
    }
  Matrix Z = Q * Zt * Q.transpose();
  Z = symmetric_part(Z);
  Matrix Zp;
  if (!project<MaxN>(Z, Zp, nullptr, nullptr, &z)) return false;
  if (z(0) < -64.0 * static_cast<double>(n) * kEps * z.cwiseAbs().maxCoeff()) return false;
  Yt.noalias() = U * Zp * U.transpose();
  Yt = symmetric_part(Yt);
  return true;
}

// An orthonormal basis of diag(1/d) P (the range of Yt = diag(1/d) W diag(1/d) when P spans W's).
template <int MaxN>
SquareMatrix<MaxN> range_basis(const typename BasicReduction<MaxN>::Vector& d, const SquareMatrix<MaxN>& P) {
  using Matrix = SquareMatrix<MaxN>;
  const Index n = P.rows(), k = P.cols();
  Matrix M = d.cwiseInverse().asDiagonal() * P;
  if (k == 0) return M;
  Eigen::HouseholderQR<Matrix> qr(M);
  return qr.householderQ() * Matrix::Identity(n, k);
}

}  // namespace

template <int MaxN>
bool psd_ls_kernel(const BasicReduction<MaxN>& data, double epsilon_s, int max_iterations, PsdLsKernel<MaxN>& out) {
  using Matrix = SquareMatrix<MaxN>;
  using Vector = typename BasicReduction<MaxN>::Vector;
  const Index n = data.n, r = data.rank_a;

  Problem<MaxN> p;
  p.n = n;
  p.epsilon = epsilon_s;
  Vector s = data.s_a;
  s.tail(n - r).setZero();
  p.s = s;
  p.h = s.cwiseAbs2();
  p.h_max = n > 0 ? p.h(0) : 0.0;
  const Matrix C0 = data.U_a.transpose() * data.R12 * data.V_a;
  p.scale = (s.asDiagonal() * C0).norm();  // ||R11^T R12||_F
  Matrix Ct = C0;
  Ct.diagonal() -= epsilon_s * s;
  p.G = 0.5 * (s.asDiagonal() * Ct + (s.asDiagonal() * Ct).transpose());
  p.c.resize(n, n);
  for (Index j = 0; j < n; ++j)
    for (Index i = 0; i < n; ++i) p.c(i, j) = 0.5 * (p.h(i) + p.h(j));

  // The unconstrained symmetric minimizer: symmetric Procrustes for R12 - epsilon R11.
  Matrix Yt;
  procrustes_eigenbasis(s, Ct, Yt);

  Matrix best;
  double best_kkt = std::numeric_limits<double>::infinity();
  out.iterations = 0;
  auto consider = [&](const Matrix& candidate) {
    const double kkt = kkt_residual(p, candidate);
    if (kkt >= 0.0 && kkt < best_kkt) {
      best_kkt = kkt;
      best = candidate;
    }
    return kkt >= 0.0 && kkt <= kPsdLsTolerance;
  };

  bool done = false;
  {
    Vector w;
    if (!symmetric_eigen(Yt, w)) return false;
    if (w(0) >= 0.0) {  // Procrustes is feasible, so it is the minimizer
      best = Yt;
      const double kkt = kkt_residual(p, Yt);
      if (kkt >= 0.0) best_kkt = kkt;  // an eigensolver failure leaves it unconverged
      done = true;
    }
  }

  if (!done) {
    // Preconditioning by the congruence W = D Yt D, D = diag(d), d_i = h_i^(1/4) (floored for a
    // rank-deficient A): the curvature c_ij / (d_i^2 d_j^2) lies in [1, (k^1/2 + k^-1/2) / 2],
    // k = cond(A)^2, instead of [h_min, h_max].
    Vector d(n);
    const double h_floor = std::max(p.h_max * 1e-12, std::numeric_limits<double>::min());
    for (Index i = 0; i < n; ++i) d(i) = std::sqrt(std::sqrt(std::max(p.h(i), h_floor)));
    Matrix cw(n, n), Gw(n, n);
    for (Index j = 0; j < n; ++j)
      for (Index i = 0; i < n; ++i) {
        const double dd = d(i) * d(j);
        cw(i, j) = p.c(i, j) / (dd * dd);
        Gw(i, j) = p.G(i, j) / dd;
      }
    const double lipschitz = std::max(cw.maxCoeff(), std::numeric_limits<double>::min());

    Matrix W, Wnext, P, candidate, g, gnext;
    Index rank = 0, previous_rank = -1;
    // Procrustes in W: the Newton method's start, or projected gradient's after its projection.
    Matrix start = symmetric_part(Matrix(d.asDiagonal() * Yt * d.asDiagonal()));
    if (r == n) {
      // The semismooth Newton method (psd_ls_newton.hpp), for full-rank A: in W the curvature is
      // positive and well conditioned. Its iterate is exactly feasible; the KKT test in the
      // original units decides, and where it fails projected gradient goes on from the iterate.
      PsdLsNewton<Matrix, Vector> newton(cw, Gw);
      const double scale = std::max(Gw.norm(), std::numeric_limits<double>::min());
      Matrix Z = start;
      newton.solve(Z, kNewtonStop * scale, scale, max_iterations, start, rank, out.newton);
      if (out.newton.iterations < 0) return false;  // an eigensolver failed
      out.iterations = out.newton.iterations;
      if (consider(symmetric_part(Matrix(d.cwiseInverse().asDiagonal() * start * d.cwiseInverse().asDiagonal())))) {
        done = out.newton_solved = true;
      }
    }
    if (!done) {
      if (!project<MaxN>(start, W, &P, &rank)) return false;
      if (face_solve(p, range_basis<MaxN>(d, P), candidate) && consider(candidate)) done = true;
    }
    if (!done) {
      // The objective in W (up to a constant) and its gradient c o W - G.
      auto objective = [&](const Matrix& X) { return 0.5 * cw.cwiseProduct(X).cwiseProduct(X).sum() - Gw.cwiseProduct(X).sum(); };
      g = cw.cwiseProduct(W) - Gw;
      double phi = objective(W);
      // Spectral projected gradient (Birgin, Martinez and Raydan 2000): Barzilai-Borwein steps,
      // safeguarded to [1 / L, 1] (the curvature lies in [1, L]), with a non-monotone acceptance
      // over the last kMemory objective values; a step that fails it is redone with 1 / L, which
      // always decreases the objective (sufficient decrease of projected gradient).
      constexpr int kMemory = 8;
      double recent[kMemory];
      for (double& v : recent) v = phi;
      double alpha = 1.0 / lipschitz, next_try = 1e-3;
      while (!done && out.iterations < max_iterations) {
        ++out.iterations;
        previous_rank = rank;
        if (!project<MaxN>(symmetric_part(Matrix(W - alpha * g)), Wnext, &P, &rank)) return false;
        double phi_next = objective(Wnext);
        const double reference = *std::max_element(recent, recent + kMemory);
        if (phi_next > reference - 1e-4 * g.cwiseProduct(W - Wnext).sum() && alpha > 1.0 / lipschitz) {
          alpha = 1.0 / lipschitz;
          if (!project<MaxN>(symmetric_part(Matrix(W - alpha * g)), Wnext, &P, &rank)) return false;
          phi_next = objective(Wnext);
        }
        gnext = cw.cwiseProduct(Wnext) - Gw;
        const Matrix step = Wnext - W;
        const double sy = step.cwiseProduct(gnext - g).sum(), ss = step.squaredNorm();
        alpha = sy > 0.0 ? std::clamp(ss / sy, 1.0 / lipschitz, 1.0) : 1.0;
        const double moved = std::sqrt(ss) / std::max(Wnext.norm(), std::numeric_limits<double>::min());
        W = Wnext;
        g = gnext;
        phi = phi_next;
        recent[out.iterations % kMemory] = phi;
        // Once the rank has settled and the iterates move little, the face W identifies, solved
        // exactly: the minimizer as soon as the face is right to the tolerance. Each try costs
        // three eigendecompositions, an iteration one: the next try waits until the iterates move
        // 100 times less.
        if (rank != previous_rank || moved > next_try) continue;
        next_try = moved * 1e-2;
        if (face_solve(p, range_basis<MaxN>(d, P), candidate) && consider(candidate)) done = true;
      }
      if (!done) consider(d.cwiseInverse().asDiagonal() * W * d.cwiseInverse().asDiagonal());
    }
  }
  if (best.size() == 0) {
    // No iterate had a finite KKT residual: the projection of Procrustes, feasible.
    if (!project<MaxN>(Yt, best)) return false;
  }

  out.kkt_residual = best_kkt;
  out.converged = best_kkt <= kPsdLsTolerance;
  out.X_s = data.V_a * best * data.V_a.transpose();
  out.X_s = symmetric_part(out.X_s);
  out.X_s.diagonal().array() += epsilon_s;

  // The certificate, from the returned X_s itself.
  Matrix Y = out.X_s;
  Y.diagonal().array() -= epsilon_s;
  Matrix S = data.R11.transpose() * (data.R11 * out.X_s - data.R12);
  S = symmetric_part(S);
  Vector wy, ws;
  if (!symmetric_eigen(Y, wy) || !symmetric_eigen(S, ws)) return false;
  out.primal_min_eig = n > 0 ? wy(0) : 0.0;
  out.dual_min_eig = n > 0 ? ws(0) : 0.0;
  out.complementarity = Y.cwiseProduct(S).sum();
  const double denominator = p.h_max * out.X_s.norm() + p.scale;
  out.duality_gap = denominator > 0.0 ? std::abs(out.complementarity) / denominator : 0.0;
  return true;
}

#define SPDFIT_INSTANTIATE(MaxN) \
  template bool psd_ls_kernel<MaxN>(const BasicReduction<MaxN>&, double, int, PsdLsKernel<MaxN>&);
SPDFIT_FOR_EACH_MAX_N(SPDFIT_INSTANTIATE)
#undef SPDFIT_INSTANTIATE

}  // namespace spdfit::detail
