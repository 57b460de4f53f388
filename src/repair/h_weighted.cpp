#include "repair/h_weighted.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <utility>

#include "numerics/linalg.hpp"

namespace spdfit::detail {

using Eigen::Index;
using Eigen::MatrixXd;
using Eigen::VectorXd;

namespace {

using Mask = Eigen::Matrix<bool, Eigen::Dynamic, Eigen::Dynamic>;

// The penalty's start and its growth: H is scaled to max 1 and the data to order one by the
// caller, so these are in those units. A penalty about ten times the largest weight makes the
// first subproblem's infeasibility small; growing it tenfold per multiplier update (to a cap that
// keeps the Newton systems' conditioning reasonable) gives the few updates measured in
// docs/performance.md.
constexpr double kPenaltyStart = 10.0;
constexpr double kPenaltyGrowth = 10.0;
constexpr double kPenaltyMax = 1e4;
// The margin of the subproblems' stopping test over their gradient's rounding level.
constexpr double kGradientRounding = 2.0;
constexpr double kArmijo = 1e-4;
constexpr int kCgMaxIterations = 300;
// Step lengths 1, 1/2, ... tried by the gradient's test before the subproblem counts as solved.
constexpr int kGradientHalvings = 4;

Index positive_count(const VectorXd& lambda) {
  const Index n = lambda.size();
  Index r = 0;
  while (r < n && lambda(n - 1 - r) > 0.0) ++r;
  return r;
}

// M := Z - s X and its eigendecomposition (ascending; eigenvalues only without `vectors`).
void decompose(const MatrixXd& Z, double s, const MatrixXd& X, MatrixXd& P, VectorXd& lambda, bool vectors = true) {
  P = Z - s * X;
  if (!symmetric_eigen_in_place(P, lambda, vectors)) throw std::runtime_error("the eigensolver did not converge");
}

// (M)_+ = P1 diag(lambda_+) P1^T.
MatrixXd positive_part(const MatrixXd& P, const VectorXd& lambda) {
  const Index n = lambda.size(), r = positive_count(lambda);
  MatrixXd Q = P.rightCols(r);
  for (Index k = 0; k < r; ++k) Q.col(k) *= std::sqrt(lambda(n - r + k));
  MatrixXd out;
  lower_gram(Q, out);
  make_symmetric_from_lower(out);
  return out;
}

// Linear maps D -> P (C o (P^T D P)) P^T whose coefficient matrix C is constant on the block of
// M's positive eigenvectors (c_pp), a matrix C_pn between positive and non-positive ones, and
// constant among the non-positive ones (c_nn): the projection's derivative J (1, Omega12, 0; Qi &
// Sun 2006) and the preconditioner's correction. Subtracting the constant of one block, c D, leaves
// a map supported on the blocks that touch the other side; it is computed from the smaller side's
// k eigenvectors Pq (the rest Pr): T + T^T with T = Pq (a Kqq Pq^T / 2 + (B o Kqr) Pr^T), Kq = Pq^T D,
// two products of n x n by n x k matrices, k = min(r, n - r).
class Structured {
 public:
  Structured(const MatrixXd& P, Index r) : P_(P), r_(r) {}
  Index positive() const { return r_; }

  void apply(const MatrixXd& D, double c_pp, const MatrixXd& C_pn, double c_nn, MatrixXd& out) {
    const Index n = P_.rows(), r = r_, a = n - r;
    if (r <= a) {
      block(D, P_.rightCols(r), P_.leftCols(a), c_pp - c_nn, (C_pn.array() - c_nn).matrix(), out);
      if (c_nn != 0.0) out += c_nn * D;
    } else {
      block(D, P_.leftCols(a), P_.rightCols(r), c_nn - c_pp, (C_pn.array() - c_pp).matrix().transpose(), out);
      if (c_pp != 0.0) out += c_pp * D;
    }
  }

 private:
  void block(const MatrixXd& D, const Eigen::Ref<const MatrixXd>& Pq, const Eigen::Ref<const MatrixXd>& Pr,
             double a, const MatrixXd& B, MatrixXd& out) {
    const Index n = P_.rows(), k = Pq.cols();
    if (k == 0) {
      out.setZero(n, n);
      return;
    }
    multiply(Pq, true, D, false, K1_);  // k x n
    multiply(K1_, false, Pq, false, K11_);
    multiply(K11_, false, Pq, true, S_);  // Kqq Pq^T
    S_ *= 0.5 * a;
    if (Pr.cols() > 0) {
      multiply(K1_, false, Pr, false, K12_);
      K12_ = B.cwiseProduct(K12_);
      multiply(K12_, false, Pr, true, R_);
      S_ += R_;
    }
    multiply(Pq, false, S_, false, T_);
    out = T_ + T_.transpose();
  }

  const MatrixXd& P_;
  Index r_;
  MatrixXd K1_, K11_, S_, K12_, R_, T_;
};

}  // namespace

HWeightedResult h_weighted_alm(const MatrixXd& G, const MatrixXd& H, const FixedPattern& pattern, const MatrixXd& B,
                               int max_iterations, double tolerance, const MatrixXd* X0, const MatrixXd* Z0) {
  const Index n = G.rows();
  HWeightedResult out;
  Mask fixed = Mask::Zero(n, n);
  for (Index p = 0; p < pattern.size(); ++p) fixed(pattern.row[p], pattern.col[p]) = fixed(pattern.col[p], pattern.row[p]) = true;
  const MatrixXd free = (!fixed.array()).cast<double>().matrix();
  const MatrixXd H2 = H.cwiseAbs2();
  const MatrixXd H2free = H2.cwiseProduct(free);
  // The preconditioner's scalar stand-in for H o H: its mean over the free entries.
  const double free_count = free.sum();
  const double h_mean = std::max(free_count > 0.0 ? H2free.sum() / free_count : 1.0, 1e-8);
  // X stays exactly symmetric (with H, G and B symmetric, every step is): the penalty's
  // eigendecomposition reads one triangle, so it does not see an antisymmetric part, which would
  // grow from step to step on the entries of weight 0 until the gradient no longer predicts the
  // function and the line search stalls at an infeasible X (a start D X0 D one rounding off
  // symmetric did that on a 6 x 6 problem).
  MatrixXd X = X0 ? MatrixXd(0.5 * (*X0 + X0->transpose())) : G;
  for (Index p = 0; p < pattern.size(); ++p) {
    const Index i = pattern.row[p], j = pattern.col[p];
    X(i, j) = X(j, i) = B(i, j);
  }
  MatrixXd Z = Z0 ? *Z0 : MatrixXd::Zero(n, n);
  double s = kPenaltyStart;
  const double dual_scale = 1.0 + H2free.cwiseProduct(G).norm();
  auto objective = [&](const MatrixXd& Y) { return 0.5 * H2.cwiseProduct((Y - G).cwiseAbs2()).sum(); };

  MatrixXd P;
  VectorXd lambda;
  decompose(Z, s, X, P, lambda);
  MatrixXd Zp, grad, Zp_trial, grad_trial, D, r, z, p, w, correction;
  // The subproblem's gradient at Y, whose M = Z - s Y is decomposed in (P, lambda); Zp gets (M)_+.
  const auto gradient_at = [&](const MatrixXd& Y, MatrixXd& Zp_out, MatrixXd& grad_out) {
    Zp_out = positive_part(P, lambda);
    grad_out = (H2.cwiseProduct(Y - G) - Zp_out).cwiseProduct(free);
  };
  double gn = 0.0, rounding = 0.0, previous_primal = std::numeric_limits<double>::infinity();
  const double root_n = std::sqrt(static_cast<double>(n));
  for (out.outer = 0;; ++out.outer) {
    // The subproblem's tolerance: loose at first, down to a tenth of the final dual tolerance.
    const double inner_tolerance =
        std::max(0.1 * tolerance * dual_scale, 0.1 * dual_scale * std::pow(1e-2, out.outer));
    bool fresh = false;  // Zp and grad are those of X already (the line search computed them)
    for (;;) {
      if (!fresh) gradient_at(X, Zp, grad);
      fresh = false;
      gn = grad.norm();
      // The gradient's own rounding: Zp comes from an eigendecomposition of M = Z - s X, exact for a
      // matrix within about eps ||M||_2 of it (as in correlation_newton).
      rounding = kGradientRounding * root_n * std::numeric_limits<double>::epsilon() *
                 std::max(std::abs(lambda(0)), std::abs(lambda(n - 1)));
      if (gn <= std::max(inner_tolerance, rounding) || out.iterations >= max_iterations) break;
      const double phi = objective(X) + 0.5 * lambda.cwiseMax(0.0).squaredNorm() / s;
      Structured J(P, positive_count(lambda));
      const Index rr = J.positive(), a = n - rr;
      MatrixXd omega12(rr, a), c12(rr, a);
      for (Index i = 0; i < rr; ++i) {
        const double li = lambda(a + i);
        for (Index j = 0; j < a; ++j) {
          omega12(i, j) = li / (li - lambda(j));
          c12(i, j) = 1.0 / (h_mean + s * omega12(i, j)) - 1.0 / h_mean;
        }
      }
      const double c11 = 1.0 / (h_mean + s) - 1.0 / h_mean;
      const double mu = 1e-10 * s;
      auto hessian = [&](const MatrixXd& V, MatrixXd& result) {
        J.apply(V, 1.0, omega12, 0.0, result);
        result = (H2.cwiseProduct(V) + s * result + mu * V).cwiseProduct(free);
      };
      // (h_mean + s J)^-1, exact in the eigenvectors: V / h + P ((1 / (h + s Omega) - 1 / h) o (P^T V P)) P^T.
      auto precondition = [&](const MatrixXd& V, MatrixXd& result) {
        J.apply(V, c11, c12, 0.0, correction);
        result = (V / h_mean + correction).cwiseProduct(free);
      };
      D.setZero(n, n);
      r = -grad;
      precondition(r, z);
      p = z;
      double rz = r.cwiseProduct(z).sum();
      const double cg_stop = std::min(1e-2, gn / dual_scale) * gn;
      for (int k = 0; k < kCgMaxIterations && r.norm() > cg_stop; ++k) {
        hessian(p, w);
        const double pw = p.cwiseProduct(w).sum();
        if (!(pw > 0.0)) break;
        const double step = rz / pw;
        D += step * p;
        r -= step * w;
        precondition(r, z);
        const double rz_next = r.cwiseProduct(z).sum();
        p = z + (rz_next / rz) * p;
        rz = rz_next;
      }
      const double slope = grad.cwiseProduct(D).sum();
      const double rounding = 16.0 * std::numeric_limits<double>::epsilon() * (std::abs(phi) + 1.0);
      // Armijo backtracking; the full step (usually taken) is decomposed with eigenvectors for the
      // next step, shorter ones with eigenvalues only (the value needs no more), and the one taken
      // again with eigenvectors. Where the predicted decrease is below the value's rounding (near a
      // subproblem's solution), Armijo's test compares rounding errors and backtracks at random
      // (measured: steps of 6e-5 to 2e-4 for a dozen Newton steps at a standstill, n = 1000); the
      // gradient's norm, whose rounding is far smaller, decides there instead.
      double t = 1.0;
      MatrixXd trial;
      if (-slope <= rounding) {
        bool taken = false;
        for (int k = 0; k < kGradientHalvings && !taken; ++k, t *= 0.5) {
          trial = X + t * D;
          decompose(Z, s, trial, P, lambda);
          gradient_at(trial, Zp_trial, grad_trial);
          taken = grad_trial.norm() < gn;
        }
        if (!taken) {
          // No step reduces the gradient: the subproblem is solved to its rounding.
          decompose(Z, s, X, P, lambda);
          ++out.iterations;
          break;
        }
        std::swap(Zp, Zp_trial);
        std::swap(grad, grad_trial);
        fresh = true;
      } else {
        for (int k = 0; k < 40; ++k) {
          trial = X + t * D;
          decompose(Z, s, trial, P, lambda, k == 0);
          const double phi_t = objective(trial) + 0.5 * lambda.cwiseMax(0.0).squaredNorm() / s;
          if (phi_t <= phi + kArmijo * t * slope + rounding) break;
          t *= 0.5;
        }
        if (t != 1.0) decompose(Z, s, trial, P, lambda);
      }
      X = std::move(trial);
      ++out.iterations;
    }
    // The multiplier update. X's distance to the semidefinite matrices is at most ||Z - Zp|| / s:
    // X - (Z - Zp) / s = -(Z - s X)_- / s is semidefinite.
    const double primal = (Z - Zp).norm() / s / (1.0 + X.norm());
    const double dual = gn / dual_scale;
    out.kkt_residual = std::max(primal, dual);
    Z = Zp;
    if (primal <= tolerance && dual <= std::max(tolerance, rounding / dual_scale)) {
      out.converged = true;
      break;
    }
    if (out.iterations >= max_iterations) break;
    // The multipliers converge linearly at a rate that improves with the penalty; a larger penalty
    // also makes the next subproblem's Newton steps shorter-sighted (more backtracking). So the
    // penalty grows only when the infeasibility did not fall tenfold.
    if (primal > tolerance && primal > 0.1 * previous_primal) s = std::min(s * kPenaltyGrowth, kPenaltyMax);
    previous_primal = primal;
    decompose(Z, s, X, P, lambda);
  }

  // The semidefinite iterate -(M)_- / s for the last M = Z_old - s X (P, lambda), its fixed entries
  // then set exactly.
  {
    const Index rr = positive_count(lambda), a = n - rr;
    out.clipped = rr;
    MatrixXd Q = P.leftCols(a);
    for (Index k = 0; k < a; ++k) Q.col(k) *= std::sqrt(std::max(-lambda(k), 0.0) / s);
    lower_gram(Q, out.X);
    make_symmetric_from_lower(out.X);
  }
  double residual = 0.0;
  for (Index p = 0; p < pattern.size(); ++p) {
    const Index i = pattern.row[p], j = pattern.col[p];
    residual += (i == j ? 1.0 : 2.0) * std::pow(out.X(i, j) - B(i, j), 2);
    out.X(i, j) = out.X(j, i) = B(i, j);
  }
  out.residual = std::sqrt(residual);

  // The dual function g(Z) = inf over X with the fixed entries of ||H o (X - G)||^2 / 2 - <Z, X>,
  // a lower bound on the optimum for every Z >= 0; finite only when Z vanishes on the free entries
  // of weight 0. Those entries of Z are zeroed and Z shifted by t I back to semidefinite, which
  // needs every diagonal entry fixed or weighted.
  MatrixXd Zd = Z;
  bool zeroed = false;
  for (Index j = 0; j < n; ++j) {
    for (Index i = 0; i < n; ++i) {
      if (!fixed(i, j) && H2(i, j) == 0.0 && Zd(i, j) != 0.0) {
        Zd(i, j) = 0.0;
        zeroed = true;
      }
    }
  }
  out.dual_value = std::numeric_limits<double>::quiet_NaN();
  bool feasible = true;
  if (zeroed) {
    MatrixXd copy = Zd;
    VectorXd mu;
    if (!symmetric_eigen_in_place(copy, mu, false)) throw std::runtime_error("the eigensolver did not converge");
    const double t = std::max(0.0, -mu(0));
    if (t > 0.0) {
      for (Index i = 0; i < n; ++i) feasible = feasible && (fixed(i, i) || H2(i, i) > 0.0);
      Zd.diagonal().array() += t;
    }
  }
  if (feasible) {
    double g = 0.0;
    for (Index j = 0; j < n; ++j) {
      for (Index i = 0; i < n; ++i) {
        const double z = Zd(i, j);
        if (fixed(i, j)) {
          g += 0.5 * H2(i, j) * std::pow(B(i, j) - G(i, j), 2) - z * B(i, j);
        } else if (H2(i, j) > 0.0) {
          g += -z * G(i, j) - 0.5 * z * z / H2(i, j);
        }
      }
    }
    out.dual_value = g;
  }
  return out;
}

}  // namespace spdfit::detail
