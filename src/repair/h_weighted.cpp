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
constexpr double kPenaltyMax = 1e5;
constexpr double kArmijo = 1e-4;
constexpr int kCgMaxIterations = 300;

Index positive_count(const VectorXd& lambda) {
  const Index n = lambda.size();
  Index r = 0;
  while (r < n && lambda(n - 1 - r) > 0.0) ++r;
  return r;
}

// M := Z - s X and its eigendecomposition (ascending).
void decompose(const MatrixXd& Z, double s, const MatrixXd& X, MatrixXd& P, VectorXd& lambda) {
  P = Z - s * X;
  if (!symmetric_eigen_in_place(P, lambda, true)) throw std::runtime_error("the eigensolver did not converge");
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

// Linear maps D -> P (C o (P^T D P)) P^T whose coefficient matrix C is c11 on the block of
// M's positive eigenvectors, C12 between positive and non-positive ones and 0 among the
// non-positive ones: the projection's derivative J (c11 = 1, C12 = Omega12, Qi & Sun 2006) and the
// preconditioner's correction. With P1 the r positive eigenvectors, K1 = P1^T D, it is T + T^T
// for T = P1 (c11 K11 P1^T / 2 + (C12 o K1 P2) P2^T): two products of n x n by n x r matrices.
class Structured {
 public:
  Structured(const MatrixXd& P, Index r) : P_(P), r_(r) {}
  Index positive() const { return r_; }

  void apply(const MatrixXd& D, double c11, const MatrixXd& C12, MatrixXd& out) {
    const Index n = P_.rows(), r = r_, a = n - r;
    if (r == 0) {
      out.setZero(n, n);
      return;
    }
    const auto P1 = P_.rightCols(r);
    multiply(P1, true, D, false, K1_);  // r x n
    multiply(K1_, false, P1, false, K11_);
    multiply(K11_, false, P1, true, S_);  // K11 P1^T
    S_ *= 0.5 * c11;
    if (a > 0) {
      const auto P2 = P_.leftCols(a);
      multiply(K1_, false, P2, false, K12_);
      K12_ = C12.cwiseProduct(K12_);
      multiply(K12_, false, P2, true, R_);
      S_ += R_;
    }
    multiply(P1, false, S_, false, T_);
    out = T_ + T_.transpose();
  }

 private:
  const MatrixXd& P_;
  Index r_;
  MatrixXd K1_, K11_, S_, K12_, R_, T_;
};

}  // namespace

HWeightedResult h_weighted_alm(const MatrixXd& G, const MatrixXd& H, const FixedPattern& pattern, const MatrixXd& B,
                               int max_iterations, double tolerance) {
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
  MatrixXd X = G;
  for (Index p = 0; p < pattern.size(); ++p) {
    const Index i = pattern.row[p], j = pattern.col[p];
    X(i, j) = X(j, i) = B(i, j);
  }
  MatrixXd Z = MatrixXd::Zero(n, n);
  double s = kPenaltyStart;
  const double dual_scale = 1.0 + H2free.cwiseProduct(G).norm();
  auto objective = [&](const MatrixXd& Y) { return 0.5 * H2.cwiseProduct((Y - G).cwiseAbs2()).sum(); };

  MatrixXd P;
  VectorXd lambda;
  decompose(Z, s, X, P, lambda);
  MatrixXd Zp, grad, D, r, z, p, w, correction;
  double gn = 0.0;
  for (out.outer = 0;; ++out.outer) {
    // The subproblem's tolerance: loose at first, down to a tenth of the final dual tolerance.
    const double inner_tolerance =
        std::max(0.1 * tolerance * dual_scale, 0.1 * dual_scale * std::pow(1e-2, out.outer));
    for (;;) {
      Zp = positive_part(P, lambda);
      grad = (H2.cwiseProduct(X - G) - Zp).cwiseProduct(free);
      gn = grad.norm();
      if (gn <= inner_tolerance || out.iterations >= max_iterations) break;
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
        J.apply(V, 1.0, omega12, result);
        result = (H2.cwiseProduct(V) + s * result + mu * V).cwiseProduct(free);
      };
      // (h_mean + s J)^-1, exact in the eigenvectors: V / h + P ((1 / (h + s Omega) - 1 / h) o (P^T V P)) P^T.
      auto precondition = [&](const MatrixXd& V, MatrixXd& result) {
        J.apply(V, c11, c12, correction);
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
      double t = 1.0;
      MatrixXd trial;
      for (int k = 0; k < 40; ++k) {
        trial = X + t * D;
        decompose(Z, s, trial, P, lambda);
        const double phi_t = objective(trial) + 0.5 * lambda.cwiseMax(0.0).squaredNorm() / s;
        if (phi_t <= phi + kArmijo * t * slope + rounding) break;
        t *= 0.5;
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
    if (out.kkt_residual <= tolerance) {
      out.converged = true;
      break;
    }
    if (out.iterations >= max_iterations) break;
    s = std::min(s * kPenaltyGrowth, kPenaltyMax);
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
