#include "repair/correlation_newton.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <utility>

#include "numerics/linalg.hpp"

namespace spdfit::detail {

using Eigen::Index;
using Eigen::MatrixXd;
using Eigen::MatrixXf;
using Eigen::VectorXd;
using Eigen::VectorXf;

namespace {

constexpr double kEps = std::numeric_limits<double>::epsilon();
constexpr double kEpsSingle = std::numeric_limits<float>::epsilon();

// Mixed precision: from this many rows on, a step decomposes its trial point in single precision
// (ssyevd: half of dsyevd's time), and its next step's Jacobian products run in sgemm, when the
// gradient at the trial is expected to stay far above single precision's rounding level of it,
// L = sqrt(n) eps_single ||G + diag y||_2 (as for double below): the gradient now above
// kSingleMargin L, and the one predicted for the trial from the rate so far (g_k^2 / g_k-1) above
// kSinglePredicted L. The next direction then carries a relative error of about L / g, no larger
// than the conjugate gradients' own forcing term (1e-2) at those gradients. Where a
// single-precision trial's gradient still lands below kSingleRedo L (its direction would be
// mostly rounding), that point is decomposed again in double. The stopping test, the last steps
// and the answer are always in double precision.
constexpr Index kSingleMinRows = 1000;
constexpr double kSingleMargin = 1e3;
constexpr double kSinglePredicted = 1e2;
constexpr double kSingleRedo = 10.0;

// The margin of the stopping test over the rounding level of the dual gradient (see the loop).
constexpr double kGradientRounding = 2.0;

// How many of the ascending eigenvalues are positive (they come last).
Index positive_count(const VectorXd& lambda) {
  const Index n = lambda.size();
  Index r = 0;
  while (r < n && lambda(n - 1 - r) > 0.0) ++r;
  return r;
}

// The dual at y from the eigendecomposition G + diag(y) = P diag(lambda) P^T (Qi & Sun 2006):
// theta(y) = ||(G + diag y)_+||_F^2 / 2 - b^T y, and with P its gradient
// F(y) = diag(P diag(lambda_+) P^T) - b, summed column by column (no n x n temporary).
double theta_at(const VectorXd& lambda, const VectorXd& b, const VectorXd& y) {
  return 0.5 * lambda.cwiseMax(0.0).squaredNorm() - b.dot(y);
}

// P in double or single precision (the sum in double).
template <typename Matrix>
VectorXd gradient_at(const Matrix& P, const VectorXd& lambda, const VectorXd& b) {
  VectorXd F = -b;
  const Index n = lambda.size();
  for (Index j = n - positive_count(lambda); j < n; ++j)
    F += lambda(j) * P.col(j).cwiseAbs2().template cast<double>();
  return F;
}

// The generalized Jacobian of F at the eigendecomposition P diag(lambda) P^T (Qi & Sun 2006,
// eq. (20)): V h = diag(P (Omega o (P^T diag(h) P)) P^T), with Omega_ij = 1 when lambda_i,
// lambda_j > 0, lambda_i / (lambda_i - lambda_j) when lambda_i > 0 >= lambda_j, 0 when both <= 0.
//
// With the r positive eigenvalues last (P = [P2 P1], P1 their eigenvectors) and K = P1^T diag(h) P
// = [K2 K1] (r x n), V h = rowsum(P1 o (P [2 Omega12 o K2, K1]^T)): two products of an n x n by an
// n x r matrix (BLAS, multithreaded, for large n), O(n^2 r), into buffers kept between products.
// (Qi & Sun's complement form, O(n^2 (n - r)) for r > n/2, computes h - (...) and loses the
// semidefiniteness of V to cancellation; the conjugate gradients then stall, so it is not used.)
//
// In the precision of P (Scalar): single precision in the mixed-precision steps (kSingleMinRows),
// whose directions need no more, with sgemm's half of dgemm's time; h and V h in double, the
// diagonal computed in Scalar and kept in double.
template <typename Scalar>
class Jacobian {
 public:
  using Matrix = Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic>;
  using Vector = Eigen::Matrix<Scalar, Eigen::Dynamic, 1>;

  // Refers to P (no copy): P must outlive the products.
  Jacobian(const Matrix& P, const VectorXd& lambda) : P_(P), r_(positive_count(lambda)) {
    const Index n = lambda.size(), r = r_, a = n - r;
    omega_.resize(r, a);  // 2 Omega12: the off-diagonal blocks count twice
    for (Index j = 0; j < a; ++j)
      for (Index i = 0; i < r; ++i) {
        const double li = lambda(a + i), lj = lambda(j);
        omega_(i, j) = static_cast<Scalar>(2.0 * li / (li - lj));
      }
    // The diagonal of V (Borsdorf & Higham's preconditioner): V_kk = sum_ij P_ki^2 Omega_ij P_kj^2,
    // a sum of non-negative terms (no cancellation): s1 o s1 + rowsum(Q1 o (Q2 (2 Omega12)^T)),
    // Q = P o P.
    const auto P1 = P.rightCols(r);
    const Vector s1 = P1.cwiseAbs2().rowwise().sum();
    diagonal_ = s1.cwiseAbs2().template cast<double>();
    if (r > 0 && a > 0) {
      const Matrix Q2 = P.leftCols(a).cwiseAbs2();
      Matrix Q2_omega;
      multiply(Q2, false, omega_, true, Q2_omega);
      diagonal_ += P1.cwiseAbs2().cwiseProduct(Q2_omega).rowwise().sum().template cast<double>();
    }
  }

  void apply(const VectorXd& h, VectorXd& out) {
    const Index n = P_.rows(), r = r_, a = n - r;
    out.setZero(n);
    if (r == 0) return;
    const auto P1 = P_.rightCols(r);
    hP1_ = h.cast<Scalar>().asDiagonal() * P1;
    multiply(hP1_, true, P_, false, K_);  // r x n
    K_.leftCols(a) = omega_.cwiseProduct(K_.leftCols(a));
    multiply(P_, false, K_, true, Y_);  // n x r
    out = P1.cwiseProduct(Y_).rowwise().sum().template cast<double>();
  }

  const VectorXd& diagonal() const { return diagonal_; }

 private:
  const Matrix& P_;
  Index r_;
  Matrix omega_;
  VectorXd diagonal_;
  Matrix hP1_, K_, Y_;  // buffers of apply
};

// Preconditioned conjugate gradients for (V + mu I) d = rhs, to a relative residual `tol`.
template <typename Jacobian>
VectorXd pcg(Jacobian& V, double mu, const VectorXd& rhs, double tol, int max_iterations) {
  const Index n = rhs.size();
  VectorXd d = VectorXd::Zero(n);
  VectorXd r = rhs;
  const VectorXd precondition = (V.diagonal().array() + mu).max(1e-12).inverse().matrix();
  VectorXd z = precondition.cwiseProduct(r);
  VectorXd p = z, w;
  double rz = r.dot(z);
  const double stop = tol * rhs.norm();
  for (int k = 0; k < max_iterations && r.norm() > stop; ++k) {
    V.apply(p, w);
    w += mu * p;
    const double pw = p.dot(w);
    if (!(pw > 0.0)) break;
    const double step = rz / pw;
    d += step * p;
    r -= step * w;
    z = precondition.cwiseProduct(r);
    const double rz_next = r.dot(z);
    p = z + (rz_next / rz) * p;
    rz = rz_next;
  }
  return d;
}

// P := G + diag(y), then its eigendecomposition in place (P the eigenvectors with `vectors`).
// With `single`, rounded to single precision (the lower triangle) and decomposed in Pf instead
// (its eigenvectors stay there; P is left as it was), lambda widened to double.
void decompose(const MatrixXd& G, const VectorXd& y, MatrixXd& P, MatrixXf& Pf, VectorXd& lambda,
               bool vectors, bool single) {
  if (single) {
    const Index n = G.rows();
    Pf.resize(n, n);
    for (Index j = 0; j < n; ++j) {
      Pf(j, j) = static_cast<float>(G(j, j) + y(j));
      Pf.col(j).tail(n - 1 - j) = G.col(j).tail(n - 1 - j).cast<float>();
    }
    VectorXf w;
    if (!symmetric_eigen_in_place(Pf, w, vectors))
      throw std::runtime_error("the eigensolver did not converge");
    lambda = w.cast<double>();
    return;
  }
  P = G;  // into P's own storage (the same size): no allocation
  P.diagonal() += y;
  if (!symmetric_eigen_in_place(P, lambda, vectors))
    throw std::runtime_error("the eigensolver did not converge");
}

}  // namespace

CorrelationNewtonResult correlation_newton(MatrixXd G, const VectorXd& b, int max_iterations,
                                           double tolerance, MatrixXd* eigenvectors, VectorXd* eigenvalues) {
  const Index n = G.rows();
  CorrelationNewtonResult out;
  VectorXd y = b - G.diagonal();
  MatrixXd P;
  // The eigenvectors of the single-precision steps (see kSingleMinRows), freed when the
  // double-precision steps begin; `single` says which of P and Pf holds the current ones.
  MatrixXf Pf;
  bool single = false;
  VectorXd lambda;
  if (eigenvectors && eigenvalues && eigenvectors->rows() == n) {
    P = std::move(*eigenvectors);
    lambda = std::move(*eigenvalues);
  } else {
    P.resize(n, n);
    decompose(G, y, P, Pf, lambda, true, false);
  }
  double theta = theta_at(lambda, b, y);
  VectorXd F = gradient_at(P, lambda, b);
  // F is computed from an eigendecomposition of M = G + diag(y), exact for M + E with ||E||_2 about
  // eps ||M||_2; the projection is non-expansive, so F carries an error up to about
  // sqrt(n) eps ||M||_2, which no iteration removes. Where that exceeds the requested tolerance
  // (a C whose entries are far larger than the diagonal it is given), the stop is at that
  // rounding level, with kGradientRounding's margin over it.
  const double root_n = std::sqrt(static_cast<double>(n));
  auto norm_m = [&]() { return std::max(std::abs(lambda(0)), std::abs(lambda(n - 1))); };
  auto stop = [&]() { return std::max(tolerance, kGradientRounding * root_n * kEps * norm_m()); };
  constexpr double kArmijo = 1e-4;
  const double initial_rms = std::max(F.norm() / root_n, std::numeric_limits<double>::min());
  auto single_level = [&]() { return root_n * kEpsSingle * norm_m(); };
  double previous_gradient = 0.0;
  for (; out.iterations < max_iterations; ++out.iterations) {
    const double gradient = F.norm();
    if (!single && gradient <= stop()) break;
    const bool next_single = n >= kSingleMinRows && gradient > kSingleMargin * single_level() &&
                             (out.iterations == 0 ||
                              gradient * (gradient / previous_gradient) > kSinglePredicted * single_level());
    previous_gradient = gradient;
    VectorXd step;
    {
      // The Jacobian's buffers are freed before the next eigendecomposition.
      const double mu = std::min(1e-2, gradient) * 1e-6;
      // The conjugate gradients' relative tolerance (the inexact Newton method's forcing term)
      // follows the gradient relative to the initial gradient's root-mean-square entry, which
      // keeps the local rate quadratic whatever the units of G. (In the units of b it stays at
      // its cap while the gradient is large, as for a G whose entries dwarf the diagonal asked
      // for, and the steps are then poor; relative to the whole initial gradient it asks for
      // more conjugate-gradient iterations than the rate needs on well-scaled problems.)
      // No more than the stop needs, either: a residual of half the stopping level ends the
      // iteration after this step (Eisenstat and Walker's safeguard, in spirit).
      const double forcing = std::min(1e-2, std::max(gradient / initial_rms, 0.5 * stop() / gradient));
      if (single) {
        Jacobian<float> V(Pf, lambda);
        step = pcg(V, mu, -F, forcing, 200);
      } else {
        Jacobian<double> V(P, lambda);
        step = pcg(V, mu, -F, forcing, 200);
      }
    }
    // Single-precision eigenvectors are not needed past the direction: freed before a
    // double-precision trial (its workspace then takes their place at the peak).
    if (!next_single) Pf = MatrixXf();
    // Armijo backtracking on theta (convex, so the Newton step is a descent direction). The
    // current eigenvectors are not needed past the direction: each trial is decomposed in P's
    // storage (Pf's in single precision), the full step (usually taken) with eigenvectors, for the
    // next iteration; shorter ones with eigenvalues only, and the one taken again with eigenvectors.
    const double slope = F.dot(step);
    const double theta0 = theta;
    // Near the solution the decrease (about ||F||^2) falls below theta's own rounding: there the
    // comparison allows that rounding, or the full Newton step would be refused forever.
    // A single-precision theta (here or at the trial) is exact for eigenvalues each off by up to
    // about eps_single ||G + diag y||_2: theta's error is up to ||lambda_+||_1 times that.
    const double rounding =
        single || next_single
            ? 16.0 * kEpsSingle * (lambda.cwiseMax(0.0).sum() * norm_m() + std::abs(theta0) + 1.0)
            : 16.0 * kEps * (std::abs(theta0) + 1.0);
    double t = 1.0;
    VectorXd trial = y + step;
    for (int k = 0; k < 40; ++k) {
      decompose(G, trial, P, Pf, lambda, k == 0, next_single);
      theta = theta_at(lambda, b, trial);
      if (theta <= theta0 + kArmijo * t * slope + rounding) break;
      t *= 0.5;
      trial = y + t * step;
    }
    y = std::move(trial);
    if (t != 1.0) {
      decompose(G, y, P, Pf, lambda, true, next_single);
      theta = theta_at(lambda, b, y);
    }
    single = next_single;
    F = single ? gradient_at(Pf, lambda, b) : gradient_at(P, lambda, b);
    if (single && F.norm() < kSingleRedo * single_level()) {
      Pf = MatrixXf();
      single = false;
      decompose(G, y, P, Pf, lambda, true, false);
      theta = theta_at(lambda, b, y);
      F = gradient_at(P, lambda, b);
    }
  }
  if (single) {  // out of iterations after a single-precision step: the answer from a double one
    Pf = MatrixXf();
    decompose(G, y, P, Pf, lambda, true, false);
    F = gradient_at(P, lambda, b);
  }
  out.gradient_norm = F.norm();
  out.converged = out.gradient_norm <= stop();

  // X = (G + diag y)_+ = Q Q^T with Q = P1 diag(lambda_+)^1/2, formed in P's columns; its lower
  // triangle by BLAS dsyrk for large n, mirrored.
  G = MatrixXd();  // freed before X is allocated
  const Index r = positive_count(lambda);
  out.clipped = n - r;
  for (Index j = n - r; j < n; ++j) P.col(j) *= std::sqrt(lambda(j));
  lower_gram(P.rightCols(r), out.X);
  make_symmetric_from_lower(out.X);
  return out;
}

}  // namespace spdfit::detail
